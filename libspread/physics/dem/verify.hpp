#pragma once
// Built-in verification cases: head-on impacts against Hertz theory, Patterson &
// Reece's vane and the seed's Appendix-1 cone, each returning the simulated and the reference values.
#include <vector>

#include "libspread/physics/dem/engine.hpp"

namespace spread::dem {

// ---- Impacts: sphere on a plane or on a sphere, gravity off, head-on -----------------------------
struct ImpactCase {
  bool sphere_sphere = false;
  double restitution = 0.5;
  double speed_m_s = 1.0;          // approach speed (relative)
  double friction = 0.0;
  double contact_steps = 500.0;    // N_c (dt = t_c / N_c); the δ^{1/4} damping converges slowly (docs/dem.md)
  ContactLaw law = kHertzThorntonLaw;  // kHertzThorntonLaw or kLinearSpringDashpotLaw (the reference models those)
  Integrator integrator = Integrator::kSymplecticEuler;
  double oblique_angle_rad = 0.0;  // angle of the approach velocity from the normal (sphere–plane only)
  bool rotation = false;
};
struct ImpactResult {
  double e_requested = 0.0;
  double e_measured = 0.0;             // normal separation speed / approach speed
  double t_contact_s = 0.0;            // time with a non-zero contact force
  double t_contact_hertz_s = 0.0;      // 2.87 (M*²/(R* E*² v))^{1/5}: the elastic (e = 1) duration
  double t_contact_ref_s = 0.0;        // the damped model's duration from its overlap ODE (contact_reference)
  double energy_ratio = 0.0;           // kinetic energy after / before (translation + rotation)
  double momentum_rel_error = 0.0;     // |Σ m v after − before| / Σ m |v| before
  double tangential_speed_ratio = 0.0; // oblique: tangential speed of the centre after / before
  double tangential_impulse_ratio = 0.0;  // oblique: |J_t| / (μ |J_n|), <= 1 by Coulomb
};
ImpactResult run_impact(const ImpactCase& c);

// Reference for the impact: one head-on contact of the damped model (Hertz with δ^{1/4} damping,
// Eqs. 16–18, or the linear spring–dashpot; force clipped at zero), as the non-dimensional overlap ODE
// x'' = −max(0, x^{3/2} + γ√6 x^{1/4} x') (Hertz) or −max(0, x + 2ζ x') (linear), x(0) = 0, x'(0) = 1,
// solved by adaptive Dormand–Prince at tolerance `tol`. The contact ends when the clipped force is zero
// again while receding (as the simulation measures it). duration × t0 is the contact time, with
// t0 = (M*/k)^{2/5} v^{−1/5}, k = 4/3 sqrt(R*) E* (Hertz) or t0 = sqrt(M*/k_n) (linear); restitution
// is the separation speed / approach speed.
struct ContactReference {
  double duration = 0.0;     // non-dimensional contact time
  double restitution = 0.0;  // non-dimensional separation speed
};
ContactReference contact_reference(const ContactLaw& law, double damping_ratio, double tol = 1e-12);

// ---- Patterson & Reece: flat disc with one radial vane -------------------------------------------
struct VaneCase {
  double rpm = 500.0;
  double friction = 0.3;
  double r0_m = 0.1;
  double radius_m = 0.4;
  double particle_radius_m = 1e-3;
};
struct VaneResult {
  double rpm = 0.0, mu = 0.0;
  double v_radial = 0.0, v_tangential = 0.0;              // simulated at r = R (m/s)
  double v_radial_ref = 0.0, v_tangential_ref = 0.0;      // closed form
  double rel_error_radial = 0.0, rel_error_tangential = 0.0;
  double t_exit_s = 0.0, t_exit_ref_s = 0.0;
};
// Closed form of r̈ + 2μω ṙ − ω² r = −μ g, r(0) = r0, ṙ(0) = 0: time and radial speed at r = R.
void vane_reference(double omega_rad_s, double mu, double r0_m, double radius_m, double g, double& t_exit_s,
                    double& v_radial_m_s);
VaneResult run_vane(const VaneCase& c);

// ---- Appendix 1: point mass on a spinning cone without vanes (non-dimensional) ------------------
struct ConeState {
  double speed = 0.0;                   // |v| / (ωR)
  double elevation_deg = 0.0;           // angle of v above the horizontal
  double angle_from_tangent_deg = 0.0;  // angle of the horizontal velocity from the tangential direction
  double t_exit = 0.0;                  // ω t at ρ = 1
};
struct ConeCase {
  double mu = 0.25;
  double rho0 = 0.4, v0 = 0.02, gamma = 0.0004, alpha_rad = kPi / 12.0;  // Table 3
  double mesh_size = 0.0;               // ξ (normalised by R); 0 = analytic cone
  int particles = 4;                    // non-interacting copies at evenly spaced start angles, averaged
  double radius_m = 0.1;                // dimensional R used for the DEM run
  double particle_radius = 0.005;       // δ, normalised by R (seed Sect. 3.3)
};
struct ConeResult {
  double mu = 0.0, mesh_size = 0.0;
  ConeState simulated, reference;
  double rel_error_speed = 0.0, rel_error_elevation = 0.0, rel_error_angle = 0.0, rel_error_t_exit = 0.0;
  std::size_t triangles = 0;
};
// The Appendix-1 ODE (Eqs. 54–62) written in cone coordinates, solved by adaptive Dormand–Prince at
// tolerance `tol` with the exit ρ = 1 located exactly.
ConeState cone_reference(const ConeCase& c, double tol = 1e-12);
ConeResult run_cone(const ConeCase& c);

}  // namespace spread::dem
