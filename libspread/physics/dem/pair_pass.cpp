// Particle–particle contacts over the Verlet pair list (CSR half list, neighbor_list.hpp; the direct form
// looks only at the near list's pairs), as stages over the pass's own view of the engine (PairPassArrays:
// flat arrays, nothing else): per particle i, the touching pairs of a chunk of its list
// (touching_in_chunk), the contact law over them two at a time or one (law_over_touching), and i's
// finished sums (finish_particle). Where the processor has AVX-512, the direct form stages the touching
// pairs of many particles and runs the law over eight at a time (pair_pass_batched_avx512; on several
// threads pair_pass_batched_threads_avx512, the sums still added in pair order). Newton's third law (seed
// Eq. 1) is applied per pair, so each pair's law runs once.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <thread>
#include <utility>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

// The contact laws' templates take eight-lane values here, inlined into the AVX-512 pass only (lanes.hpp).
#pragma GCC diagnostic ignored "-Wpsabi"
// SPREAD_UNROLL (contact_kernel.hpp) on the short loops over lanes, components and history slots: GCC at
// -O2 left most of them as loops, with a group's history lanes and i's sums on the stack (-O3's
// -fpeel-loops unrolls them; the pragma does it in the build users get; docs/drum.md).


#include "libspread/core/cpu_features.hpp"
#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"

namespace spread::dem {

using detail::kMinParallelItems;

namespace {
using lanes::Lanes2;
using lanes::pack;
using lanes::splat;
using lanes::V3;

// The pass's forms, one template argument: per-pair results stored for a gather (threads, an energy
// monitor) or added straight into the sums; along a periodic z axis (minimum image) or not; with the next
// step's opening kick and drift (drift: direct form only, PairPassArrays::drift_dt_s) or without, so that
// the passes without it carry none of its code.
struct PairForm {
  bool store_pairs;
  bool periodic;
  bool drift;
};

// What the pass reads and writes, as flat arrays taken once outside the loop (the vectors' bounds and
// sizes do not change within the pass). Copied into each thread (firstprivate): shared, its pointers were
// read through the parallel region's argument block, and since a byte store (held) may alias anything,
// GCC reloaded them for every listed pair.
template <class Law>
struct PairPassArrays {
  const double *x, *y, *z, *vx, *vy, *vz, *wx, *wy, *wz, *radius, *mass, *inertia;
  const std::uint16_t* material;
  const std::uint8_t* active;
  const std::uint32_t *pair_start, *partner;
  double* history;
  std::uint8_t* held;
  double *pair_force, *pair_torque_i, *pair_torque_j;  // per pair (stored form)
  PairSum* sums;                                       // per particle
  double *fx, *fy, *fz, *tx, *ty, *tz;                 // the particles' force sums (the wall pass started them)
  const PairParams* params;                            // material pair table, row-major
  const typename Law::Coeffs* coeffs;                  // Law::coeffs per material pair
  std::size_t material_count;
  double period_m, dt_s;
  // Velocity Verlet's closing half kick, applied to each particle as its sums complete (the data are
  // still in cache; DemEngine::kick would read them all again): Δt/2 (s), 0 when the step has no kick here.
  double kick_dt_s;
  double gravity_m_s2[3];
  const double *inv_mass, *inv_inertia;
  double *kick_v[3], *kick_w[3];  // the velocities and spins the kick writes (the same arrays as vx… wz)
  // The pairs the direct pass looks at: entries [near_start[i], near_start[i + 1]) of near_pairs, each a
  // pair index (the near list, neighbor_list.hpp); null: all of i's listed pairs (the stored form).
  const std::uint32_t *near_start, *near_pairs;
  // The near list's bodies per entry and the bodies' touch rows (x, y, z, r; r NaN when inactive): the batched
  // pass's touch test, eight entries a register (null: one entry at a time). The drift form brings both
  // kinds of rows to the new positions and velocities as it moves each particle (the next pass then reads
  // them as they are); a particle's rows are read last by its own batch's stages 1 and 2.
  const std::uint32_t *near_first, *near_second;
  double* touch_rows;
  double* law_rows;  // the bodies' law rows (vx, vy, vz, wx, wy, wz, r, I), with touch_rows
  std::uint8_t* near_held;  // NearList::held, kept with `held` by the pass that reads the touch rows
  // The next step's opening half kick and drift, applied right after the closing kick when nothing comes
  // between the two steps (DemEngine::steps), by the passes of form drift: Δt of the drift (s). Both kicks
  // take the same forces and the same Δt/2, so the opening one adds the closing one's increment again.
  // drift_clears_sums: the sums are left at zero for the next step's force evaluation, as kick_drift's
  // clear_sums leaves them (otherwise its wall pass zeroes them, and they are not written here); x0…: the
  // positions at the near list's build, for the largest move since (null: not measured).
  double drift_dt_s;
  bool drift_clears_sums;
  double* position[3];
  const double *x0, *y0, *z0;
};

// Particle i's pairs to look at: entries [begin, end) of `at` (null: the pair indices themselves).
struct PairRange {
  const std::uint32_t* at;
  std::uint32_t begin, end;
  std::uint32_t operator[](std::uint32_t e) const { return at != nullptr ? at[e] : e; }
};
template <class Law>
SPREAD_CONTACT_INLINE PairRange pairs_of(const PairPassArrays<Law>& a, std::size_t i) {
  if (a.near_start != nullptr) return {a.near_pairs, a.near_start[i], a.near_start[i + 1]};
  return {nullptr, a.pair_start[i], a.pair_start[i + 1]};
}

// One kick's increments for particle i with force f (N) and torque t (N m): Δv = Δt (F/m + g),
// Δω = Δt T/I, exactly as DemEngine::kick and kick_spin compute them (Δt = kick_dt_s).
template <bool kRotation, class Law>
SPREAD_CONTACT_INLINE void kick_increments(const PairPassArrays<Law>& a, std::size_t i, const double (&f)[3], const double (&t)[3],
                                           double (&dv)[3], double (&dw)[3]) {
  const double dt = a.kick_dt_s, inv_m = a.inv_mass[i];
SPREAD_UNROLL(3)
  for (int c = 0; c < 3; ++c) dv[c] = dt * (f[c] * inv_m + a.gravity_m_s2[c]);
  if constexpr (kRotation) {
    const double inv_i = a.inv_inertia[i];
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) dw[c] = dt * t[c] * inv_i;
  }
}

// v += Δt (F/m + g), ω += Δt T/I for particle i, with its sums as stored.
template <bool kRotation, class Law>
SPREAD_CONTACT_INLINE void kick_particle(const PairPassArrays<Law>& a, std::size_t i) {
  if (!a.active[i]) return;
  const double f[3] = {a.fx[i], a.fy[i], a.fz[i]};
  double t[3] = {0.0, 0.0, 0.0}, dv[3], dw[3];
  if constexpr (kRotation) {
    t[0] = a.tx[i];
    t[1] = a.ty[i];
    t[2] = a.tz[i];
  }
  kick_increments<kRotation>(a, i, f, t, dv, dw);
SPREAD_UNROLL(3)
  for (int c = 0; c < 3; ++c) {
    a.kick_v[c][i] += dv[c];
    if constexpr (kRotation) a.kick_w[c][i] += dw[c];
  }
}

// Velocity Verlet's closing half kick of particle i with its finished sums F = F_walls + (partners' share +
// own share), the next step's opening half kick with the same F (v(t + 3Δt/2) = v(t + Δt) + Δt/2 a(t + Δt):
// the same increment added twice), and the next step's drift x += Δt v — each operation as kick_particle
// and the engine's kick_drift_range do it, so the bits are those of the two passes. The drift and the move
// apply to every particle, the kicks to the active ones (as there).
// The pairs' share of the sums comes as total_f = partners' share + own share (N), total_t likewise (N m).
template <bool kRotation, class Law>
SPREAD_CONTACT_INLINE void kick_twice_and_drift(const PairPassArrays<Law>& a, std::size_t i, const double (&total_f)[3],
                                                const double (&total_t)[3], double& moved2) {
  const double f[3] = {a.fx[i] + total_f[0], a.fy[i] + total_f[1], a.fz[i] + total_f[2]};
  double t[3] = {0.0, 0.0, 0.0};
  if constexpr (kRotation) {
    const double* const torque[3] = {a.tx, a.ty, a.tz};
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) t[c] = torque[c][i] + total_t[c];
  }
  double v[3] = {a.kick_v[0][i], a.kick_v[1][i], a.kick_v[2][i]}, w[3] = {0.0, 0.0, 0.0};
  if constexpr (kRotation) {
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) w[c] = a.kick_w[c][i];
  }
  if (a.active[i]) {
    double dv[3], dw[3];
    kick_increments<kRotation>(a, i, f, t, dv, dw);
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      v[c] = (v[c] + dv[c]) + dv[c];
      a.kick_v[c][i] = v[c];
      if constexpr (kRotation) {
        w[c] = (w[c] + dw[c]) + dw[c];
        a.kick_w[c][i] = w[c];
      }
    }
  }
  if (a.drift_clears_sums) {
    a.fx[i] = a.fy[i] = a.fz[i] = 0.0;
    if constexpr (kRotation) a.tx[i] = a.ty[i] = a.tz[i] = 0.0;
  }
  double x[3];
SPREAD_UNROLL(3)
  for (int c = 0; c < 3; ++c) {
    x[c] = a.position[c][i] + a.drift_dt_s * v[c];
    a.position[c][i] = x[c];
  }
  if (a.touch_rows != nullptr) {
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      a.touch_rows[4 * i + static_cast<std::size_t>(c)] = x[c];
      a.law_rows[8 * i + static_cast<std::size_t>(c)] = v[c];
      if constexpr (kRotation) a.law_rows[8 * i + 3 + static_cast<std::size_t>(c)] = w[c];
    }
  }
  if (a.x0 != nullptr) {
    const double dx = x[0] - a.x0[i], dy = x[1] - a.y0[i], dz = x[2] - a.z0[i];
    moved2 = std::max(moved2, dx * dx + dy * dy + dz * dz);
  }
}

