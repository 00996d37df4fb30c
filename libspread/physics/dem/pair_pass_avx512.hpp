#pragma once
// The pair pass where the processor has AVX-512: the particle-by-particle pass compiled for it (the stored
// form), the batched pass's stage 1 eight near entries a register from the touch rows (stage_batch; the
// batched pass itself, written over the lanes, is pair_pass_batched.hpp, its entry per width
// pair_pass_widths.hpp), and the batched pass on several threads (pair_pass_batched_threads_avx512, the sums
// still added in pair order).
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
#include "libspread/physics/dem/pair_pass_batched.hpp"
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
// Not forced inline: the generic batched pass (batched_pass, pair_pass_widths.hpp) calls it, and a function
// of the default target may not force in one of AVX-512's; flatten in the AVX-512 pass inlines it there.
#define SPREAD_ROWS_CALLER __attribute__((target("avx512f"))) inline
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
        for (std::size_t b = 0; b < kept; ++b) staged_sums<V, kForm, lanes::Lanes8>(a, kept_batches[b], kept_start[b], kept_start[b + 1], moved2);
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
        staged_law<V, kForm, lanes::Lanes8>(a, s, n);
        if (my_turn) {
          staged_sums<V, kForm, lanes::Lanes8>(a, s, i0, i1, moved2);
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
