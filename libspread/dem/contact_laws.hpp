#pragma once
// Contact laws as evaluators (HOOMD/LAMMPS style, DESIGN.md §7): each law is a type with an inline
// eval() over parameters derived once per material pair (PairParams) and a per-contact tangential
// history of 4 doubles stored in flat arrays by the caller (no heap object per contact).
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
#include "libspread/dem/lanes.hpp"
#include "libspread/dem/material.hpp"

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

namespace spread::dem {

struct ContactInput {
  Vec3 normal = Vec3::UnitZ();
  double overlap_m = 0.0;
  Vec3 slip_m_s = Vec3::Zero();
  double r_eff_m = 0.0;   // R* = (1/R_a + 1/R_b)^-1; walls: R_a
  double m_eff_kg = 0.0;  // M* = (1/m_a + 1/m_b)^-1; walls: m_a
  double dt_s = 0.0;
};

// The parts of a law that depend only on the two bodies (R*, M*, the pair's material constants), not on
// the contact's state: computed by Law::coeffs once per material pair whose particles all share one
// radius and mass (the engine's table, refreshed when particles are added), or per contact otherwise.
// The per-step kernel is then left with the distance's sqrt and one reciprocal (plus δ^{1/2} for Hertz).
struct PairCoeffs {
  double r_eff_m = 0.0;   // R* (rolling resistance; the Hertz prefactors below)
  double m_eff_kg = 0.0;  // M*
  double k_n = 0.0;       // linear: k_n (N/m);      Hertz: 4/3 sqrt(R*) E*  (F_el = k_n δ^{3/2}, Eq. 16)
  double k_t = 0.0;       // linear: k_t (N/m);      Hertz: 8 G* sqrt(R*)    (k_t(δ) = this · δ^{1/2}, Eq. 19)
  double c_n = 0.0;       // linear: 2ζ sqrt(M* k_n); Hertz: γ sqrt(8 E* M* sqrt(R*))  (× δ^{1/4}, Eq. 18)
  double c_t = 0.0;       // linear: 2ζ sqrt(M* k_t); Hertz: 2γ sqrt(8 G* M* sqrt(R*)) (× δ^{1/4}, Eq. 24)
  bool uniform = false;   // engine table only: true when the entry holds for every particle pair of these materials
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
template <class T>
struct LawHistory {
  lanes::V3<T> elastic;
  T overlap_m;
};
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

// Eigen-interface evaluation shared by the laws: the wall contacts and single contacts call it; the pair
// pass calls Law::kernel directly (one contact, or two in lanes).
template <class Law>
SPREAD_CONTACT_INLINE ContactForce eval_one(const PairParams& p, const PairCoeffs& c, const ContactInput& in, double* history) {
  using lanes::V3;
  LawHistory<double> h{{history[0], history[1], history[2]}, history[3]};
  const V3<double> n{in.normal.x(), in.normal.y(), in.normal.z()};
  const LawForce<double> r = Law::kernel(c, p.friction, ContactNormal<double>{n, n, 1.0}, in.overlap_m,
                                         V3<double>{in.slip_m_s.x(), in.slip_m_s.y(), in.slip_m_s.z()}, in.dt_s, h);
  history[0] = h.elastic.x;
  history[1] = h.elastic.y;
  history[2] = h.elastic.z;
  history[3] = h.overlap_m;
  ContactForce out;
  out.force_n = Vec3(r.force_n.x, r.force_n.y, r.force_n.z);
  out.tangential_force_n = Vec3(r.tangential_n.x, r.tangential_n.y, r.tangential_n.z);
  out.normal_force_n = r.normal_force_n;
  return out;
}

// Hertz normal force (Eq. 16) with δ^{1/4} damping (Eqs. 17–18) clipped at 0, and Thornton's
// incremental tangential law (Eqs. 19–20) with damping (Eqs. 23–24) and the Coulomb cap (Eq. 6).
struct HertzThornton {
  static constexpr bool kNeedsHistory = true;