// Particle i as its pairs read it (it is `first` in all of them), and its share of its pairs, summed from
// zero in pair order.
template <class Law>
struct FirstBody {
  std::size_t i;
  double x, y, z;  // position (m)
  double r, m;     // radius (m), mass (kg)
  V3<double> v, w;  // velocity (m/s), spin (rad/s)
  bool active;
  const PairParams* params_row;
  const typename Law::Coeffs* coeffs_row;
  double sum_f[3], sum_t[3];  // force (N), torque (N m)
};

// One touching pair's contact (T = double), or two pairs' side by side (T = Lanes2) with the same
// material pair: normal and overlap from the pair vector d (from j to i), the levers (Eq. 10), the
// contact points' relative velocity (Eq. 8), the law, and the moments on both (Eq. 15) with the law's
// rolling resistance.
template <class T>
struct PairOut {
  V3<T> f, t_i, t_j;  // force on i (j gets −f); torques on i and j
};
template <class V, class T>
SPREAD_CONTACT_INLINE PairOut<T> pair_contact(const V3<T>& d, T dist2, T ri, T rj, const V3<T>& v_rel, const V3<T>& wi,
                                              const V3<T>& wj, T inertia_eff, const PairParams& pp,
                                              const typename V::Law::Coeffs& pc, double dt, LawHistory<T>& h) {
  using Law = typename V::Law;
  constexpr bool kRotation = V::kRotation;
  // 1/|d|² does not wait for the sqrt (the two overlap); the normal is d |d| / |d|².
  const T inv_dist2 = splat<T>(1.0) / dist2;
  const T dist = lanes::sqrt(dist2);
  const V3<T> n = d * (dist * inv_dist2);
  const T overlap = (ri + rj) - dist;
  const T li = Law::lever(ri, pp.share_a, overlap), lj = Law::lever(rj, pp.share_b, overlap);
  // Arms −l_i n and +l_j n both lie along n, so the relative velocity of the contact points,
  // v_i + ω_i × (−l_i n) − v_j − ω_j × (l_j n), takes one cross product, and both torques share n × F_t.
  V3<T> slip = v_rel;
  if constexpr (kRotation) slip = slip - cross(li * wi + lj * wj, n);
  const LawForce<T> law = Law::kernel(pc, pp.friction, ContactNormal<T>{n, d, inv_dist2}, overlap, slip, dt, h);
  PairOut<T> out{law.force_n, lanes::zero3<T>(), lanes::zero3<T>()};
  if constexpr (kRotation) {
    const V3<T> n_cross_ft = cross(n, law.tangential_n);
    out.t_i = (-li) * n_cross_ft;  // (−l_i n) × F_t
    out.t_j = (-lj) * n_cross_ft;  // (l_j n) × (−F_t)
  }
  if constexpr (Law::kRolling) {
    const V3<T> rolling = Law::rolling_torque(pp, law.normal_force_n, pc.r_eff_m, wi - wj, inertia_eff, dt);
    out.t_i = out.t_i + rolling;
    out.t_j = out.t_j - rolling;
  }
  return out;
}

// Pair vector from j to i (minimum image along a periodic axis).
template <class Law, PairForm kForm>
SPREAD_CONTACT_INLINE V3<double> separation(const PairPassArrays<Law>& a, const FirstBody<Law>& b, std::size_t j) {
  double dz = b.z - a.z[j];
  if constexpr (kForm.periodic) dz = minimum_image_z(dz, a.period_m);
  return V3<double>{b.x - a.x[j], b.y - a.y[j], dz};
}

// A finished pair: i's share into its running sums, j's share (Newton's third law, Eq. 1) into j's sums —
// finished when the loop reaches j > i — or, when stored, into the pair's output slots.
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE void add_pair(const PairPassArrays<typename V::Law>& a, FirstBody<typename V::Law>& b, std::uint32_t k,
                                    std::size_t j, const PairOut<double>& r) {
  a.held[k] = 1;
  b.sum_f[0] += r.f.x; b.sum_f[1] += r.f.y; b.sum_f[2] += r.f.z;
  if constexpr (V::kRotation) { b.sum_t[0] += r.t_i.x; b.sum_t[1] += r.t_i.y; b.sum_t[2] += r.t_i.z; }
  if constexpr (kForm.store_pairs) {
    a.pair_force[k * 3] = r.f.x; a.pair_force[k * 3 + 1] = r.f.y; a.pair_force[k * 3 + 2] = r.f.z;
    if constexpr (V::kRotation) {
      a.pair_torque_i[k * 3] = r.t_i.x; a.pair_torque_i[k * 3 + 1] = r.t_i.y; a.pair_torque_i[k * 3 + 2] = r.t_i.z;
      a.pair_torque_j[k * 3] = r.t_j.x; a.pair_torque_j[k * 3 + 1] = r.t_j.y; a.pair_torque_j[k * 3 + 2] = r.t_j.z;
    }
  } else {
    PairSum& sj = a.sums[j];
    sj.f[0] -= r.f.x; sj.f[1] -= r.f.y; sj.f[2] -= r.f.z;
    if constexpr (V::kRotation) { sj.t[0] += r.t_j.x; sj.t[1] += r.t_j.y; sj.t[2] += r.t_j.z; }
  }
}

// One touching pair alone (T = double): any materials and sizes. Its history is updated; the result is
// returned for the sums.
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE PairOut<double> one_pair_out(const PairPassArrays<typename V::Law>& a, const FirstBody<typename V::Law>& b,
                                                   std::uint32_t k, double dist2) {
  using Law = typename V::Law;
  const std::size_t j = a.partner[k];
  double* const hist = a.history + static_cast<std::size_t>(k) * kHistoryDoubles;
  const PairParams& pp = b.params_row[a.material[j]];
  // R* = r_i r_j / (r_i + r_j), M* = m_i m_j / (m_i + m_j) and what the law derives from them: from the
  // material-pair table when both materials have one size, else per contact.
  const typename Law::Coeffs& tab = b.coeffs_row[a.material[j]];
  const double rj = a.radius[j];
  const typename Law::Coeffs pc = tab.uniform ? tab : Law::coeffs(pp, b.r * rj / (b.r + rj), b.m * a.mass[j] / (b.m + a.mass[j]));
  V3<double> wj{0.0, 0.0, 0.0};
  if constexpr (V::kRotation) wj = V3<double>{a.wx[j], a.wy[j], a.wz[j]};
  double inertia_eff = 0.0;
  if constexpr (Law::kRolling) inertia_eff = a.inertia[b.i] * a.inertia[j] / (a.inertia[b.i] + a.inertia[j]);
  LawHistory<double> h = load_history(hist);
  const PairOut<double> r = pair_contact<V>(separation<Law, kForm>(a, b, j), dist2, b.r, rj,
                                                            b.v - V3<double>{a.vx[j], a.vy[j], a.vz[j]}, b.w, wj,
                                                            inertia_eff, pp, pc, a.dt_s, h);
  store_history(h, hist);
  return r;
}
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE void one_pair(const PairPassArrays<typename V::Law>& a, FirstBody<typename V::Law>& b, std::uint32_t k,
                                    double dist2) {
  add_pair<V, kForm>(a, b, k, a.partner[k], one_pair_out<V, kForm>(a, b, k, dist2));
}

// Two touching pairs of one material pair whose table entry holds (both materials of one size), side by
// side in lanes (lanes.hpp: lane by lane the same operations as one_pair).
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE void two_pairs(const PairPassArrays<typename V::Law>& a, FirstBody<typename V::Law>& b,
                                     std::uint32_t k0, std::uint32_t k1, double dist2_0, double dist2_1) {
  using Law = typename V::Law;
  const std::size_t j0 = a.partner[k0], j1 = a.partner[k1];
  const V3<double> d0 = separation<Law, kForm>(a, b, j0), d1 = separation<Law, kForm>(a, b, j1);
  V3<Lanes2> wj = lanes::zero3<Lanes2>();
  if constexpr (V::kRotation) wj = V3<Lanes2>{pack(a.wx[j0], a.wx[j1]), pack(a.wy[j0], a.wy[j1]), pack(a.wz[j0], a.wz[j1])};
  Lanes2 inertia_eff = splat<Lanes2>(0.0);
  if constexpr (Law::kRolling) {
    const Lanes2 ii = splat<Lanes2>(a.inertia[b.i]), ij = pack(a.inertia[j0], a.inertia[j1]);
    inertia_eff = ii * ij / (ii + ij);
  }
  double* const h0 = a.history + static_cast<std::size_t>(k0) * kHistoryDoubles;
  double* const h1 = a.history + static_cast<std::size_t>(k1) * kHistoryDoubles;
  LawHistory<Lanes2> h = load_history(h0, h1);
  const V3<Lanes2> v_rel{splat<Lanes2>(b.v.x) - pack(a.vx[j0], a.vx[j1]), splat<Lanes2>(b.v.y) - pack(a.vy[j0], a.vy[j1]),
                         splat<Lanes2>(b.v.z) - pack(a.vz[j0], a.vz[j1])};
  const PairOut<Lanes2> r = pair_contact<V>(
      V3<Lanes2>{pack(d0.x, d1.x), pack(d0.y, d1.y), pack(d0.z, d1.z)}, pack(dist2_0, dist2_1), splat<Lanes2>(b.r),
      pack(a.radius[j0], a.radius[j1]), v_rel, V3<Lanes2>{splat<Lanes2>(b.w.x), splat<Lanes2>(b.w.y), splat<Lanes2>(b.w.z)},
      wj, inertia_eff, b.params_row[a.material[j0]], b.coeffs_row[a.material[j0]], a.dt_s, h);
SPREAD_UNROLL(2)
  for (int l = 0; l < 2; ++l) {
    store_history(h, l, l == 0 ? h0 : h1);
    add_pair<V, kForm>(a, b, l == 0 ? k0 : k1, l == 0 ? j0 : j1,
                       PairOut<double>{lanes::lane3(r.f, l), lanes::lane3(r.t_i, l), lanes::lane3(r.t_j, l)});
  }
}

