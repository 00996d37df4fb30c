#pragma once
// The batched pair pass, written once over the lane type L (lanes.hpp): Lanes8 in AVX-512 registers
// (pair_pass_avx512.hpp), Lanes4 in AVX2 registers or, portable, two SSE2 registers each. The touching pairs
// of consecutive particles are staged (stage 1), the law runs over them W at a time, pairs of different first
// bodies side by side (stage 2), and the sums are added in pair order afterwards (stage 3). A pair's law reads
// only the state and its own history, never a sum, and lane by lane every operation is the scalar one, so the
// bits are those of the particle-by-particle pass for every W (DemPairPass.EveryRegisterWidthGivesTheSameBits).
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/engine_detail.hpp"
#include "libspread/physics/dem/lane_rows.hpp"
#include "libspread/physics/dem/pair_kicks.hpp"
#include "libspread/physics/dem/pair_pass_context.hpp"
#include "libspread/physics/dem/pair_pass_stages.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace spread::dem::pairs {

// The lanes of L (lanes.hpp: Lanes8, Lanes4, Lanes2).
template <class L>
inline constexpr int kLanes = static_cast<int>(sizeof(L) / sizeof(double));

// W values base[index[l]] in one value; eight as lane_rows.hpp loads them (two a load, halves joined).
template <class L>
SPREAD_CONTACT_INLINE L gather_lanes(const double* base, const std::uint32_t* index) {
  if constexpr (kLanes<L> == 8) {
    return gather_lanes8(base, index);
  } else {
    L v;
SPREAD_UNROLL(4)
    for (int l = 0; l < kLanes<L>; ++l) v[l] = base[index[l]];
    return v;
  }
}
template <class L>
SPREAD_CONTACT_INLINE L load_lanes(const double* p) {
  L v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
template <class L>
SPREAD_CONTACT_INLINE void store_lanes(double* p, L v) {
  __builtin_memcpy(p, &v, sizeof v);
}
// W pairs' histories (kHistoryDoubles each) as kHistoryDoubles values, slot by slot, and back for the first
// `valid` lanes; eight transposed in registers (lane_rows.hpp).
template <class L>
SPREAD_CONTACT_INLINE void load_histories(double* const (&rows)[kLanes<L>], L (&slot)[kHistoryDoubles]) {
  if constexpr (kLanes<L> == 8) {
    load_rows8(rows, slot);
  } else {
SPREAD_UNROLL(4)
    for (int c = 0; c < kHistoryDoubles; ++c)
SPREAD_UNROLL(4)
      for (int l = 0; l < kLanes<L>; ++l) slot[c][l] = rows[l][c];
  }
}
template <class L>
SPREAD_CONTACT_INLINE void store_histories(const L (&slot)[kHistoryDoubles], double* const (&rows)[kLanes<L>],
                                           std::uint32_t valid) {
  if constexpr (kLanes<L> == 8) {
    store_histories8(slot, rows, valid);
  } else {
    for (std::uint32_t l = 0; l < valid; ++l)
SPREAD_UNROLL(4)
      for (int c = 0; c < kHistoryDoubles; ++c) rows[l][c] = slot[c][l];
  }
}
// Whether the law reads the bodies from their law rows: eight lanes, and the pass has the rows.
template <class L, class Law>
SPREAD_CONTACT_INLINE bool law_rows_for(const PairPassArrays<Law>& a) {
  return kLanes<L> == 8 && a.law_rows != nullptr;
}
template <class L>
SPREAD_CONTACT_INLINE void load_law_rows(const double* const (&rows)[kLanes<L>], L (&col)[8]) {
  if constexpr (kLanes<L> == 8) load_rows8x8(rows, col);
}

// The batched pass (one thread, sums added directly): the touching pairs of consecutive particles are
// staged, the law runs over them W at a time in lanes — eight in AVX-512 registers, four in AVX2 registers or,
// portable, in pairs of SSE2 registers; pairs of different first bodies side by side — and the results are
// added in pair order afterwards. A pair's law reads only the state
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

// Staged pairs [q, q + W) (W = the lanes of L): one material pair whose table entry holds (both materials of
// one size), W pairs in lanes; otherwise each alone. Lanes past `valid` repeat pair q and are not written back.
template <class V, PairForm kForm, class L>
SPREAD_CONTACT_INLINE void lane_pairs(const PairPassArrays<typename V::Law>& a, PairBatch& s, std::uint32_t q,
                                      std::uint32_t valid) {
  using Law = typename V::Law;
  constexpr int W = kLanes<L>;
  std::uint32_t* const j = s.j + q;
SPREAD_UNROLL(8)
  for (int l = 0; l < W; ++l) {
    j[l] = a.partner[s.k[q + l]];
    // Stage 3 adds into j's sums, which a later particle finished a step ago: likely out of L2 by now.
    __builtin_prefetch(a.sums + j[l], 1);
  }
  bool one_entry = true;
  std::size_t entry = 0;
  if (a.material_count > 1) {
    const std::uint16_t mi = a.material[s.i[q]], mj = a.material[j[0]];
SPREAD_UNROLL(8)
    for (int l = 1; l < W; ++l) one_entry &= (a.material[s.i[q + l]] == mi) & (a.material[j[l]] == mj);
    entry = static_cast<std::size_t>(mi) * a.material_count + mj;
  }
  if (!one_entry || !a.coeffs[entry].uniform) {
    staged_pairs_alone<V, kForm>(a, s, q, valid);
    return;
  }
  const std::uint32_t* i = s.i + q;
  // Each body's v, ω, r, I: from its law row where the pass has them (eight lanes), else lane by lane from
  // the arrays.
  L body_i[8], body_j[8];
  if (law_rows_for<L>(a)) {
    const double* rows_i[W];
    const double* rows_j[W];
SPREAD_UNROLL(8)
    for (int l = 0; l < W; ++l) {
      rows_i[l] = a.law_rows + 8 * static_cast<std::size_t>(i[l]);
      rows_j[l] = a.law_rows + 8 * static_cast<std::size_t>(j[l]);
    }
    load_law_rows<L>(rows_i, body_i);
    load_law_rows<L>(rows_j, body_j);
  } else {
    const double* const arrays[8] = {a.vx, a.vy, a.vz, a.wx, a.wy, a.wz, a.radius, a.inertia};
SPREAD_UNROLL(8)
    for (int c = 0; c < 8; ++c) {
      const bool needed = c < 3 || (c < 6 && V::kRotation) || c == 6 || (c == 7 && Law::kRolling);
      body_i[c] = needed ? gather_lanes<L>(arrays[c], i) : splat<L>(0.0);
      body_j[c] = needed ? gather_lanes<L>(arrays[c], j) : splat<L>(0.0);
    }
  }
  const V3<L> v_rel{body_i[0] - body_j[0], body_i[1] - body_j[1], body_i[2] - body_j[2]};
  V3<L> wi = lanes::zero3<L>(), wj = lanes::zero3<L>();
  if constexpr (V::kRotation) {
    wi = V3<L>{body_i[3], body_i[4], body_i[5]};
    wj = V3<L>{body_j[3], body_j[4], body_j[5]};
  }
  L inertia_eff = splat<L>(0.0);
  if constexpr (Law::kRolling) inertia_eff = body_i[7] * body_j[7] / (body_i[7] + body_j[7]);
  double* hist[W];
SPREAD_UNROLL(8)
  for (int l = 0; l < W; ++l) hist[l] = a.history + static_cast<std::size_t>(s.k[q + l]) * kHistoryDoubles;
  L h_in[kHistoryDoubles];
  load_histories<L>(hist, h_in);
  LawHistory<L> h{{h_in[0], h_in[1], h_in[2]}, h_in[3]};
  const PairOut<L> r = pair_contact<V>(
      V3<L>{load_lanes<L>(s.d[0] + q), load_lanes<L>(s.d[1] + q), load_lanes<L>(s.d[2] + q)}, load_lanes<L>(s.dist2 + q),
      body_i[6], body_j[6], v_rel, wi, wj, inertia_eff, a.params[entry], a.coeffs[entry],
      a.dt_s, h);
  const L h_out[kHistoryDoubles] = {h.elastic.x, h.elastic.y, h.elastic.z, h.overlap_m};
  store_histories<L>(h_out, hist, valid);
  const V3<L>* outs[3] = {&r.f, &r.t_i, &r.t_j};
  double(*slots[3])[PairBatch::kSlots] = {s.f, s.t_i, s.t_j};
SPREAD_UNROLL(3)
  for (int o = 0; o < 3; ++o) {
    store_lanes<L>(slots[o][0] + q, outs[o]->x);
    store_lanes<L>(slots[o][1] + q, outs[o]->y);
    store_lanes<L>(slots[o][2] + q, outs[o]->z);
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


// Stage 2: the law over the n staged pairs, W at a time; the last group's spare lanes repeat its first pair.
template <class V, PairForm kForm, class L>
SPREAD_CONTACT_INLINE void staged_law(const PairPassArrays<typename V::Law>& a, PairBatch& s, std::uint32_t n) {
  constexpr std::uint32_t W = kLanes<L>;
  constexpr std::uint32_t kAhead = 16;  // pairs: two groups
  for (std::uint32_t p = 0; p < std::min(kAhead, n); ++p)
    __builtin_prefetch(a.history + static_cast<std::size_t>(s.k[p]) * kHistoryDoubles, 1);
  for (std::uint32_t q = 0; q < n; q += W) {
    const std::uint32_t valid = std::min<std::uint32_t>(W, n - q);
SPREAD_UNROLL(8)
    for (std::uint32_t l = valid; l < W; ++l) {
      s.k[q + l] = s.k[q];
      s.i[q + l] = s.i[q];
      s.dist2[q + l] = s.dist2[q];
SPREAD_UNROLL(3)
      for (int c = 0; c < 3; ++c) s.d[c][q + l] = s.d[c][q];
    }
    // The histories (32 bytes per listed pair, megabytes in all) of two groups ahead.
    for (std::uint32_t p = q + kAhead; p < std::min(q + kAhead + W, n); ++p)
      __builtin_prefetch(a.history + static_cast<std::size_t>(s.k[p]) * kHistoryDoubles, 1);
    lane_pairs<V, kForm, L>(a, s, q, valid);
  }
}

// Stage 3: the sums of particles [i0, i1), in pair order. The drift form kicks and drifts the particles
// once their sums are complete, eight a register with eight lanes (the rest, and with fewer lanes all, one at a
// time): a particle's kick reads only its own sums and arrays, and stage 3 of the particles after it in the
// batch writes neither.
template <class V, PairForm kForm, class L>
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
    std::uint32_t p = 0;
    if constexpr (kLanes<L> == 8) {
      lanes::Lanes8 moved8 = splat<lanes::Lanes8>(0.0);
      for (; p + 8 <= particles; p += 8) {
        const double* const total_f[3] = {s.total_f[0] + p, s.total_f[1] + p, s.total_f[2] + p};
        const double* const total_t[3] = {s.total_t[0] + p, s.total_t[1] + p, s.total_t[2] + p};
        kick_twice_and_drift8<V::kRotation>(a, static_cast<std::size_t>(i0 + p), total_f, total_t, moved8);
      }
SPREAD_UNROLL(8)
      for (int l = 0; l < 8; ++l) moved2 = std::max(moved2, moved8[l]);
    }
    for (; p < particles; ++p) {
      const double total_f[3] = {s.total_f[0][p], s.total_f[1][p], s.total_f[2][p]};
      double total_t[3] = {0.0, 0.0, 0.0};
      if constexpr (V::kRotation) for (int c = 0; c < 3; ++c) total_t[c] = s.total_t[c][p];
      kick_twice_and_drift<V::kRotation>(a, static_cast<std::size_t>(i0 + p), total_f, total_t, moved2);
    }
  }
}


}  // namespace spread::dem::pairs

#pragma GCC diagnostic pop
