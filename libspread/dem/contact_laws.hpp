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

namespace detail {
// Carries the stored elastic tangential force into the current tangent plane keeping its magnitude:
// the contact frame turns as the bodies roll and the walls spin.
SPREAD_CONTACT_INLINE Vec3 carry_into_plane(const double* history, const Vec3& normal) {
  Vec3 f(history[0], history[1], history[2]);
  const double mag2 = f.squaredNorm();
  if (mag2 == 0.0) return f;
  f -= f.dot(normal) * normal;
  const double new2 = f.squaredNorm();
  return new2 > 0.0 ? Vec3(f * std::sqrt(mag2 / new2)) : Vec3(Vec3::Zero());
}
// Coulomb cap (Eq. 6) with the spring shortened to the friction limit on slip (the β = 1 remark of
// Sect. 2.1: the viscous part is disregarded when shortening).
SPREAD_CONTACT_INLINE Vec3 coulomb(Vec3& elastic, const Vec3& damping, double limit) {
  const double el2 = elastic.squaredNorm();
  if (el2 > limit * limit) elastic *= limit / std::sqrt(el2);
  Vec3 total = elastic + damping;
  const double t2 = total.squaredNorm();
  if (t2 > limit * limit) total *= limit / std::sqrt(t2);
  return total;
}
}  // namespace detail

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
    ContactForce out;
    const double delta = in.overlap_m;
    const double sqrt_delta = std::sqrt(delta);
    const double quarter = std::sqrt(sqrt_delta);  // δ^{1/4}
    const double delta_rate = -in.slip_m_s.dot(in.normal);
    const double f_el = c.k_n * delta * sqrt_delta;                       // Eq. 16
    const double f_n = std::max(0.0, f_el + c.c_n * quarter * delta_rate);  // Eqs. 17–18
    out.normal_force_n = f_n;

    const Vec3 slip_t = in.slip_m_s - in.slip_m_s.dot(in.normal) * in.normal;
    Vec3 elastic = detail::carry_into_plane(history, in.normal);
    // Eq. 20 unloading branch, integrated over one step: scale by k_t/k_t,old = sqrt(δ/δ_old) when the
    // overlap (and with it the contact radius) shrinks (Appendix 2, Eq. 63).
    const double delta_old = history[3];
    if (delta < delta_old && delta_old > 0.0) elastic *= std::sqrt(delta / delta_old);
    const double k_t = c.k_t * sqrt_delta;  // k_t = 8 G* sqrt(R* δ)
    elastic -= k_t * in.dt_s * slip_t;      // Eq. 19, force opposes the slip
    const Vec3 damping = -c.c_t * quarter * slip_t;  // Eq. 23
    out.tangential_force_n = detail::coulomb(elastic, damping, p.friction * f_n);
    history[0] = elastic.x();
    history[1] = elastic.y();
    history[2] = elastic.z();
    history[3] = delta;
    out.force_n = f_n * in.normal + out.tangential_force_n;
    return out;
  }
  // Lever arm from a's centre to the contact point (Eq. 10, corrected share).
  SPREAD_CONTACT_INLINE static double lever(double radius_m, double share, double overlap_m) { return radius_m - share * overlap_m; }
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
    ContactForce out;
    const double delta_rate = -in.slip_m_s.dot(in.normal);
    const double f_n = std::max(0.0, c.k_n * in.overlap_m + c.c_n * delta_rate);
    out.normal_force_n = f_n;
    const Vec3 slip_t = in.slip_m_s - in.slip_m_s.dot(in.normal) * in.normal;
    Vec3 elastic = detail::carry_into_plane(history, in.normal);
    elastic -= c.k_t * in.dt_s * slip_t;
    out.tangential_force_n = detail::coulomb(elastic, -c.c_t * slip_t, p.friction * f_n);
    history[0] = elastic.x();
    history[1] = elastic.y();
    history[2] = elastic.z();
    history[3] = in.overlap_m;
    out.force_n = f_n * in.normal + out.tangential_force_n;
    return out;
  }
  // Seed 001: d_c = −(R − h/2) n, i.e. each body takes half the overlap.
  SPREAD_CONTACT_INLINE static double lever(double radius_m, double share, double overlap_m) {
    (void)share;
    return radius_m - 0.5 * overlap_m;
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
