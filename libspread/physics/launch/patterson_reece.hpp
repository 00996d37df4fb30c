#pragma once
// Motion of a granule along a radial vane of a spinning disc with sliding friction μ on disc and vane
// (Patterson & Reece 1962, docs/design.md §2), generalised to a cone whose surface rises outward at angle α.
//
// s is the distance along the generatrix from the axis (radius ρ = s cos α, height z = s sin α).
// In the disc's rotating frame, at constant ω, the granule feels (per unit mass):
//   centrifugal ω² ρ outward (horizontal): along s  ω² s cos²α, into the surface  ω² s cos α sin α;
//   gravity g down:                       along s −g sin α,     into the surface  g cos α;
//   Coriolis 2 ω ρ̇ = 2 ω ṡ cos α, tangential — taken by the vane, so the vane pushes with that force.
// Sliding friction μ times both normal forces opposes ṡ > 0:
//   s̈ = ω² cos²α s − g sin α − μ (g cos α + ω² cos α sin α s + 2 ω cos α ṡ)
//   s̈ + 2a ṡ − b s = −c,  a = μ ω cos α,  b = ω² cos α (cos α − μ sin α),  c = g (sin α + μ cos α).
// For α = 0 this is Patterson & Reece's r̈ + 2μω ṙ − ω² r = −μ g. Closed form from s(0) = s0, ṡ(0) = 0:
//   λ1,2 = −a ± sqrt(a² + b)  (= ω(−μ ± sqrt(μ² + 1)) on a flat disc),  s_p = c / b,
//   s(t) = s_p + A e^{λ1 t} + B e^{λ2 t},  A = (s0 − s_p)(−λ2)/(λ1 − λ2),  B = (s0 − s_p) λ1/(λ1 − λ2).
// The granule moves only if s0 > s_p (otherwise friction holds it) and b > 0 (tan α < 1/μ).
// At the vane end the velocity relative to the disc lies along the generatrix: elevation α, speed ṡ;
// in the inertial frame the rim speed ω ρ_exit adds tangentially (so the absolute elevation is below α).
// For s0 ≪ s_exit on a flat disc ṙ/(ωR) → sqrt(1 + μ²) − μ: the exit angle from the tangent tends to
// atan(sqrt(1 + μ²) − μ).
namespace spread::launch {

struct VaneMotion {
  double omega_rad_s;       // disc speed ω > 0
  double friction;          // μ ≥ 0, same on disc and vane
  double cone_angle_rad;    // α ≥ 0 (0 = flat)
  double gravity_m_s2;

  // Closed-form solution from radius r0_m (horizontal) at rest relative to the vane.
  // Throws std::invalid_argument when the granule cannot move outward.
  struct Solution {
    double lambda1, lambda2;  // 1/s
    double a_m, b_m;          // A, B
    double s_p_m;             // particular (equilibrium) position along the generatrix
    double s_m(double t_s) const;            // position along the generatrix
    double s_dot_m_s(double t_s) const;      // speed along the generatrix (relative to the disc)
  };
  Solution solve(double r0_m) const;
};

struct VaneExit {
  double time_s;                 // transit time from r0 to the exit radius
  double speed_along_vane_m_s;   // ṡ at exit, relative to the disc
  double radial_speed_m_s;       // horizontal radial component ṡ cos α
  double vertical_speed_m_s;     // ṡ sin α
  double tangential_speed_m_s;   // ω ρ_exit (inertial frame)
  double turned_angle_rad;       // ω · time_s, the angle the vane turned during the transit
};

// Exit at horizontal radius r_exit_m from r0_m (ṡ(0) = 0): safeguarded Newton on s(t) = s_exit.
VaneExit vane_exit(const VaneMotion& motion, double r0_m, double r_exit_m);

// atan(sqrt(1 + μ²) − μ): flat-disc exit angle from the tangent for r0 ≪ R (and ω²R ≫ μg).
double exit_angle_from_tangent_limit_rad(double friction);

}  // namespace spread::launch
