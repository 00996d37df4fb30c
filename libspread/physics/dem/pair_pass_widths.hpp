#pragma once
// The batched pair pass's entry for each register width, chosen at run time (pair_pass.cpp): eight lanes in
// AVX-512 registers, four in AVX2 registers, and the portable one, four lanes in two SSE2 registers each
// (any processor the baseline runs on). Each is the one pass of pair_pass_batched.hpp compiled for its
// registers (flatten: everything inlined into it, with its target); the same bits for every width.
#include <algorithm>
#include <cstdint>

#include "libspread/physics/dem/lanes.hpp"
#include "libspread/physics/dem/pair_pass_avx512.hpp"
#include "libspread/physics/dem/pair_pass_batched.hpp"
#include "libspread/physics/dem/pair_pass_context.hpp"
#include "libspread/physics/dem/pair_pass_stages.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace spread::dem::pairs {

// Stage 1 for W lanes: with eight (AVX-512) stage_batch (the touch rows where the pass has them), else entry
// by entry.
template <class V, PairForm kForm, class L>
SPREAD_CONTACT_INLINE long long stage_for(const PairPassArrays<typename V::Law>& a, PairBatch& s, long long i0, long long limit,
                                          std::uint32_t& n) {
#if defined(__x86_64__) || defined(__i386__)
  if constexpr (kLanes<L> == 8) return stage_batch<V, kForm>(a, s, i0, limit, n);
#endif
  return stage_touching<V, kForm>(a, s, i0, limit, n);
}

// The batched pass over particles [0, count) with W lanes; stage 1 from the touch rows (eight entries a
// register, stage_batch) where the lanes are eight, else entry by entry.
template <class V, PairForm kForm, class L>
SPREAD_CONTACT_INLINE double batched_pass(PairPassArrays<typename V::Law>& a, long long count) {
  static_assert(!kForm.store_pairs, "the batched pass adds the sums directly");
  PairBatch s;
  double moved2 = 0.0;
  long long i0 = 0;
  while (i0 < count) {
    std::uint32_t n = 0;
    const long long i1 = stage_for<V, kForm, L>(a, s, i0, count, n);
    if (i1 == i0) {  // a list longer than the batch: that particle alone, by the portable pass
      moved2 = std::max(moved2, pair_pass_portable<V, kForm>(a, i0, i0 + 1, 1));
      ++i0;
      continue;
    }
    staged_law<V, kForm, L>(a, s, n);
    staged_sums<V, kForm, L>(a, s, i0, i1, moved2);
    i0 = i1;
  }
  return moved2;
}

#if defined(__x86_64__) || defined(__i386__)
template <class V, PairForm kForm>
__attribute__((target("avx512f"))) SPREAD_CONTACT_FLATTEN double pair_pass_batched_avx512(PairPassArrays<typename V::Law> a,
                                                                                         long long count) {
  return batched_pass<V, kForm, lanes::Lanes8>(a, count);
}
template <class V, PairForm kForm>
__attribute__((target("avx2"))) SPREAD_CONTACT_FLATTEN double pair_pass_batched_avx2(PairPassArrays<typename V::Law> a,
                                                                                     long long count) {
  return batched_pass<V, kForm, lanes::Lanes4>(a, count);
}
#endif
template <class V, PairForm kForm>
SPREAD_CONTACT_FLATTEN double pair_pass_batched_portable(PairPassArrays<typename V::Law> a, long long count) {
  return batched_pass<V, kForm, lanes::Lanes4>(a, count);
}

}  // namespace spread::dem::pairs

#pragma GCC diagnostic pop
