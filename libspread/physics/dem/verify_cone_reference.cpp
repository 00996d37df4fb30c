// Reference for `spread verify cone`: seed Appendix 1 (Eqs. 53–62). A point mass on the cone
// z = tanα ρ spinning at ω = 1 (non-dimensional: lengths / R, time τ = ωt, gravity γ = g/(ω²R)).
//
// Cone coordinates: s along the generator, φ the polar angle. With e_s = (cosα cosφ, cosα sinφ, sinα),
// e_φ = (−sinφ, cosφ, 0) and the inner normal n = (−sinα cosφ, −sinα sinφ, cosα) (as in Eq. 54):
//   a = (s̈ − s cos²α φ̇²) e_s + cosα (2ṡφ̇ + s φ̈) e_φ + s cosα sinα φ̇² n.
// Forces per unit mass: −γ(sinα e_s + cosα n) + φ_R n + μ φ_R n_v, n_v the unit velocity of the cone
// relative to the particle (the cone moves at s cosα e_φ). The n-equation gives the reaction
// φ_R = γ cosα + s cosα sinα φ̇² (always > 0 here), which is Eq. 59's constraint solved exactly.
#include <algorithm>
#include <array>
#include <cmath>

#include "libspread/core/dormand_prince.hpp"
#include "libspread/physics/dem/verify.hpp"

namespace spread::dem {

namespace {
using State = std::array<double, 4>;  // s, φ, ṡ, φ̇

State rhs(const ConeCase& c, const State& y) {
  const double ca = std::cos(c.alpha_rad), sa = std::sin(c.alpha_rad);
  const double s = y[0], sd = y[2], pd = y[3];
  const double reaction = c.gamma * ca + s * ca * sa * pd * pd;
  // Particle velocity relative to the cone, in (e_s, e_φ).
  const double rel_s = sd, rel_p = s * ca * (pd - 1.0);
  const double rel = std::hypot(rel_s, rel_p);
  double fs = 0.0, fp = 0.0;
  if (rel > 0.0) {
    fs = -c.mu * reaction * rel_s / rel;
    fp = -c.mu * reaction * rel_p / rel;
  }
  const double sdd = s * ca * ca * pd * pd - c.gamma * sa + fs;
  const double pdd = (fp / ca - 2.0 * sd * pd) / s;
  return {sd, pd, sdd, pdd};
}

}  // namespace

ConeState cone_reference(const ConeCase& c, double tol) {
  const double ca = std::cos(c.alpha_rad), sa = std::sin(c.alpha_rad);
  State y = {c.rho0 / ca, 0.0, 0.0, c.v0 / c.rho0};  // ξ(0) = (ρ0, 0, tanα ρ0), ξ̇(0) = (0, v0, 0)
  const double s_exit = 1.0 / ca;
  const dormand_prince::EventHit<4> exit = dormand_prince::integrate_until(
      [&](const State& x) { return rhs(c, x); }, y, 1e-3, tol, 1e-14, [&](const State& x) { return x[0] >= s_exit; });
  y = exit.y;
  const double t = exit.t;
  const double s = y[0], sd = y[2], pd = y[3];
  const double v_radial = sd * ca, v_z = sd * sa, v_tan = s * ca * pd;
  ConeState out;
  out.speed = std::sqrt(sd * sd + v_tan * v_tan);
  out.elevation_deg = std::atan2(v_z, std::hypot(v_radial, v_tan)) * 180.0 / kPi;
  out.angle_from_tangent_deg = std::atan2(v_radial, v_tan) * 180.0 / kPi;
  out.t_exit = t;
  return out;
}

}  // namespace spread::dem