// Stage 1 of entries [chunk, chunk_end) of i's pairs (range): without a branch on "touching" — about a third of
// the listed pairs touch, scattered, so that branch was mispredicted often — the touching pairs' indices
// and squared distances are appended to the buffers; a pair that has just come apart releases its
// tangential spring. Returns how many touch. With pair vectors given (d[3], batched pass below), each
// touching pair's vector from j to i is kept too.
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE std::uint32_t touching_in_chunk(const PairPassArrays<typename V::Law>& a, const FirstBody<typename V::Law>& b,
                                                      const PairRange& range, std::uint32_t chunk, std::uint32_t chunk_end,
                                                      std::uint32_t* pairs, double* dist2s, double* const* d = nullptr) {
  std::uint32_t touching = 0;
  for (std::uint32_t e = chunk; e < chunk_end; ++e) {
    const std::uint32_t k = range[e];
    const std::size_t j = a.partner[k];
    const V3<double> dk = separation<typename V::Law, kForm>(a, b, j);
    const double dist2 = squared_norm(dk);
    const double cut = b.r + a.radius[j];
    const bool touches = (dist2 < cut * cut) & b.active & (a.active[j] != 0) & (dist2 != 0.0);
    pairs[touching] = k;
    dist2s[touching] = dist2;
    if (d != nullptr) {
      d[0][touching] = dk.x;
      d[1][touching] = dk.y;
      d[2][touching] = dk.z;
    }
    touching += touches ? 1u : 0u;
    // The history is touched only if it holds anything (held byte): the apart pairs cost a byte read, not
    // 32 bytes. Rarely true, so predictable.
    if (a.held[k] & static_cast<std::uint8_t>(!touches)) {
      clear_history(a.history + static_cast<std::size_t>(k) * kHistoryDoubles);
      a.held[k] = 0;
    }
    if constexpr (kForm.store_pairs) {
SPREAD_UNROLL(3)
      for (int c = 0; c < 3; ++c) a.pair_force[k * 3 + c] = 0.0;
      if constexpr (V::kRotation)
SPREAD_UNROLL(3)
        for (int c = 0; c < 3; ++c) a.pair_torque_i[k * 3 + c] = a.pair_torque_j[k * 3 + c] = 0.0;
    }
  }
  return touching;
}

// Stage 2: the contact law over the touching pairs, in pair order (so the sums are those of one loop),
// two pairs at a time in lanes when they share their materials' table entry.
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE void law_over_touching(const PairPassArrays<typename V::Law>& a, FirstBody<typename V::Law>& b,
                                             const std::uint32_t* pairs, const double* dist2s, std::uint32_t touching) {
  std::uint32_t q = 0;
  for (; q + 2 <= touching; q += 2) {
    const std::uint32_t k0 = pairs[q], k1 = pairs[q + 1];
    const std::uint16_t m0 = a.material[a.partner[k0]];
    if (a.material[a.partner[k1]] != m0 || !b.coeffs_row[m0].uniform) {
      one_pair<V, kForm>(a, b, k0, dist2s[q]);
      one_pair<V, kForm>(a, b, k1, dist2s[q + 1]);
    } else {
      two_pairs<V, kForm>(a, b, k0, k1, dist2s[q], dist2s[q + 1]);
    }
  }
  for (; q < touching; ++q) one_pair<V, kForm>(a, b, pairs[q], dist2s[q]);
}

// Stage 3: i's sums. Stored, they are kept for the gather, which adds the partners' share in the same
// order as the direct pass; direct, every pair with i as `second` came earlier (its `first` is smaller),
// so sums[i] is complete and goes into the force sums.
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE void finish_sums(const PairPassArrays<typename V::Law>& a, std::size_t i, const double (&sum_f)[3],
                                       const double (&sum_t)[3], double& moved2) {
  PairSum& si = a.sums[i];
  if constexpr (kForm.store_pairs) {
    for (int c = 0; c < 3; ++c) { si.f[c] = sum_f[c]; if constexpr (V::kRotation) si.t[c] = sum_t[c]; }
    return;
  }
  if constexpr (kForm.drift) {
    double total_f[3], total_t[3] = {0.0, 0.0, 0.0};
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      total_f[c] = si.f[c] + sum_f[c];
      if constexpr (V::kRotation) total_t[c] = si.t[c] + sum_t[c];
    }
    kick_twice_and_drift<V::kRotation>(a, i, total_f, total_t, moved2);
    si = PairSum{};
    return;
  }
  a.fx[i] += si.f[0] + sum_f[0];
  a.fy[i] += si.f[1] + sum_f[1];
  a.fz[i] += si.f[2] + sum_f[2];
  if constexpr (V::kRotation) {
    a.tx[i] += si.t[0] + sum_t[0];
    a.ty[i] += si.t[1] + sum_t[1];
    a.tz[i] += si.t[2] + sum_t[2];
  }
  si = PairSum{};
  if (a.kick_dt_s != 0.0) kick_particle<V::kRotation>(a, i);
}
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE void finish_particle(const PairPassArrays<typename V::Law>& a, const FirstBody<typename V::Law>& b,
                                           double& moved2) {
  finish_sums<V, kForm>(a, b.i, b.sum_f, b.sum_t, moved2);
}

