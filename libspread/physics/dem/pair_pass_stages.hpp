#pragma once
// The pair pass's portable stages, per particle i: the touching pairs of a chunk of its list
// (touching_in_chunk), the contact law over them two at a time (SSE2 lanes) or one (law_over_touching),
// and i's finished sums (finish_particle, with the kicks of pair_kicks.hpp). Newton's third law (seed Eq. 1)
// is applied per pair, so each pair's law runs once. pair_pass_portable runs them particle by particle.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/engine_detail.hpp"
#include "libspread/physics/dem/pair_kicks.hpp"
#include "libspread/physics/dem/pair_pass_context.hpp"

// The contact laws' templates take eight-lane values here, inlined into the AVX-512 pass only (lanes.hpp).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace spread::dem::pairs {

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

}  // namespace spread::dem::pairs

#pragma GCC diagnostic pop