  SPREAD_CONTACT_INLINE static PairCoeffs coeffs(const PairParams& p, double r_eff_m, double m_eff_kg) {
    PairCoeffs c;
    const double sqrt_r = std::sqrt(r_eff_m);
    c.r_eff_m = r_eff_m;
    c.m_eff_kg = m_eff_kg;
    // Eq. 16: F_el = 4/3 sqrt(R*) E* δ^{3/2}; Eq. 18: c_n = γ sqrt(8 E* M* sqrt(R*)) — γ is the damping
    // ratio against the linearised stiffness dF/dδ = 2 E* sqrt(R* δ).
    c.k_n = (4.0 / 3.0) * sqrt_r * p.e_star_pa;
    c.c_n = p.damping_ratio * std::sqrt(8.0 * p.e_star_pa * m_eff_kg * sqrt_r);
    c.k_t = 8.0 * p.g_star_pa * sqrt_r;                                             // k_t = 8 G* sqrt(R* δ)
    c.c_t = 2.0 * p.damping_ratio * std::sqrt(8.0 * p.g_star_pa * m_eff_kg * sqrt_r);  // Eq. 24
    return c;
  }
  static ContactForce eval(const PairParams& p, const ContactInput& in, double* history) {
    return eval(p, coeffs(p, in.r_eff_m, in.m_eff_kg), in, history);
  }
  // in.r_eff_m and in.m_eff_kg are not read: c holds what depends on them.
  static ContactForce eval(const PairParams& p, const PairCoeffs& c, const ContactInput& in, double* history) {
    return eval_one<HertzThornton>(p, c, in, history);
  }
  // One contact (T = double) or two (T = lanes::Lanes2) with the same coefficients c and friction μ.
  // contact_normal: unit normal from b to a, and its unnormalised axis (ContactNormal); delta_m: overlap > 0;
  // slip_m_s: Eq. 8; h: in/out history.
  template <class T>
  SPREAD_CONTACT_INLINE static LawForce<T> kernel(const PairCoeffs& c, double friction, const ContactNormal<T>& contact_normal,
                                                  T delta_m, const lanes::V3<T>& slip_m_s, double dt_s, LawHistory<T>& h) {
    using lanes::splat;
    const lanes::V3<T>& normal = contact_normal.unit;
    const T sqrt_delta = lanes::sqrt(delta_m);
    const T quarter = lanes::sqrt(sqrt_delta);  // δ^{1/4}
    const T slip_n = dot(slip_m_s, normal);
    const T f_el = splat<T>(c.k_n) * delta_m * sqrt_delta;                         // Eq. 16
    const T f_n = lanes::max0(f_el + splat<T>(c.c_n) * quarter * (-slip_n));  // Eqs. 17–18, δ̇ = −slip·n
    const lanes::V3<T> slip_t = slip_m_s - slip_n * normal;
    lanes::V3<T> elastic = detail::carry_into_plane(h.elastic, contact_normal.axis, contact_normal.inv_axis2);
    // Eq. 20 unloading branch, integrated over one step: scale by k_t/k_t,old = sqrt(δ/δ_old) when the
    // overlap (and with it the contact radius) shrinks (Appendix 2, Eq. 63).
    const T delta_old = h.overlap_m;
    const auto unloading = lanes::both(delta_m < delta_old, delta_old > splat<T>(0.0));
    if (lanes::any(unloading))
      elastic = lanes::select(unloading, elastic * lanes::sqrt(delta_m / lanes::select(unloading, delta_old, splat<T>(1.0))),
                              elastic);
    const T k_t = splat<T>(c.k_t) * sqrt_delta;         // k_t = 8 G* sqrt(R* δ)
    elastic = elastic - (k_t * splat<T>(dt_s)) * slip_t;  // Eq. 19, force opposes the slip
    const lanes::V3<T> damping = (splat<T>(-c.c_t) * quarter) * slip_t;  // Eq. 23
    LawForce<T> out;
    out.tangential_n = detail::coulomb(elastic, damping, splat<T>(friction) * f_n);
    out.normal_force_n = f_n;
    out.force_n = f_n * normal + out.tangential_n;
    h.elastic = elastic;
    h.overlap_m = delta_m;
    return out;
  }
  // Lever arm from a's centre to the contact point (Eq. 10, corrected share).
  template <class T>
  SPREAD_CONTACT_INLINE static T lever(T radius_m, double share, T overlap_m) { return radius_m - lanes::splat<T>(share) * overlap_m; }
};

// Seed 001: F_n = k_n δ + 2ζ sqrt(M* k_n) δ̇ (clipped at 0), tangential spring k_t with dashpot
// 2ζ sqrt(M* k_t) and a Coulomb slider; the spring is shortened to the friction limit on slip.
struct LinearSpringDashpot {
  static constexpr bool kNeedsHistory = true;

