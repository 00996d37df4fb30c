#pragma once
// The pair pass where the processor has AVX-512: the particle-by-particle pass compiled for it (the stored
// form), and the batched pass (the direct form): the touching pairs of many particles staged, the law over
// eight at a time in one register, the sums in pair order afterwards (the same bits as the portable pass);
// on several threads pair_pass_batched_threads_avx512, the sums still added in pair order.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/engine_detail.hpp"
#include "libspread/physics/dem/lane_rows.hpp"
#include "libspread/physics/dem/pair_kicks.hpp"
#include "libspread/physics/dem/pair_pass_context.hpp"
#include "libspread/physics/dem/pair_pass_stages.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace spread::dem::pairs {

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

}  // namespace spread::dem::pairs

#pragma GCC diagnostic pop
