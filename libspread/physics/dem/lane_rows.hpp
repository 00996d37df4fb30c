#pragma once
// Eight-lane rows for the AVX-512 pair pass and its kicks: eight values into one register, rows of four or
// eight doubles transposed in registers, and back. Plain vector-extension code, used only inside functions
// compiled for AVX-512 (pair_pass_avx512.hpp, pair_kicks.hpp).
#include <cstddef>
#include <cstdint>

#include "libspread/physics/dem/contact_kernel.hpp"
#include "libspread/physics/dem/lanes.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace spread::dem::pairs {

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

}  // namespace spread::dem::pairs

#pragma GCC diagnostic pop