template <class V>
SPREAD_CONTACT_INLINE FirstBody<typename V::Law> first_body(const PairPassArrays<typename V::Law>& a, std::size_t i) {
  FirstBody<typename V::Law> b{i, a.x[i], a.y[i], a.z[i], a.radius[i], a.mass[i], V3<double>{a.vx[i], a.vy[i], a.vz[i]},
                               V3<double>{0.0, 0.0, 0.0}, a.active[i] != 0,
                               a.params + static_cast<std::size_t>(a.material[i]) * a.material_count,
                               a.coeffs + static_cast<std::size_t>(a.material[i]) * a.material_count,
                               {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  if constexpr (V::kRotation) b.w = V3<double>{a.wx[i], a.wy[i], a.wz[i]};
  return b;
}

// One particle of the pass: its list in chunks through stages 1 and 2, then stage 3.
template <class V, PairForm kForm>
__attribute__((always_inline)) inline void pass_particle(const PairPassArrays<typename V::Law>& a, long long ii, double& moved2) {
  FirstBody<typename V::Law> b = first_body<V>(a, static_cast<std::size_t>(ii));
  constexpr std::uint32_t kChunk = 64;
  const PairRange range = pairs_of(a, b.i);
  for (std::uint32_t chunk = range.begin; chunk < range.end; chunk += kChunk) {
    std::uint32_t pairs[kChunk];
    double dist2s[kChunk];
    const std::uint32_t touching = touching_in_chunk<V, kForm>(a, b, range, chunk, std::min(range.end, chunk + kChunk), pairs, dist2s);
    law_over_touching<V, kForm>(a, b, pairs, dist2s, touching);
  }
  finish_particle<V, kForm>(a, b, moved2);
}

// The pass, particle by particle, compiled for the baseline and (on x86) for AVX-512, chosen at run time
// (pair_pass below). flatten: the whole pair kernel (geometry, law, lane operations) inlined into the
// loop; at -O2 GCC otherwise keeps the law as a call per touching pair, which costs about a third of the
// pass. Each has its own OpenMP loop: the region is outlined from the function it is written in, with
// that function's target.
// Particles [begin, end). noinline: the batched pass calls it for a particle whose list outgrows a batch,
// and flatten there would otherwise compile a second copy of the whole two-lane pass into it.
template <class V, PairForm kForm>
__attribute__((noinline)) SPREAD_CONTACT_FLATTEN double pair_pass_portable(PairPassArrays<typename V::Law> a, long long begin,
                                                                           long long end, int threads) {
  const bool parallel = kForm.store_pairs && threads > 1 && end - begin >= kMinParallelItems;
  double moved2 = 0.0;
#pragma omp parallel for schedule(static) num_threads(threads) if (parallel) firstprivate(a) reduction(max : moved2)
  for (long long ii = begin; ii < end; ++ii) pass_particle<V, kForm>(a, ii, moved2);
  return moved2;
}
#if defined(__x86_64__) || defined(__i386__)
template <class V, PairForm kForm>
__attribute__((target("avx512f"))) SPREAD_CONTACT_FLATTEN double pair_pass_avx512(PairPassArrays<typename V::Law> a,
                                                                                 long long count, int threads) {
  const bool parallel = kForm.store_pairs && threads > 1 && count >= kMinParallelItems;
  double moved2 = 0.0;
#pragma omp parallel for schedule(static) num_threads(threads) if (parallel) firstprivate(a) reduction(max : moved2)
  for (long long ii = 0; ii < count; ++ii) pass_particle<V, kForm>(a, ii, moved2);
  return moved2;
}

// The batched pass (one thread, sums added directly): the touching pairs of consecutive particles are
// staged, the law runs over them eight at a time in AVX-512 lanes — pairs of different first bodies
// side by side — and the results are added in pair order afterwards. A pair's law reads only the state
// and its own history, never a sum, so computing all of a batch's forces before adding any changes no
// sum: each is added to in the same order as in pass_particle (the same bits).
struct PairBatch {
  // Staged pairs. The batch is about 45 KB with the results and the kicks' totals, most of L1 (48 KB); 128
  // pairs took the same time on the drum, 64 more (docs/drum.md).
  static constexpr std::uint32_t kPairs = 256;
  static constexpr std::uint32_t kSlots = kPairs + 8;
  alignas(64) double d[3][kSlots];  // pair vector from j to i (m)
  alignas(64) double dist2[kSlots];  // |d|² (m²)
  alignas(64) double f[3][kSlots], t_i[3][kSlots], t_j[3][kSlots];
  std::uint32_t k[kSlots], i[kSlots], j[kSlots];  // pair index, first body, second body
  std::uint32_t e[kSlots];                          // near entry (the rows' stage 1 only)
  std::uint32_t particle_end[kPairs];  // the staged pairs of the window's p-th particle end at particle_end[p]
  // The pairs' share of the p-th particle's sums, partners' share + own share (N, N m): stage 3 of the drift
  // form, which kicks and drifts the batch's particles eight at a time after their sums.
  alignas(64) double total_f[3][kPairs], total_t[3][kPairs];
};

// Eight values into one register, two at a time (a load and a load into the upper half), then the halves
// joined: GCC's per-lane insertion went through the stack, a 64-byte load after eight 8-byte stores.
SPREAD_CONTACT_INLINE lanes::Lanes8 lanes8(double a0, double a1, double a2, double a3, double a4, double a5, double a6,
                                           double a7) {
  using Lanes4 = double __attribute__((vector_size(32)));
  const Lanes4 low = __builtin_shufflevector(lanes::Lanes2{a0, a1}, lanes::Lanes2{a2, a3}, 0, 1, 2, 3);
  const Lanes4 high = __builtin_shufflevector(lanes::Lanes2{a4, a5}, lanes::Lanes2{a6, a7}, 0, 1, 2, 3);
  return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
}
SPREAD_CONTACT_INLINE lanes::Lanes8 gather_lanes8(const double* base, const std::uint32_t* index) {
  return lanes8(base[index[0]], base[index[1]], base[index[2]], base[index[3]], base[index[4]], base[index[5]],
                base[index[6]], base[index[7]]);
}
SPREAD_CONTACT_INLINE lanes::Lanes8 load_lanes8(const double* p) {
  lanes::Lanes8 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
SPREAD_CONTACT_INLINE void store_lanes8(double* p, lanes::Lanes8 v) { __builtin_memcpy(p, &v, sizeof v); }

// Eight rows of four doubles (rows[l]: a pair's history, kHistoryDoubles = 4, or a body's touch row) as four
// eight-lane values, slot by slot: each row loaded whole, two rows a register, and the 8 × 4 block
// transposed in registers (12 shuffles, where the lanes filled one at a time took 32 loads and 28 shuffles).
using Lanes4 = double __attribute__((vector_size(32)));
static_assert(kHistoryDoubles == 4, "the history transposes are written for four slots");
template <class Row>
SPREAD_CONTACT_INLINE void load_rows8(Row* const (&rows)[8], lanes::Lanes8 (&slot)[4]) {
  using lanes::Lanes8;
  Lanes4 r[8];
SPREAD_UNROLL(8)
  for (int l = 0; l < 8; ++l) __builtin_memcpy(&r[l], rows[l], sizeof r[l]);
  // a_l = rows l and l + 4; then pairs of slots of rows (l, l + 1) side by side in each 128-bit lane.
  Lanes8 a[4];
SPREAD_UNROLL(4)
  for (int l = 0; l < 4; ++l) a[l] = __builtin_shufflevector(r[l], r[l + 4], 0, 1, 2, 3, 4, 5, 6, 7);
  const Lanes8 b0 = __builtin_shufflevector(a[0], a[1], 0, 8, 2, 10, 4, 12, 6, 14);  // slots 0, 2 of rows 0 1 | 4 5
  const Lanes8 b1 = __builtin_shufflevector(a[0], a[1], 1, 9, 3, 11, 5, 13, 7, 15);  // slots 1, 3
  const Lanes8 b2 = __builtin_shufflevector(a[2], a[3], 0, 8, 2, 10, 4, 12, 6, 14);  // rows 2 3 | 6 7
  const Lanes8 b3 = __builtin_shufflevector(a[2], a[3], 1, 9, 3, 11, 5, 13, 7, 15);
  slot[0] = __builtin_shufflevector(b0, b2, 0, 1, 8, 9, 4, 5, 12, 13);
  slot[2] = __builtin_shufflevector(b0, b2, 2, 3, 10, 11, 6, 7, 14, 15);
  slot[1] = __builtin_shufflevector(b1, b3, 0, 1, 8, 9, 4, 5, 12, 13);
  slot[3] = __builtin_shufflevector(b1, b3, 2, 3, 10, 11, 6, 7, 14, 15);
}
// An 8 × 8 block of doubles transposed in registers (24 shuffles): r[l][c] → col[c][l].
SPREAD_CONTACT_INLINE void transpose8x8(const lanes::Lanes8 (&r)[8], lanes::Lanes8 (&col)[8]) {
  using lanes::Lanes8;
  Lanes8 t[8], u[8];
SPREAD_UNROLL(4)
  for (int l = 0; l < 8; l += 2) {
    t[l] = __builtin_shufflevector(r[l], r[l + 1], 0, 8, 2, 10, 4, 12, 6, 14);      // columns 0 2 4 6 of rows l, l + 1
    t[l + 1] = __builtin_shufflevector(r[l], r[l + 1], 1, 9, 3, 11, 5, 13, 7, 15);  // columns 1 3 5 7
  }
SPREAD_UNROLL(2)
  for (int h = 0; h < 8; h += 4) {  // rows h … h + 3
    u[h] = __builtin_shufflevector(t[h], t[h + 2], 0, 1, 8, 9, 4, 5, 12, 13);          // columns 0, 4
    u[h + 1] = __builtin_shufflevector(t[h], t[h + 2], 2, 3, 10, 11, 6, 7, 14, 15);    // columns 2, 6
    u[h + 2] = __builtin_shufflevector(t[h + 1], t[h + 3], 0, 1, 8, 9, 4, 5, 12, 13);  // columns 1, 5
    u[h + 3] = __builtin_shufflevector(t[h + 1], t[h + 3], 2, 3, 10, 11, 6, 7, 14, 15);  // columns 3, 7
  }
  col[0] = __builtin_shufflevector(u[0], u[4], 0, 1, 2, 3, 8, 9, 10, 11);
  col[4] = __builtin_shufflevector(u[0], u[4], 4, 5, 6, 7, 12, 13, 14, 15);
  col[2] = __builtin_shufflevector(u[1], u[5], 0, 1, 2, 3, 8, 9, 10, 11);
  col[6] = __builtin_shufflevector(u[1], u[5], 4, 5, 6, 7, 12, 13, 14, 15);
  col[1] = __builtin_shufflevector(u[2], u[6], 0, 1, 2, 3, 8, 9, 10, 11);
  col[5] = __builtin_shufflevector(u[2], u[6], 4, 5, 6, 7, 12, 13, 14, 15);
  col[3] = __builtin_shufflevector(u[3], u[7], 0, 1, 2, 3, 8, 9, 10, 11);
  col[7] = __builtin_shufflevector(u[3], u[7], 4, 5, 6, 7, 12, 13, 14, 15);
}
// Eight rows of eight doubles (a body's law row each) as eight eight-lane values, column by column: the
// rows loaded whole and transposed (where eight columns filled a lane at a time take 64 loads and 56 shuffles).
SPREAD_CONTACT_INLINE void load_rows8x8(const double* const (&rows)[8], lanes::Lanes8 (&col)[8]) {
  lanes::Lanes8 r[8];
SPREAD_UNROLL(8)
  for (int l = 0; l < 8; ++l) __builtin_memcpy(&r[l], rows[l], sizeof r[l]);
  transpose8x8(r, col);
}

// The inverse: lane l of the four slots back to rows[l], for the first `valid` lanes.
SPREAD_CONTACT_INLINE void store_histories8(const lanes::Lanes8 (&slot)[4], double* const (&rows)[8], std::uint32_t valid) {
  using lanes::Lanes8;
  const Lanes8 c0 = __builtin_shufflevector(slot[0], slot[1], 0, 8, 2, 10, 4, 12, 6, 14);  // slots 0 1 of lanes 0 2 4 6
  const Lanes8 c1 = __builtin_shufflevector(slot[0], slot[1], 1, 9, 3, 11, 5, 13, 7, 15);  // of lanes 1 3 5 7
  const Lanes8 c2 = __builtin_shufflevector(slot[2], slot[3], 0, 8, 2, 10, 4, 12, 6, 14);  // slots 2 3
  const Lanes8 c3 = __builtin_shufflevector(slot[2], slot[3], 1, 9, 3, 11, 5, 13, 7, 15);
  Lanes4 r[8];
  r[0] = __builtin_shufflevector(c0, c2, 0, 1, 8, 9);
  r[2] = __builtin_shufflevector(c0, c2, 2, 3, 10, 11);
  r[4] = __builtin_shufflevector(c0, c2, 4, 5, 12, 13);
  r[6] = __builtin_shufflevector(c0, c2, 6, 7, 14, 15);
  r[1] = __builtin_shufflevector(c1, c3, 0, 1, 8, 9);
  r[3] = __builtin_shufflevector(c1, c3, 2, 3, 10, 11);
  r[5] = __builtin_shufflevector(c1, c3, 4, 5, 12, 13);
  r[7] = __builtin_shufflevector(c1, c3, 6, 7, 14, 15);
SPREAD_UNROLL(8)
  for (std::uint32_t l = 0; l < valid; ++l) __builtin_memcpy(rows[l], &r[l], sizeof r[l]);
}

// Touch rows 2M and 2M + 1 of eight consecutive ones (x, y, z, r) given the new x, y, z of lanes 2M and 2M + 1;
// r stays as the row has it.
template <int M>
SPREAD_CONTACT_INLINE void store_touch_rows2(double* rows, lanes::Lanes8 x, lanes::Lanes8 y, lanes::Lanes8 z) {
  double* const at = rows + 8 * M;
  const lanes::Lanes8 old = load_lanes8(at);
  const lanes::Lanes8 xy = __builtin_shufflevector(x, y, 2 * M, 8 + 2 * M, 0, 0, 2 * M + 1, 9 + 2 * M, 0, 0);
  const lanes::Lanes8 xyz = __builtin_shufflevector(xy, z, 0, 1, 8 + 2 * M, 3, 4, 5, 9 + 2 * M, 7);
  store_lanes8(at, __builtin_shufflevector(xyz, old, 0, 1, 2, 11, 4, 5, 6, 15));
}

// kick_twice_and_drift for particles [i, i + 8), a particle a lane: lane by lane the same operations in the
// same order (the same bits), eight particles an instruction (one at a time they took about a quarter of the
// pass's samples; in registers about 18 time-stamp ticks a particle, docs/drum.md). total_f[c], total_t[c]:
// the pairs' share of the eight particles' sums, component c. moved2: the largest squared move since the near
// list's build, lane by lane.
template <bool kRotation, class Law>
SPREAD_CONTACT_INLINE void kick_twice_and_drift8(const PairPassArrays<Law>& a, std::size_t i, const double* const (&total_f)[3],
                                                 const double* const (&total_t)[3], lanes::Lanes8& moved2) {
  using lanes::Lanes8;
  using lanes::Mask8;
  using Bytes8 = std::uint8_t __attribute__((vector_size(8)));
  Bytes8 active_bytes;
  __builtin_memcpy(&active_bytes, a.active + i, sizeof active_bytes);
  const Mask8 active = __builtin_convertvector(active_bytes, Mask8) != 0;  // the kicks apply to the active only
  const Lanes8 dt = splat<Lanes8>(a.kick_dt_s), inv_m = load_lanes8(a.inv_mass + i);
  double* const force[3] = {a.fx, a.fy, a.fz};
  double* const torque[3] = {a.tx, a.ty, a.tz};
  Lanes8 v[3], w[3] = {splat<Lanes8>(0.0), splat<Lanes8>(0.0), splat<Lanes8>(0.0)};
SPREAD_UNROLL(3)
  for (int c = 0; c < 3; ++c) {
    const Lanes8 f = load_lanes8(force[c] + i) + load_lanes8(total_f[c]);
    const Lanes8 dv = dt * (f * inv_m + splat<Lanes8>(a.gravity_m_s2[c]));
    const Lanes8 v0 = load_lanes8(a.kick_v[c] + i);
    v[c] = lanes::select(active, (v0 + dv) + dv, v0);
    store_lanes8(a.kick_v[c] + i, v[c]);
  }
  if constexpr (kRotation) {
    const Lanes8 inv_i = load_lanes8(a.inv_inertia + i);
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      const Lanes8 t = load_lanes8(torque[c] + i) + load_lanes8(total_t[c]);
      const Lanes8 dw = dt * t * inv_i;
      const Lanes8 w0 = load_lanes8(a.kick_w[c] + i);
      w[c] = lanes::select(active, (w0 + dw) + dw, w0);
      store_lanes8(a.kick_w[c] + i, w[c]);
    }
  }
  if (a.drift_clears_sums) {
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      store_lanes8(force[c] + i, splat<Lanes8>(0.0));
      if constexpr (kRotation) store_lanes8(torque[c] + i, splat<Lanes8>(0.0));
    }
  }
  Lanes8 x[3];
  const Lanes8 drift_dt = splat<Lanes8>(a.drift_dt_s);
SPREAD_UNROLL(3)
  for (int c = 0; c < 3; ++c) {
    x[c] = load_lanes8(a.position[c] + i) + drift_dt * v[c];
    store_lanes8(a.position[c] + i, x[c]);
  }
  if (a.touch_rows != nullptr) {
    double* const rows = a.touch_rows + 4 * i;
    store_touch_rows2<0>(rows, x[0], x[1], x[2]);
    store_touch_rows2<1>(rows, x[0], x[1], x[2]);
    store_touch_rows2<2>(rows, x[0], x[1], x[2]);
    store_touch_rows2<3>(rows, x[0], x[1], x[2]);
    // The law rows (vx, vy, vz, wx, wy, wz, r, I) as written before the pass (no spin: zeros).
    const Lanes8 col[8] = {v[0], v[1], v[2], w[0], w[1], w[2], load_lanes8(a.radius + i), load_lanes8(a.inertia + i)};
    Lanes8 row[8];
    transpose8x8(col, row);
SPREAD_UNROLL(8)
    for (int l = 0; l < 8; ++l) store_lanes8(a.law_rows + 8 * (i + static_cast<std::size_t>(l)), row[l]);
  }
  if (a.x0 != nullptr) {
    const Lanes8 dx = x[0] - load_lanes8(a.x0 + i), dy = x[1] - load_lanes8(a.y0 + i), dz = x[2] - load_lanes8(a.z0 + i);
    const Lanes8 d2 = dx * dx + dy * dy + dz * dz;
    moved2 = lanes::select(moved2 < d2, d2, moved2);  // std::max(moved2, d2), lane by lane
  }
}

// Staged pairs [q, q + valid) one at a time (materials differ, or sizes within a material). noinline: one
// copy of the one-pair law per variant, not one inside each batched pass.
template <class V, PairForm kForm>
__attribute__((noinline)) SPREAD_CONTACT_FLATTEN void staged_pairs_alone(const PairPassArrays<typename V::Law>& a, PairBatch& s,
                                                                         std::uint32_t q, std::uint32_t valid) {
  for (std::uint32_t l = 0; l < valid; ++l) {
    const FirstBody<typename V::Law> b = first_body<V>(a, s.i[q + l]);
    const PairOut<double> r = one_pair_out<V, kForm>(a, b, s.k[q + l], s.dist2[q + l]);
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      s.f[c][q + l] = (&r.f.x)[c];
      s.t_i[c][q + l] = (&r.t_i.x)[c];
      s.t_j[c][q + l] = (&r.t_j.x)[c];
    }
  }
}

