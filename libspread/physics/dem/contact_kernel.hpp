#pragma once
// What every contact law's kernel works with (contact_laws.hpp puts the sub-models together): the
// contact's input and output in Eigen types (single contacts, walls) and in the kernel's lane types
// (lanes.hpp), the per-contact tangential history of kHistoryDoubles doubles stored in flat arrays by the
// caller (no heap object per contact), and the two tangential helpers the tangential models share.
//
// Conventions for one contact between body a (always a particle) and body b (particle or wall):
//   normal      unit vector from b towards a — the direction of the repulsive force on a (seed Eq. 1)
//   overlap_m   δ_n = R_a + R_b − |r_ab| > 0 (Eq. 4); walls: R_a − distance
//   slip_m_s    velocity of a's contact point minus b's contact point (Eq. 8); δ̇_n = −slip·normal
// The force returned acts on a; b receives its opposite.
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>  // cross products

#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/lanes.hpp"

// The laws run once per touching pair per step inside the pair loop; GCC's size heuristics at -O2 leave
// them (and their helpers) as calls, which costs more than the arithmetic. Forced inline there.
// SPREAD_CONTACT_FLATTEN marks the loop that calls them: everything it calls is inlined into it.
#if defined(__GNUC__)
#define SPREAD_CONTACT_INLINE inline __attribute__((always_inline))
#define SPREAD_CONTACT_FLATTEN __attribute__((flatten))
#else
#define SPREAD_CONTACT_INLINE inline
#define SPREAD_CONTACT_FLATTEN
#endif
// SPREAD_UNROLL(n) before a short loop of constant count (lanes, components, history slots): unrolled
// completely, so that what it indexes stays in registers. GCC at -O2 unrolls a loop completely only when the
// code does not grow, and left such loops in the pair pass with their values on the stack. Clang builds
// only the sanitizer build here and is left to its own unrolling: with the pragma, pair_pass.cpp took 122 s
// to compile under the sanitizers instead of 104 s.
#if defined(__GNUC__) && !defined(__clang__)
#define SPREAD_PRAGMA(text) _Pragma(#text)
#define SPREAD_UNROLL(n) SPREAD_PRAGMA(GCC unroll n)
#else
#define SPREAD_UNROLL(n)
#endif