  SPREAD_CONTACT_INLINE static PairCoeffs coeffs(const PairParams& p, double r_eff_m, double m_eff_kg) {
    PairCoeffs c;
    c.r_eff_m = r_eff_m;
    c.m_eff_kg = m_eff_kg;
    c.k_n = p.kn_linear_n_m;
    c.k_t = p.kt_linear_n_m;
    c.c_n = 2.0 * p.damping_ratio * std::sqrt(m_eff_kg * p.kn_linear_n_m);  // 2ζ sqrt(M* k_n)
    c.c_t = 2.0 * p.damping_ratio * std::sqrt(m_eff_kg * p.kt_linear_n_m);  // 2ζ sqrt(M* k_t)
    return c;
  }
  static ContactForce eval(const PairParams& p, const ContactInput& in, double* history) {
    return eval(p, coeffs(p, in.r_eff_m, in.m_eff_kg), in, history);
  }
  // in.r_eff_m and in.m_eff_kg are not read: c holds what depends on them.
  static ContactForce eval(const PairParams& p, const PairCoeffs& c, const ContactInput& in, double* history) {
    return eval_one<LinearSpringDashpot>(p, c, in, history);
  }
  // As HertzThornton::kernel. The history's overlap is stored, not used.
  template <class T>
  SPREAD_CONTACT_INLINE static LawForce<T> kernel(const PairCoeffs& c, double friction, const ContactNormal<T>& contact_normal,
                                                  T delta_m, const lanes::V3<T>& slip_m_s, double dt_s, LawHistory<T>& h) {
    using lanes::splat;
    const lanes::V3<T>& normal = contact_normal.unit;
    const T slip_n = dot(slip_m_s, normal);
    const T f_n = lanes::max0(splat<T>(c.k_n) * delta_m + splat<T>(c.c_n) * (-slip_n));  // δ̇ = −slip·n
    const lanes::V3<T> slip_t = slip_m_s - slip_n * normal;
    lanes::V3<T> elastic = detail::carry_into_plane(h.elastic, contact_normal.axis, contact_normal.inv_axis2);
    elastic = elastic - (splat<T>(c.k_t) * splat<T>(dt_s)) * slip_t;
    LawForce<T> out;
    out.tangential_n = detail::coulomb(elastic, splat<T>(-c.c_t) * slip_t, splat<T>(friction) * f_n);
    out.normal_force_n = f_n;
    out.force_n = f_n * normal + out.tangential_n;
    h.elastic = elastic;
    h.overlap_m = delta_m;
    return out;
  }
  // Seed 001: d_c = −(R − h/2) n, i.e. each body takes half the overlap.
  template <class T>
  SPREAD_CONTACT_INLINE static T lever(T radius_m, double share, T overlap_m) {
    (void)share;
    return radius_m - lanes::splat<T>(0.5) * overlap_m;
  }
};

// Rolling resistance (constant directional torque): M_r = −μ_r F_n R* ω̂_rel, limited so that it can at
// most stop the relative spin within one step (it never reverses it).
inline Vec3 rolling_torque(double rolling_friction, double normal_force_n, double r_eff_m, const Vec3& relative_spin_rad_s,
                           double inertia_eff_kg_m2, double dt_s) {
  const double w = relative_spin_rad_s.norm();
  if (w == 0.0 || rolling_friction == 0.0) return Vec3::Zero();
  const double mag = std::min(rolling_friction * normal_force_n * r_eff_m, w * inertia_eff_kg_m2 / dt_s);
  return (-mag / w) * relative_spin_rad_s;
}

}  // namespace spread::dem
