// Particle–particle contacts over the Verlet pair list (CSR half list, neighbor_list.hpp): the pair
// kernel, the pass in its two forms (sums added directly, or stored per pair and gathered), and the
// gather. Newton's third law (seed Eq. 1) is applied per pair, so each pair's law runs once.
#include <algorithm>
#include <cstdint>
#include <utility>

#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"

namespace spread::dem {

using detail::kMinParallelItems;

namespace {
using lanes::Lanes2;
using lanes::pack;
using lanes::V3;

// One touching pair's contact (T = double), or two pairs' side by side (T = Lanes2) with the same
// material pair: normal and overlap from the pair vector d (from j to i), the levers (Eq. 10), the
// contact points' relative velocity (Eq. 8), the law, and the moments on both (Eq. 15).
template <class T>
struct PairOut {
  V3<T> f, t_i, t_j;  // force on i (j gets −f); torques on i and j
  T normal_force_n;
};
template <class Law, bool kRotation, class T>
SPREAD_CONTACT_INLINE PairOut<T> pair_contact(const V3<T>& d, T dist2, T ri, T rj, const V3<T>& v_rel, const V3<T>& wi,
                                              const V3<T>& wj, const PairParams& pp, const typename Law::Coeffs& pc, double dt,
                                              LawHistory<T>& h) {
  // 1/|d|² does not wait for the sqrt (the two overlap); the normal is d |d| / |d|².
  const T inv_dist2 = lanes::splat<T>(1.0) / dist2;
  const T dist = lanes::sqrt(dist2);
  const V3<T> n = d * (dist * inv_dist2);
  const T overlap = (ri + rj) - dist;
  const T li = Law::lever(ri, pp.share_a, overlap), lj = Law::lever(rj, pp.share_b, overlap);
  // Arms −l_i n and +l_j n both lie along n, so the relative velocity of the contact points,
  // v_i + ω_i × (−l_i n) − v_j − ω_j × (l_j n), takes one cross product, and both torques share n × F_t.
  V3<T> slip = v_rel;
  if constexpr (kRotation) slip = slip - cross(li * wi + lj * wj, n);
  const LawForce<T> law = Law::kernel(pc, pp.friction, ContactNormal<T>{n, d, inv_dist2}, overlap, slip, dt, h);
  PairOut<T> out{law.force_n, lanes::zero3<T>(), lanes::zero3<T>(), law.normal_force_n};
  if constexpr (kRotation) {
    const V3<T> n_cross_ft = cross(n, law.tangential_n);
    out.t_i = (-li) * n_cross_ft;  // (−l_i n) × F_t
    out.t_j = (-lj) * n_cross_ft;  // (l_j n) × (−F_t)
  }
  return out;
}
}  // namespace

template <class Law, bool kRotation>
void DemEngine::particle_forces() {
  const std::size_t n = p_.size();
  if (pair_sum_.size() != n) pair_sum_.assign(n, PairSum{});
  // Per-pair results are stored (and gathered in a second pass) when threads share the pairs or an
  // energy monitor reads them; one thread adds them straight into the sums. Same sums, same order.
  const bool threaded = params_.threads > 1 && static_cast<long long>(pairs_.size()) >= kMinParallelItems;
  const bool periodic = params_.periodic_z.enabled;
  if (threaded || monitor_ != nullptr) {
    if (periodic) pair_forces<Law, kRotation, true, true>();
    else pair_forces<Law, kRotation, true, false>();
    gather_stored_pair_forces<kRotation>();
  } else {
    if (periodic) pair_forces<Law, kRotation, false, true>();
    else pair_forces<Law, kRotation, false, false>();
  }
}

// flatten: the whole pair kernel (geometry, law, lane operations) inlined into the loop; at -O2 GCC
// otherwise keeps the law as a call per touching pair, which costs about a third of the pass.
template <class Law, bool kRotation, bool kStorePairs, bool kPeriodic>
SPREAD_CONTACT_FLATTEN void DemEngine::pair_forces() {
  using Coeffs = typename Law::Coeffs;
  // Flat arrays once, outside the loop (the vectors' bounds and sizes do not change within the pass).
  const double* const px = p_.x.data();
  const double* const py = p_.y.data();
  const double* const pz = p_.z.data();
  const double* const pvx = p_.vx.data();
  const double* const pvy = p_.vy.data();
  const double* const pvz = p_.vz.data();
  const double* const pwx = kRotation ? p_.wx.data() : nullptr;
  const double* const pwy = kRotation ? p_.wy.data() : nullptr;
  const double* const pwz = kRotation ? p_.wz.data() : nullptr;
  const double* const radius = p_.radius_m.data();
  const double* const mass = p_.mass_kg.data();
  const double* const inertia = p_.inertia_kg_m2.data();
  const std::uint16_t* const material = p_.material.data();
  const std::uint8_t* const active = p_.active.data();
  const std::uint32_t* const pair_start = pairs_.first_start.data();
  const std::uint32_t* const partner = pairs_.second.data();
  double* const history = pairs_.history.data();
  std::uint8_t* const held = pairs_.held.data();
  double* const out_force = pairs_.force.data();
  double* const out_torque_i = pairs_.torque_first.data();
  double* const out_torque_j = pairs_.torque_second.data();
  PairSum* const sums = pair_sum_.data();
  const PairParams* const params_row0 = &pair_table_(0, 0);
  const std::size_t material_count = pair_table_.material_count();
  const Coeffs* const coeffs_row0 = coeffs_table<Law>(pair_coeffs_);
  const double period = params_.periodic_z.length_m();
  const double dt = dt_s_;
  const long long nn = static_cast<long long>(p_.size());
  const bool parallel = kStorePairs && params_.threads > 1 && nn >= kMinParallelItems;

  // firstprivate: each thread (also the only one) gets the pointers as locals. Shared, they are read
  // through the outlined region's argument block, and since a byte store (held) may alias anything,
  // GCC reloaded every array's pointer for every listed pair.
#pragma omp parallel for schedule(static) num_threads(params_.threads) if (parallel)                                  \
    firstprivate(px, py, pz, pvx, pvy, pvz, pwx, pwy, pwz, radius, mass, inertia, material, active, pair_start, partner, \
                     history, held, out_force, out_torque_i, out_torque_j, sums, params_row0, material_count,         \
                     coeffs_row0, period, dt)
  for (long long ii = 0; ii < nn; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    const std::uint32_t k_begin = pair_start[i], k_end = pair_start[i + 1];
    const bool i_active = active[i] != 0;
    const double xi = px[i], yi = py[i], zi = pz[i];
    const V3<double> vi{pvx[i], pvy[i], pvz[i]};
    V3<double> wi{0.0, 0.0, 0.0};
    if constexpr (kRotation) wi = V3<double>{pwx[i], pwy[i], pwz[i]};
    const double ri = radius[i], mi = mass[i];
    const PairParams* const params_row = params_row0 + static_cast<std::size_t>(material[i]) * material_count;
    const Coeffs* const coeffs_row = coeffs_row0 + static_cast<std::size_t>(material[i]) * material_count;
    // This particle's share of its own pairs (it is `first` in all of them), summed from zero in pair order.
    double sum_f[3] = {0.0, 0.0, 0.0}, sum_t[3] = {0.0, 0.0, 0.0};
    // Pair vector from j to i (minimum image along a periodic axis).
    auto separation = [&](std::size_t j) {
      double dz = zi - pz[j];
      if constexpr (kPeriodic) dz = minimum_image_z(dz, period);
      return V3<double>{xi - px[j], yi - py[j], dz};
    };
    // A finished pair: i's share into the running sums, j's share (Newton's third law, Eq. 1) into j's
    // sums — finished when the loop reaches j > i — or, when stored, into the pair's output slots.
    auto add = [&](std::uint32_t k, std::size_t j, const V3<double>& f, const V3<double>& t_i, const V3<double>& t_j) {
      held[k] = 1;
      sum_f[0] += f.x; sum_f[1] += f.y; sum_f[2] += f.z;
      if constexpr (kRotation) { sum_t[0] += t_i.x; sum_t[1] += t_i.y; sum_t[2] += t_i.z; }
      if constexpr (kStorePairs) {
        out_force[k * 3] = f.x; out_force[k * 3 + 1] = f.y; out_force[k * 3 + 2] = f.z;
        if constexpr (kRotation) {
          out_torque_i[k * 3] = t_i.x; out_torque_i[k * 3 + 1] = t_i.y; out_torque_i[k * 3 + 2] = t_i.z;
          out_torque_j[k * 3] = t_j.x; out_torque_j[k * 3 + 1] = t_j.y; out_torque_j[k * 3 + 2] = t_j.z;
        }
      } else {
        PairSum& sj = sums[j];
        sj.f[0] -= f.x; sj.f[1] -= f.y; sj.f[2] -= f.z;
        if constexpr (kRotation) { sj.t[0] += t_j.x; sj.t[1] += t_j.y; sj.t[2] += t_j.z; }
      }
    };
    // One touching pair alone (T = double): any materials and sizes, rolling resistance.
    auto one_pair = [&](std::uint32_t k, double dist2) {
      const std::size_t j = partner[k];
      double* const hist = history + static_cast<std::size_t>(k) * kHistoryDoubles;
      const PairParams& pp = params_row[material[j]];
      // R* = r_i r_j / (r_i + r_j), M* = m_i m_j / (m_i + m_j) and what the law derives from them: from the
      // material-pair table when both materials have one size, else per contact.
      const Coeffs& tab = coeffs_row[material[j]];
      const double rj = radius[j];
      const Coeffs pc = tab.uniform ? tab : Law::coeffs(pp, ri * rj / (ri + rj), mi * mass[j] / (mi + mass[j]));
      V3<double> wj{0.0, 0.0, 0.0};
      if constexpr (kRotation) wj = V3<double>{pwx[j], pwy[j], pwz[j]};
      LawHistory<double> h{{hist[0], hist[1], hist[2]}, hist[3]};
      PairOut<double> r = pair_contact<Law, kRotation>(separation(j), dist2, ri, rj, vi - V3<double>{pvx[j], pvy[j], pvz[j]},
                                                         wi, wj, pp, pc, dt, h);
      hist[0] = h.elastic.x; hist[1] = h.elastic.y; hist[2] = h.elastic.z; hist[3] = h.overlap_m;
      if constexpr (Law::kRolling) {
        const double ii_ = inertia[i], ij_ = inertia[j];
        const Vec3 tr = Law::RollingModel::torque(pp.rolling_friction, r.normal_force_n, pc.r_eff_m, Vec3(wi.x - wj.x, wi.y - wj.y, wi.z - wj.z),
                                       ii_ * ij_ / (ii_ + ij_), dt);
        r.t_i = r.t_i + V3<double>{tr.x(), tr.y(), tr.z()};
        r.t_j = r.t_j - V3<double>{tr.x(), tr.y(), tr.z()};
      }
      add(k, j, r.f, r.t_i, r.t_j);
    };
    // Two stages per chunk of i's pairs. (1) Without a branch on "touching" — about a third of the listed
    // pairs touch, scattered, so that branch was mispredicted often — the touching pairs' indices are
    // appended to a small buffer and a pair that has just come apart releases its tangential spring.
    // (2) The contact law over the buffer only, in pair order (so the sums are those of one loop), two
    // pairs at a time in lanes (lanes.hpp) when they share their materials' table entry.
    constexpr std::uint32_t kChunk = 64;
    for (std::uint32_t chunk = k_begin; chunk < k_end; chunk += kChunk) {
      const std::uint32_t chunk_end = std::min(k_end, chunk + kChunk);
      std::uint32_t touching_pairs[kChunk];
      double touching_dist2[kChunk];
      std::uint32_t touching = 0;
      for (std::uint32_t k = chunk; k < chunk_end; ++k) {
        const std::size_t j = partner[k];
        const V3<double> d = separation(j);
        const double dist2 = squared_norm(d);
        const double cut = ri + radius[j];
        const bool touches = (dist2 < cut * cut) & i_active & (active[j] != 0) & (dist2 != 0.0);
        touching_pairs[touching] = k;
        touching_dist2[touching] = dist2;
        touching += touches ? 1u : 0u;
        // Contact lost: the tangential spring is released. The history is touched only if it holds
        // anything (held byte): the apart pairs cost a byte read, not 32 bytes. Rarely true, so predictable.
        if (held[k] & static_cast<std::uint8_t>(!touches)) {
          double* const hist = history + static_cast<std::size_t>(k) * kHistoryDoubles;
          hist[0] = hist[1] = hist[2] = hist[3] = 0.0;
          held[k] = 0;
        }
        if constexpr (kStorePairs) {
          for (int c = 0; c < 3; ++c) out_force[k * 3 + c] = 0.0;
          if constexpr (kRotation)
            for (int c = 0; c < 3; ++c) out_torque_i[k * 3 + c] = out_torque_j[k * 3 + c] = 0.0;
        }
      }
      std::uint32_t q = 0;
      if constexpr (!Law::kRolling) {
        for (; q + 2 <= touching; q += 2) {
          const std::uint32_t k0 = touching_pairs[q], k1 = touching_pairs[q + 1];
          const std::size_t j0 = partner[k0], j1 = partner[k1];
          const Coeffs& tab = coeffs_row[material[j0]];
          if (material[j1] != material[j0] || !tab.uniform) {
            one_pair(k0, touching_dist2[q]);
            one_pair(k1, touching_dist2[q + 1]);
            continue;
          }
          const V3<double> d0 = separation(j0), d1 = separation(j1);
          V3<Lanes2> wj2 = lanes::zero3<Lanes2>();
          if constexpr (kRotation) wj2 = V3<Lanes2>{pack(pwx[j0], pwx[j1]), pack(pwy[j0], pwy[j1]), pack(pwz[j0], pwz[j1])};
          double* const h0 = history + static_cast<std::size_t>(k0) * kHistoryDoubles;
          double* const h1 = history + static_cast<std::size_t>(k1) * kHistoryDoubles;
          LawHistory<Lanes2> h{{pack(h0[0], h1[0]), pack(h0[1], h1[1]), pack(h0[2], h1[2])}, pack(h0[3], h1[3])};
          const PairOut<Lanes2> r = pair_contact<Law, kRotation>(
              V3<Lanes2>{pack(d0.x, d1.x), pack(d0.y, d1.y), pack(d0.z, d1.z)}, pack(touching_dist2[q], touching_dist2[q + 1]),
              lanes::splat<Lanes2>(ri), pack(radius[j0], radius[j1]),
              V3<Lanes2>{lanes::splat<Lanes2>(vi.x) - pack(pvx[j0], pvx[j1]), lanes::splat<Lanes2>(vi.y) - pack(pvy[j0], pvy[j1]),
                         lanes::splat<Lanes2>(vi.z) - pack(pvz[j0], pvz[j1])},
              V3<Lanes2>{lanes::splat<Lanes2>(wi.x), lanes::splat<Lanes2>(wi.y), lanes::splat<Lanes2>(wi.z)}, wj2,
              params_row[material[j0]], tab, dt, h);
          for (int l = 0; l < 2; ++l) {
            double* const hl = l == 0 ? h0 : h1;
            hl[0] = h.elastic.x[l]; hl[1] = h.elastic.y[l]; hl[2] = h.elastic.z[l]; hl[3] = h.overlap_m[l];
            add(l == 0 ? k0 : k1, l == 0 ? j0 : j1, lanes::lane3(r.f, l), lanes::lane3(r.t_i, l), lanes::lane3(r.t_j, l));
          }
        }
      }
      for (; q < touching; ++q) one_pair(touching_pairs[q], touching_dist2[q]);
    }
    if constexpr (kStorePairs) {
      // Kept for the gather, which adds the partners' share in the same order as the direct pass.
      PairSum& si = sums[i];
      for (int c = 0; c < 3; ++c) { si.f[c] = sum_f[c]; if constexpr (kRotation) si.t[c] = sum_t[c]; }
    } else {
      // All pairs with i as `second` came earlier (their `first` is smaller): sums[i] is complete.
      PairSum& si = sums[i];
      p_.fx[i] += si.f[0] + sum_f[0];
      p_.fy[i] += si.f[1] + sum_f[1];
      p_.fz[i] += si.f[2] + sum_f[2];
      if constexpr (kRotation) {
        p_.tx[i] += si.t[0] + sum_t[0];
        p_.ty[i] += si.t[1] + sum_t[1];
        p_.tz[i] += si.t[2] + sum_t[2];
      }
      si = PairSum{};
    }
  }
}

template <bool kRotation>
void DemEngine::gather_stored_pair_forces() {
  const long long nn = static_cast<long long>(p_.size());
  const bool parallel = params_.threads > 1 && nn >= kMinParallelItems;
#pragma omp parallel for schedule(static) num_threads(params_.threads) if (parallel)
  for (long long ii = 0; ii < nn; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    // The partners' share, from zero in pair order — the order in which the direct pass adds it.
    double f[3] = {0.0, 0.0, 0.0}, t[3] = {0.0, 0.0, 0.0};
    for (std::uint32_t q = pairs_.second_start[i]; q < pairs_.second_start[i + 1]; ++q) {
      const std::uint32_t k = pairs_.second_pairs[q];
      for (int c = 0; c < 3; ++c) {
        f[c] -= pairs_.force[k * 3 + c];
        if constexpr (kRotation) t[c] += pairs_.torque_second[k * 3 + c];
      }
    }
    PairSum& si = pair_sum_[i];
    p_.fx[i] += f[0] + si.f[0];
    p_.fy[i] += f[1] + si.f[1];
    p_.fz[i] += f[2] + si.f[2];
    if constexpr (kRotation) {
      p_.tx[i] += t[0] + si.t[0];
      p_.ty[i] += t[1] + si.t[1];
      p_.tz[i] += t[2] + si.t[2];
    }
    si = PairSum{};
  }
}

const ForcePassTable kParticlePasses = ForcePassTables::particle(std::make_index_sequence<kForceVariantCount>{});

}  // namespace spread::dem