namespace spread::dem {

struct ContactInput {
  Vec3 normal = Vec3::UnitZ();
  double overlap_m = 0.0;
  Vec3 slip_m_s = Vec3::Zero();
  double r_eff_m = 0.0;   // R* = (1/R_a + 1/R_b)^-1; walls: R_a
  double m_eff_kg = 0.0;  // M* = (1/m_a + 1/m_b)^-1; walls: m_a
  double dt_s = 0.0;
};

// What a sub-model's per-pair coefficients depend on besides the materials (PairParams): R*, M* and
// √R* (computed once for the sub-models that use it, zero otherwise).
struct PairScales {
  double r_eff_m = 0.0;       // R* = (1/R_a + 1/R_b)^-1; walls: R_a
  double m_eff_kg = 0.0;      // M* = (1/m_a + 1/m_b)^-1; walls: m_a
  double sqrt_r_eff_m0_5 = 0.0;
};

// History slots per contact: elastic tangential force (N, 3 components) and the previous overlap (m).
inline constexpr int kHistoryDoubles = 4;

struct ContactForce {
  Vec3 force_n = Vec3::Zero();             // total force on a
  Vec3 tangential_force_n = Vec3::Zero();  // its tangential part (for the moment, Eq. 15)
  double normal_force_n = 0.0;             // F_n >= 0 (for rolling resistance)
};

// One contact's tangential history in the kernel's types: the elastic tangential force (N) and the
// overlap at the previous step (m). Stored as kHistoryDoubles doubles per contact by the caller.
// The law owns this layout: every pass reads and writes a contact's slots through load/store (and
// clear on release), never by index.
template <class T>
struct LawHistory {
  lanes::V3<T> elastic;
  T overlap_m;
};
inline LawHistory<double> load_history(const double* slots) { return {{slots[0], slots[1], slots[2]}, slots[3]}; }
// Two contacts' histories side by side (lane 0 from slots0, lane 1 from slots1).
inline LawHistory<lanes::Lanes2> load_history(const double* slots0, const double* slots1) {
  using lanes::pack;
  return {{pack(slots0[0], slots1[0]), pack(slots0[1], slots1[1]), pack(slots0[2], slots1[2])}, pack(slots0[3], slots1[3])};
}
inline void store_history(const LawHistory<double>& h, double* slots) {
  slots[0] = h.elastic.x;
  slots[1] = h.elastic.y;
  slots[2] = h.elastic.z;
  slots[3] = h.overlap_m;
}
inline void store_history(const LawHistory<lanes::Lanes2>& h, int lane, double* slots) {
  store_history(LawHistory<double>{lanes::lane3(h.elastic, lane), h.overlap_m[lane]}, slots);
}
// A contact that has come apart: its tangential spring is released.
inline void clear_history(double* slots) {
  for (int k = 0; k < kHistoryDoubles; ++k) slots[k] = 0.0;
}
// What a law returns for body a, in the kernel's types.
template <class T>
struct LawForce {
  lanes::V3<T> force_n;       // total
  lanes::V3<T> tangential_n;  // tangential part (the moment, Eq. 15)
  T normal_force_n;           // F_n >= 0
};

// A contact's normal as the law takes it: the unit normal, and the same direction unnormalised (`axis`,
// any length, with 1/|axis|²). What needs only the direction — the carry-over's projection — works
// from the axis, so it need not wait for the sqrt and reciprocal that normalise it: the pair pass gives
// the pair vector d and 1/|d|², walls give the unit normal twice and 1.
template <class T>
struct ContactNormal {
  lanes::V3<T> unit;
  lanes::V3<T> axis;
  T inv_axis2;
};

namespace detail {
using lanes::V3;
// Carries the stored elastic tangential force into the current tangent plane keeping its magnitude:
// the contact frame turns as the bodies roll and the walls spin. (Zero stays zero.)
// g = f − (f·n) n has |g|² = (1 − x)|f|², x = (f·n)²/|f|²: the magnitude is restored by (1 − x)^{−1/2}.
// Between two steps the normal turns little (x ~ (ω Δt)²), so for x < 1e-4 the series
// 1 + x/2 + 3x²/8 + 5x³/16 (first omitted term 35x⁴/128 < 3e-17) replaces a division and a sqrt that
// sat on the kernel's longest dependency chain; larger turns take the exact ratio.
template <class T>
SPREAD_CONTACT_INLINE V3<T> carry_into_plane(const V3<T>& f, const V3<T>& axis, T inv_axis2) {
  using lanes::splat;
  const T mag2 = squared_norm(f);
  const T f_axis = dot(f, axis);
  const V3<T> g = f - (f_axis * inv_axis2) * axis;
  const T x = (f_axis * f_axis * inv_axis2) / lanes::select(mag2 > splat<T>(0.0), mag2, splat<T>(1.0));
  const auto small = x < splat<T>(1e-4);
  const T series = splat<T>(1.0) + x * (splat<T>(0.5) + x * (splat<T>(0.375) + x * splat<T>(0.3125)));
  if (lanes::all(small)) return g * series;
  const T new2 = squared_norm(g);
  const auto turned = new2 > splat<T>(0.0);
  // A zero new2 (force along the normal, or no force) gives zero; the denominator is kept away from 0
  // so that no lane divides by zero. Each lane takes the branch it would take alone.
  const T exact = lanes::sqrt(mag2 / lanes::select(turned, new2, splat<T>(1.0)));
  return lanes::select(small, g * series, lanes::select(turned, g * exact, lanes::zero3<T>()));
}
template <class T>
SPREAD_CONTACT_INLINE V3<T> carry_into_plane(const V3<T>& f, const V3<T>& unit_normal) {
  return carry_into_plane(f, unit_normal, lanes::splat<T>(1.0));
}
// Coulomb cap (Eq. 6) with the spring shortened to the friction limit on slip (the β = 1 remark of
// Sect. 2.1: the viscous part is disregarded when shortening). The sqrt only when some contact slips.
template <class T>
SPREAD_CONTACT_INLINE V3<T> coulomb(V3<T>& elastic, const V3<T>& damping, T limit) {
  const T limit2 = limit * limit;
  const T el2 = squared_norm(elastic);
  const auto el_slips = el2 > limit2;
  if (lanes::any(el_slips)) elastic = lanes::select(el_slips, elastic * (limit / lanes::sqrt(el2)), elastic);
  V3<T> total = elastic + damping;
  const T t2 = squared_norm(total);
  const auto slips = t2 > limit2;
  if (lanes::any(slips)) total = lanes::select(slips, total * (limit / lanes::sqrt(t2)), total);
  return total;
}
}  // namespace detail

}  // namespace spread::dem