// Staged pairs [q, q + 8): one material pair whose table entry holds (both materials of one size), eight
// pairs in lanes; otherwise each alone. Lanes past `valid` repeat pair q and are not written back.
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE void eight_pairs(const PairPassArrays<typename V::Law>& a, PairBatch& s, std::uint32_t q,
                                       std::uint32_t valid) {
  using Law = typename V::Law;
  using lanes::Lanes8;
  std::uint32_t* const j = s.j + q;
SPREAD_UNROLL(8)
  for (int l = 0; l < 8; ++l) {
    j[l] = a.partner[s.k[q + l]];
    // Stage 3 adds into j's sums, which a later particle finished a step ago: likely out of L2 by now.
    __builtin_prefetch(a.sums + j[l], 1);
  }
  bool one_entry = true;
  std::size_t entry = 0;
  if (a.material_count > 1) {
    const std::uint16_t mi = a.material[s.i[q]], mj = a.material[j[0]];
SPREAD_UNROLL(8)
    for (int l = 1; l < 8; ++l) one_entry &= (a.material[s.i[q + l]] == mi) & (a.material[j[l]] == mj);
    entry = static_cast<std::size_t>(mi) * a.material_count + mj;
  }
  if (!one_entry || !a.coeffs[entry].uniform) {
    staged_pairs_alone<V, kForm>(a, s, q, valid);
    return;
  }
  const std::uint32_t* i = s.i + q;
  // Each body's v, ω, r, I: from its law row where the pass has them, else lane by lane from the arrays.
  Lanes8 body_i[8], body_j[8];
  if (a.law_rows != nullptr) {
    const double* rows_i[8];
    const double* rows_j[8];
SPREAD_UNROLL(8)
    for (int l = 0; l < 8; ++l) {
      rows_i[l] = a.law_rows + 8 * static_cast<std::size_t>(i[l]);
      rows_j[l] = a.law_rows + 8 * static_cast<std::size_t>(j[l]);
    }
    load_rows8x8(rows_i, body_i);
    load_rows8x8(rows_j, body_j);
  } else {
    const double* const arrays[8] = {a.vx, a.vy, a.vz, a.wx, a.wy, a.wz, a.radius, a.inertia};
SPREAD_UNROLL(8)
    for (int c = 0; c < 8; ++c) {
      const bool needed = c < 3 || (c < 6 && V::kRotation) || c == 6 || (c == 7 && Law::kRolling);
      body_i[c] = needed ? gather_lanes8(arrays[c], i) : splat<Lanes8>(0.0);
      body_j[c] = needed ? gather_lanes8(arrays[c], j) : splat<Lanes8>(0.0);
    }
  }
  const V3<Lanes8> v_rel{body_i[0] - body_j[0], body_i[1] - body_j[1], body_i[2] - body_j[2]};
  V3<Lanes8> wi = lanes::zero3<Lanes8>(), wj = lanes::zero3<Lanes8>();
  if constexpr (V::kRotation) {
    wi = V3<Lanes8>{body_i[3], body_i[4], body_i[5]};
    wj = V3<Lanes8>{body_j[3], body_j[4], body_j[5]};
  }
  Lanes8 inertia_eff = splat<Lanes8>(0.0);
  if constexpr (Law::kRolling) inertia_eff = body_i[7] * body_j[7] / (body_i[7] + body_j[7]);
  double* hist[8];
SPREAD_UNROLL(8)
  for (int l = 0; l < 8; ++l) hist[l] = a.history + static_cast<std::size_t>(s.k[q + l]) * kHistoryDoubles;
  Lanes8 h_in[kHistoryDoubles];
  load_rows8(hist, h_in);
  LawHistory<Lanes8> h{{h_in[0], h_in[1], h_in[2]}, h_in[3]};
  const PairOut<Lanes8> r = pair_contact<V>(
      V3<Lanes8>{load_lanes8(s.d[0] + q), load_lanes8(s.d[1] + q), load_lanes8(s.d[2] + q)}, load_lanes8(s.dist2 + q),
      body_i[6], body_j[6], v_rel, wi, wj, inertia_eff, a.params[entry], a.coeffs[entry],
      a.dt_s, h);
  const Lanes8 h_out[kHistoryDoubles] = {h.elastic.x, h.elastic.y, h.elastic.z, h.overlap_m};
  store_histories8(h_out, hist, valid);
  const V3<Lanes8>* outs[3] = {&r.f, &r.t_i, &r.t_j};
  double(*slots[3])[PairBatch::kSlots] = {s.f, s.t_i, s.t_j};
SPREAD_UNROLL(3)
  for (int o = 0; o < 3; ++o) {
    store_lanes8(slots[o][0] + q, outs[o]->x);
    store_lanes8(slots[o][1] + q, outs[o]->y);
    store_lanes8(slots[o][2] + q, outs[o]->z);
  }
}

// Stage 1 of the batched pass: the touching pairs of particles [i0, i1) staged in s, as many particles
// from i0 on as fit (a particle's whole list must fit beside the touching pairs staged before it), or
// those up to `limit` only. Sets s's per-particle ends; returns i1 (i0 when i0's list alone outgrows the
// batch) and the staged pair count in n.
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE long long stage_touching(const PairPassArrays<typename V::Law>& a, PairBatch& s, long long i0, long long limit,
                                               std::uint32_t& n) {
  n = 0;
  std::uint32_t particles = 0;
  long long i1 = i0;
  for (; i1 < limit && particles < PairBatch::kPairs; ++i1) {
    const PairRange range = pairs_of(a, static_cast<std::size_t>(i1));
    if (n + (range.end - range.begin) > PairBatch::kPairs) break;
    const FirstBody<typename V::Law> b = first_body<V>(a, static_cast<std::size_t>(i1));
    double* const d[3] = {s.d[0] + n, s.d[1] + n, s.d[2] + n};
    const std::uint32_t touching = touching_in_chunk<V, kForm>(a, b, range, range.begin, range.end, s.k + n, s.dist2 + n, d);
    for (std::uint32_t q = n; q < n + touching; ++q) s.i[q] = static_cast<std::uint32_t>(i1);
    n += touching;
    s.particle_end[particles++] = n;
  }
  return i1;
}

// Stage 1 eight near entries a register, where the pass has the near list's bodies and the touch rows (not
// along a periodic axis): the touching pairs of particles [i0, i1) staged in s, as many particles from i0 on
// as have at most a batch of near entries in all, or those up to `limit` only; the same pairs, vectors and
// squared distances as stage_touching (the same operations, lane by lane: d = x_i − x_j, |d|² = (d_x² + d_y²)
// + d_z², touching when 0 ≠ |d|² < (r_i + r_j)², an inactive body's NaN radius failing the test), and a pair
// come apart releases its spring. Each entry's two rows are loaded whole and transposed (load_rows8); the
// touching lanes are packed by the processor's compress. Returns i1 (i0 when i0's entries alone outgrow the
// batch) and the staged pair count in n. Under clang not inlined (a call per batch): clang does not give an
// OpenMP region's outlined function its function's target and fails on the AVX-512 intrinsics there; GCC
// inlines it (the call cost about 1 % of the drum's step).
#if defined(__clang__)
#define SPREAD_ROWS_STAGE __attribute__((noinline, target("avx512f")))
#define SPREAD_ROWS_CALLER SPREAD_CONTACT_INLINE
#else
#define SPREAD_ROWS_STAGE __attribute__((target("avx512f"))) SPREAD_CONTACT_INLINE
#define SPREAD_ROWS_CALLER __attribute__((target("avx512f"))) SPREAD_CONTACT_INLINE
#endif
template <class V, PairForm kForm>
SPREAD_ROWS_STAGE long long stage_touching_rows(const PairPassArrays<typename V::Law>& a,
                                                                                       PairBatch& s, long long i0, long long limit,
                                                                                       std::uint32_t& n) {
  static_assert(!kForm.periodic, "the rows' touch test has no minimum image");
  using lanes::Lanes8;
  const std::uint32_t e0 = a.near_start[i0];
  long long i1 = i0;
  while (i1 < limit && i1 - i0 < static_cast<long long>(PairBatch::kPairs) && a.near_start[i1 + 1] - e0 <= PairBatch::kPairs) ++i1;
  n = 0;
  if (i1 == i0) return i0;
  const std::uint32_t e1 = a.near_start[i1];
  const __m512i lane = _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
  for (std::uint32_t e = e0; e < e1; e += 8) {
    const std::uint32_t count = std::min<std::uint32_t>(8, e1 - e);
    const __mmask8 valid = static_cast<__mmask8>((1u << count) - 1u);
    const double* row_i[8];
    const double* row_j[8];
SPREAD_UNROLL(8)
    for (std::uint32_t l = 0; l < 8; ++l) {
      const std::uint32_t at = e + std::min(l, count - 1);  // spare lanes repeat the last entry
      row_i[l] = a.touch_rows + 4 * static_cast<std::size_t>(a.near_first[at]);
      row_j[l] = a.touch_rows + 4 * static_cast<std::size_t>(a.near_second[at]);
    }
    Lanes8 ri[4], rj[4];
    load_rows8(row_i, ri);
    load_rows8(row_j, rj);
    const Lanes8 dx = ri[0] - rj[0], dy = ri[1] - rj[1], dz = ri[2] - rj[2];
    const Lanes8 dist2 = (dx * dx + dy * dy) + dz * dz;
    const Lanes8 cut = ri[3] + rj[3];
    const __m512d dist2_v = reinterpret_cast<__m512d>(dist2);
    const __mmask8 touch = _mm512_mask_cmp_pd_mask(valid, dist2_v, reinterpret_cast<__m512d>(cut * cut), _CMP_LT_OQ) &
                           _mm512_cmp_pd_mask(dist2_v, _mm512_setzero_pd(), _CMP_NEQ_UQ);
    const __m512i k = _mm512_maskz_loadu_epi32(valid, a.near_pairs + e);
    // The springs of the apart entries that still hold one (the entries' copies of `held`, eight in one load;
    // a gather of the pairs' own bytes cost more than the rest of the test here).
    const __m128i held8 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(a.near_held + e));
    const auto held = static_cast<__mmask8>(~_mm_movemask_epi8(_mm_cmpeq_epi8(held8, _mm_setzero_si128())));
    __mmask8 release = static_cast<__mmask8>(held & valid & ~touch);
    while (release != 0) {
      const int l = __builtin_ctz(release);
      release = static_cast<__mmask8>(release & (release - 1u));
      const std::uint32_t el = e + static_cast<std::uint32_t>(l), kl = a.near_pairs[el];
      clear_history(a.history + static_cast<std::size_t>(kl) * kHistoryDoubles);
      a.held[kl] = 0;
      a.near_held[el] = 0;
    }
    // The touching lanes, packed, after the n staged (a batch has room for eight past its pairs).
    _mm512_mask_storeu_epi32(s.k + n, 0xFF, _mm512_maskz_compress_epi32(touch, k));
    _mm512_mask_storeu_epi32(s.i + n, 0xFF, _mm512_maskz_compress_epi32(touch, _mm512_maskz_loadu_epi32(valid, a.near_first + e)));
    _mm512_mask_storeu_epi32(s.e + n, 0xFF, _mm512_maskz_compress_epi32(touch, _mm512_add_epi32(_mm512_set1_epi32(static_cast<int>(e)), lane)));
    _mm512_storeu_pd(s.dist2 + n, _mm512_maskz_compress_pd(touch, dist2_v));
    _mm512_storeu_pd(s.d[0] + n, _mm512_maskz_compress_pd(touch, reinterpret_cast<__m512d>(dx)));
    _mm512_storeu_pd(s.d[1] + n, _mm512_maskz_compress_pd(touch, reinterpret_cast<__m512d>(dy)));
    _mm512_storeu_pd(s.d[2] + n, _mm512_maskz_compress_pd(touch, reinterpret_cast<__m512d>(dz)));
    n += static_cast<std::uint32_t>(__builtin_popcount(touch));
  }
  // Each particle's staged pairs end after its last (the staged first bodies ascend), or where the
  // particle before it ends when it has none.
  const auto particles = static_cast<std::uint32_t>(i1 - i0);
  for (std::uint32_t p = 0; p < particles; ++p) s.particle_end[p] = 0;
  for (std::uint32_t q = 0; q < n; ++q) s.particle_end[s.i[q] - static_cast<std::uint32_t>(i0)] = q + 1;
  for (std::uint32_t p = 1; p < particles; ++p) s.particle_end[p] = std::max(s.particle_end[p], s.particle_end[p - 1]);
  return i1;
}

// Stage 1 as the pass has it: eight entries a register from the touch rows, else entry by entry.
template <class V, PairForm kForm>
SPREAD_ROWS_CALLER long long stage_batch(const PairPassArrays<typename V::Law>& a, PairBatch& s, long long i0, long long limit,
                                         std::uint32_t& n) {
  if constexpr (!kForm.periodic) {
    if (a.touch_rows != nullptr) return stage_touching_rows<V, kForm>(a, s, i0, limit, n);
  }
  return stage_touching<V, kForm>(a, s, i0, limit, n);
}

// Stage 2: the law over the n staged pairs, eight at a time; the last group's spare lanes repeat its first
// pair.
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE void staged_law(const PairPassArrays<typename V::Law>& a, PairBatch& s, std::uint32_t n) {
  constexpr std::uint32_t kAhead = 16;  // pairs: two groups
  for (std::uint32_t p = 0; p < std::min(kAhead, n); ++p)
    __builtin_prefetch(a.history + static_cast<std::size_t>(s.k[p]) * kHistoryDoubles, 1);
  for (std::uint32_t q = 0; q < n; q += 8) {
    const std::uint32_t valid = std::min<std::uint32_t>(8, n - q);
SPREAD_UNROLL(8)
    for (std::uint32_t l = valid; l < 8; ++l) {
      s.k[q + l] = s.k[q];
      s.i[q + l] = s.i[q];
      s.dist2[q + l] = s.dist2[q];
SPREAD_UNROLL(3)
      for (int c = 0; c < 3; ++c) s.d[c][q + l] = s.d[c][q];
    }
    // The histories (32 bytes per listed pair, megabytes in all) of two groups ahead.
    for (std::uint32_t p = q + kAhead; p < std::min(q + kAhead + 8, n); ++p)
      __builtin_prefetch(a.history + static_cast<std::size_t>(s.k[p]) * kHistoryDoubles, 1);
    eight_pairs<V, kForm>(a, s, q, valid);
  }
}

// Stage 3: the sums of particles [i0, i1), in pair order. The drift form kicks and drifts the particles
// once their sums are complete, eight a register (the rest one at a time): a particle's kick reads only its
// own sums and arrays, and stage 3 of the particles after it in the batch writes neither.
template <class V, PairForm kForm>
SPREAD_CONTACT_INLINE void staged_sums(const PairPassArrays<typename V::Law>& a, PairBatch& s, long long i0, long long i1,
                                       double& moved2) {
  std::uint32_t q = 0;
  const auto particles = static_cast<std::uint32_t>(i1 - i0);
  for (std::uint32_t p = 0; p < particles; ++p) {
    double sum_f[3] = {0.0, 0.0, 0.0}, sum_t[3] = {0.0, 0.0, 0.0};
    for (; q < s.particle_end[p]; ++q) {
      a.held[s.k[q]] = 1;
      if (a.near_held != nullptr) a.near_held[s.e[q]] = 1;
      PairSum& sj = a.sums[s.j[q]];
SPREAD_UNROLL(3)
      for (int c = 0; c < 3; ++c) {
        sum_f[c] += s.f[c][q];
        sj.f[c] -= s.f[c][q];
      }
      if constexpr (V::kRotation)
SPREAD_UNROLL(3)
        for (int c = 0; c < 3; ++c) {
          sum_t[c] += s.t_i[c][q];
          sj.t[c] += s.t_j[c][q];
        }
    }
    if constexpr (kForm.drift) {
      PairSum& si = a.sums[static_cast<std::size_t>(i0 + p)];
SPREAD_UNROLL(3)
      for (int c = 0; c < 3; ++c) {
        s.total_f[c][p] = si.f[c] + sum_f[c];
        if constexpr (V::kRotation) s.total_t[c][p] = si.t[c] + sum_t[c];
      }
      si = PairSum{};
    } else {
      finish_sums<V, kForm>(a, static_cast<std::size_t>(i0 + p), sum_f, sum_t, moved2);
    }
  }
  if constexpr (kForm.drift) {
    lanes::Lanes8 moved8 = splat<lanes::Lanes8>(0.0);
    std::uint32_t p = 0;
    for (; p + 8 <= particles; p += 8) {
      const double* const total_f[3] = {s.total_f[0] + p, s.total_f[1] + p, s.total_f[2] + p};
      const double* const total_t[3] = {s.total_t[0] + p, s.total_t[1] + p, s.total_t[2] + p};
      kick_twice_and_drift8<V::kRotation>(a, static_cast<std::size_t>(i0 + p), total_f, total_t, moved8);
    }
SPREAD_UNROLL(8)
    for (int l = 0; l < 8; ++l) moved2 = std::max(moved2, moved8[l]);
    for (; p < particles; ++p) {
      const double total_f[3] = {s.total_f[0][p], s.total_f[1][p], s.total_f[2][p]};
      double total_t[3] = {0.0, 0.0, 0.0};
      if constexpr (V::kRotation) for (int c = 0; c < 3; ++c) total_t[c] = s.total_t[c][p];
      kick_twice_and_drift<V::kRotation>(a, static_cast<std::size_t>(i0 + p), total_f, total_t, moved2);
    }
  }
}

template <class V, PairForm kForm>
__attribute__((target("avx512f"))) SPREAD_CONTACT_FLATTEN double pair_pass_batched_avx512(PairPassArrays<typename V::Law> a,
                                                                                         long long count) {
  static_assert(!kForm.store_pairs, "the batched pass adds the sums directly");
  PairBatch s;
  double moved2 = 0.0;
  long long i0 = 0;
  while (i0 < count) {
    std::uint32_t n = 0;
    const long long i1 = stage_batch<V, kForm>(a, s, i0, count, n);
    if (i1 == i0) {  // a list longer than the batch: that particle alone, by the portable pass
      moved2 = std::max(moved2, pair_pass_portable<V, kForm>(a, i0, i0 + 1, 1));
      ++i0;
      continue;
    }
    staged_law<V, kForm>(a, s, n);
    staged_sums<V, kForm>(a, s, i0, i1, moved2);
    i0 = i1;
  }
  return moved2;
}

// Until `turn` reaches t: a short spin, then the core given up between looks (with more threads than cores
// the thread awaited may need this one's core).
inline void wait_for_turn(const std::atomic<int>& turn, int t) {
  for (int spins = 0; turn.load(std::memory_order_acquire) != t; ++spins) {
    if (spins < 256) __builtin_ia32_pause();
    else std::this_thread::yield();
  }
}

// The batched pass on several threads, the same bits as on one. Thread t takes the t-th of `threads`
// consecutive ranges of particles (about equal in listed pairs) and runs stages 1 and 2 over its range
// batch by batch; stage 3 — the only one that adds into sums another range reads (a pair's second body may
// lie in a later range) — runs range after range, in order, so every sum is added to in pair order. Until
// the ranges before its own are summed, a thread keeps its batches (stages 1 and 2 done) and goes on; then
// it sums those and the rest of its range as it goes. Staging reads only particles from the batch's first
// on (every pair's second body comes after its first), which stage 3 of earlier particles never writes.
template <class V, PairForm kForm>
__attribute__((target("avx512f"))) SPREAD_CONTACT_FLATTEN double pair_pass_batched_threads_avx512(PairPassArrays<typename V::Law> a,
                                                                                                 long long count, int threads) {
  static_assert(!kForm.store_pairs, "the batched pass adds the sums directly");
  std::vector<long long> range_start(static_cast<std::size_t>(threads) + 1, count);
  {
    // Range t starts at the first particle whose list starts at or past t/threads of the listed pairs; the
    // list starts ascend, so a bisection finds it.
    const auto listed_before = [&](long long i) {
      return static_cast<long long>(pairs_of(a, static_cast<std::size_t>(i)).begin - pairs_of(a, 0).begin);
    };
    const long long listed = pairs_of(a, static_cast<std::size_t>(count - 1)).end - pairs_of(a, 0).begin;
    range_start[0] = 0;
    for (int t = 1; t < threads; ++t) {
      long long lo = range_start[t - 1], hi = count;  // the answer lies in [lo, hi]
      while (lo < hi) {
        const long long mid = lo + (hi - lo) / 2;
        if (listed_before(mid) * threads >= listed * t) hi = mid;
        else lo = mid + 1;
      }
      range_start[t] = lo;
    }
  }
  std::atomic<int> turn{0};
  double moved2 = 0.0;
#pragma omp parallel num_threads(threads) firstprivate(a) reduction(max : moved2)
  {
    // Range t for thread t; a team smaller than asked for (or no OpenMP) takes the ranges in turn.
    for (int t = detail::thread_index(); t < threads; t += detail::thread_count()) {
      // Batches staged while earlier ranges were not yet summed: [0, kept) of `kept_batches`, with their
      // particles [kept_start[b], kept_start[b + 1]). Kept across steps (a few MB: no page faults per step).
      thread_local std::vector<PairBatch> kept_batches;
      thread_local std::vector<long long> kept_start;
      std::size_t kept = 0;
      kept_start.assign(1, range_start[t]);
      bool my_turn = t == 0;
      auto sum_kept = [&] {
        for (std::size_t b = 0; b < kept; ++b) staged_sums<V, kForm>(a, kept_batches[b], kept_start[b], kept_start[b + 1], moved2);
        kept = 0;
      };
      PairBatch own;
      const long long end = range_start[t + 1];
      for (long long i0 = range_start[t]; i0 < end;) {
        if (!my_turn && turn.load(std::memory_order_acquire) == t) {
          my_turn = true;
          sum_kept();
        }
        if (!my_turn && kept_batches.size() <= kept) kept_batches.resize(kept + 1);
        PairBatch& s = my_turn ? own : kept_batches[kept];
        std::uint32_t n = 0;
        long long i1 = stage_batch<V, kForm>(a, s, i0, end, n);
        if (i1 == i0) {  // a list longer than the batch: that particle alone, by the portable pass, in its turn
          wait_for_turn(turn, t);
          my_turn = true;
          sum_kept();
          moved2 = std::max(moved2, pair_pass_portable<V, kForm>(a, i0, i0 + 1, 1));
          i0 += 1;
          continue;
        }
        staged_law<V, kForm>(a, s, n);
        if (my_turn) {
          staged_sums<V, kForm>(a, s, i0, i1, moved2);
        } else {
          ++kept;
          kept_start.resize(kept + 1);
          kept_start[kept] = i1;
        }
        i0 = i1;
      }
      wait_for_turn(turn, t);
      sum_kept();
      turn.store(t + 1, std::memory_order_release);
    }
  }
  return moved2;
}
#endif

// Where the processor has AVX-512: the stored form is the particle-by-particle pass compiled for it (the
// law's lanes two doubles wide, 32 vector registers instead of 16, less of a contact's state spilled), the
// direct form the batched pass (eight pairs a register; on several threads, a range of particles each).
// The same bits either way
// (DemPairPass.WidestRegistersGiveIdenticalStates; docs/drum.md "Where the time goes"). Returns the largest
// squared move since the near list's build where the pass drifted the particles (a.drift_dt_s), else 0.
template <class V, PairForm kForm>
double pair_pass(PairPassArrays<typename V::Law> a, long long count, int threads) {
#if defined(__x86_64__) || defined(__i386__)
  if (cpu_has_avx512f()) {
    if constexpr (!kForm.store_pairs) {
      if (threads > 1 && count >= kMinParallelItems) return pair_pass_batched_threads_avx512<V, kForm>(a, count, threads);
      return pair_pass_batched_avx512<V, kForm>(a, count);
    }
    return pair_pass_avx512<V, kForm>(a, count, threads);
  }
#endif
  return pair_pass_portable<V, kForm>(a, 0, count, threads);
}

#if defined(__x86_64__) || defined(__i386__)
// `count` doubles of `storage` from an `align`-byte boundary (one row per load), grown when short; fresh
// storage holds no rows, so `kept` is cleared then.
double* aligned_rows(std::vector<double>& storage, std::size_t count, std::size_t align, bool& kept) {
  const std::size_t pad = align / sizeof(double);
  if (storage.size() < count + pad) {
    storage.resize(count + pad);
    kept = false;
  }
  const auto address = reinterpret_cast<std::uintptr_t>(storage.data());
  return storage.data() + (align - address % align) % align / sizeof(double);
}
#endif

}  // namespace

template <class V>
void DemEngine::particle_forces() {
  using Law = typename V::Law;
  const std::size_t n = p_.size();
  if (pair_sum_.size() != n) pair_sum_.assign(n, PairSum{});
  // Per-pair results are stored (and gathered in a second pass) when threads share the pairs or an
  // energy monitor reads them; one thread adds them straight into the sums. Same sums, same order.
  // Where the batched pass runs (AVX-512) several threads add them straight into the sums too: it keeps
  // the order of the additions for any thread count (pair_pass_batched_threads_avx512).
  bool batched = false;
#if defined(__x86_64__) || defined(__i386__)
  batched = cpu_has_avx512f();
#endif
  const bool shared = threads_share_pairs();
  const bool store = (shared && !batched) || monitor_ != nullptr;
  if (store) prepare_stored_pairs(n, pairs_);
  constexpr bool with_spin = V::kRotation;
  PairPassArrays<Law> a{
      p_.x.data(), p_.y.data(), p_.z.data(), p_.vx.data(), p_.vy.data(), p_.vz.data(),
      with_spin ? p_.wx.data() : nullptr, with_spin ? p_.wy.data() : nullptr, with_spin ? p_.wz.data() : nullptr,
      p_.radius_m.data(), p_.mass_kg.data(), p_.inertia_kg_m2.data(), p_.material.data(), p_.active.data(),
      pairs_.first_start.data(), pairs_.second.data(), pairs_.history.data(), pairs_.held.data(), pairs_.force.data(),
      pairs_.torque_first.data(), pairs_.torque_second.data(), pair_sum_.data(), p_.fx.data(), p_.fy.data(),
      p_.fz.data(), with_spin ? p_.tx.data() : nullptr, with_spin ? p_.ty.data() : nullptr,
      with_spin ? p_.tz.data() : nullptr, &pair_table_(0, 0), coeffs_table<Law>(pair_coeffs_),
      pair_table_.material_count(), params_.periodic_z.length_m(), dt_s_, kick_in_pass_dt_s_,
      {params_.gravity_m_s2.x(), params_.gravity_m_s2.y(), params_.gravity_m_s2.z()}, p_.inv_mass_kg.data(),
      with_spin ? p_.inv_inertia_kg_m2.data() : nullptr, {p_.vx.data(), p_.vy.data(), p_.vz.data()},
      {with_spin ? p_.wx.data() : nullptr, with_spin ? p_.wy.data() : nullptr, with_spin ? p_.wz.data() : nullptr},
      nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, 0.0, false, {nullptr, nullptr, nullptr}, nullptr, nullptr, nullptr};
  const long long count = static_cast<long long>(n);
  const bool periodic = params_.periodic_z.enabled;
  if (!store && near_.start.size() == n + 1) {
    a.near_start = near_.start.data();
    a.near_pairs = near_.pairs.data();
#if defined(__x86_64__) || defined(__i386__)
    // The batched pass's touch test reads each body's x, y, z, r in one load (r NaN: inactive, never touching).
    // Kept by the last pass's drift (the steps between: nothing else moved a particle), else written here.
    // Only where the law runs in eight-pair registers anyway: on a processor that lowers its clock for
    // 512-bit instructions, a pass of scalar laws (sizes mixed within a material) with this test in 512-bit
    // registers made the disc's whole step slower (bench_dem: 0.634–0.651 s → 0.703–0.707 s).
    if (batched && !periodic && one_size_per_material_ && near_.first.size() == near_.pairs.size()) {
      double* const rows = aligned_rows(touch_rows_, 4 * n, 32, touch_rows_kept_);
      double* const law_rows = aligned_rows(law_rows_, 8 * n, 64, touch_rows_kept_);
      for (std::size_t i = 0; i < (touch_rows_kept_ ? 0 : n); ++i) {
        rows[4 * i] = p_.x[i];
        rows[4 * i + 1] = p_.y[i];
        rows[4 * i + 2] = p_.z[i];
        rows[4 * i + 3] = p_.active[i] ? p_.radius_m[i] : std::numeric_limits<double>::quiet_NaN();
        double* const row = law_rows + 8 * i;
        row[0] = p_.vx[i];
        row[1] = p_.vy[i];
        row[2] = p_.vz[i];
        row[3] = with_spin ? p_.wx[i] : 0.0;
        row[4] = with_spin ? p_.wy[i] : 0.0;
        row[5] = with_spin ? p_.wz[i] : 0.0;
        row[6] = p_.radius_m[i];
        row[7] = p_.inertia_kg_m2[i];
      }
      a.law_rows = law_rows;
      if (!near_.held_synced) {
        for (std::size_t e = 0; e < near_.pairs.size(); ++e) near_.held[e] = pairs_.held[near_.pairs[e]];
        near_.held_synced = true;
      }
      a.touch_rows = rows;
      a.near_first = near_.first.data();
      a.near_held = near_.held.data();
      a.near_second = near_.second.data();
    }
#endif
  }
  kicked_in_pass_ = kick_in_pass_dt_s_ != 0.0;
  touch_rows_kept_ = false;
  if (a.touch_rows == nullptr) near_.held_synced = false;  // this pass updates the pairs' held bytes only
  // The next step's opening kick and drift (steps()) go with the direct pass's closing kick; the stored
  // form kicks in its gather, and a periodic axis wraps between the steps.
  const bool drift = fuse_next_step_ && kicked_in_pass_ && !store && !periodic;
  const bool measure_near = near_.x0.size() == n;
  if (drift) {
    a.drift_dt_s = dt_s_;
    a.drift_clears_sums = opening_kick_clears_sums();
    a.position[0] = p_.x.data();
    a.position[1] = p_.y.data();
    a.position[2] = p_.z.data();
    if (measure_near) {
      a.x0 = near_.x0.data();
      a.y0 = near_.y0.data();
      a.z0 = near_.z0.data();
    }
  }
  if (store) {
    if (periodic) pair_pass<V, PairForm{true, true, false}>(a, count, params_.threads);
    else pair_pass<V, PairForm{true, false, false}>(a, count, params_.threads);
    gather_stored_pair_forces<V::kRotation>();
  } else {
    const int threads = shared ? params_.threads : 1;
    double moved2 = 0.0;
    if (periodic) pair_pass<V, PairForm{false, true, false}>(a, count, threads);
    else if (drift) moved2 = pair_pass<V, PairForm{false, false, true}>(a, count, threads);
    else pair_pass<V, PairForm{false, false, false}>(a, count, threads);
    if (drift) {
      drifted_in_pass_ = true;
      touch_rows_kept_ = a.touch_rows != nullptr;
      sums_cleared_ = a.drift_clears_sums;
      moved2_since_near_ = measure_near ? moved2 : -1.0;
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
SPREAD_UNROLL(3)
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
    if (kick_in_pass_dt_s_ != 0.0 && p_.active[i]) {  // as kick_particle
      const double dt = kick_in_pass_dt_s_, inv_m = p_.inv_mass_kg[i];
      const Vec3& g = params_.gravity_m_s2;
      p_.vx[i] += dt * (p_.fx[i] * inv_m + g.x());
      p_.vy[i] += dt * (p_.fy[i] * inv_m + g.y());
      p_.vz[i] += dt * (p_.fz[i] * inv_m + g.z());
      if constexpr (kRotation) {
        const double inv_i = p_.inv_inertia_kg_m2[i];
        p_.wx[i] += dt * p_.tx[i] * inv_i;
        p_.wy[i] += dt * p_.ty[i] * inv_i;
        p_.wz[i] += dt * p_.tz[i] * inv_i;
      }
    }
  }
}

const ForcePassTable kParticlePasses = ForcePassTables::particle(std::make_index_sequence<kForceVariantCount>{});

}  // namespace spread::dem
