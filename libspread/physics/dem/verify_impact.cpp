// `spread verify impact`: head-on (and oblique) impacts measured against the requested restitution, the
// damped model's own contact duration (contact_reference, verify_impact_reference.cpp) and the elastic
// Hertz duration. Gravity is off so every velocity change comes from the contact.
#include <cmath>

#include "libspread/physics/dem/restitution.hpp"
#include "libspread/physics/dem/time_step.hpp"
#include "libspread/physics/dem/verify.hpp"

namespace spread::dem {

ImpactResult run_impact(const ImpactCase& c) {
  Material particle;
  particle.name = "impact_particle";
  particle.density_kg_m3 = 1500.0;
  particle.youngs_modulus_pa = 5e7;
  particle.poisson_ratio = 0.25;
  particle.restitution = c.restitution;
  particle.friction_particle = particle.friction_wall = c.friction;
  Material wall = particle;
  wall.name = "impact_wall";
  wall.rigid = true;

  const double r1 = 1.5e-3, r2 = 1.0e-3;
  WallSet walls;
  if (!c.sphere_sphere) {
    WallGroup g;
    g.name = "plane";
    g.pieces.push_back(make_plane(Vec3::Zero(), Vec3::UnitZ()));
    g.material = 1;
    walls.groups.push_back(g);
  }
  EngineParams params;
  params.contact_law = c.law;
  params.integrator = c.integrator;
  params.effects = effect::kWallContact | (c.sphere_sphere ? effect::kParticleContact : 0u) |
                   (c.rotation ? effect::kRotation : 0u);
  params.contact_steps = c.contact_steps;
  params.impact_speed_m_s = c.speed_m_s;
  params.min_particle_radius_m = c.sphere_sphere ? r2 : r1;
  params.max_particle_radius_m = r1;
  params.gravity_m_s2 = Vec3::Zero();
  params.linear.normal_stiffness_n_m = 2e3;
  // The automatic step is set by the smallest radius against an equal particle; refine it for the
  // actual pair so that N_c steps resolve this very contact.
  const double m1 = 1500.0 * 4.0 / 3.0 * kPi * r1 * r1 * r1;
  const double m2 = 1500.0 * 4.0 / 3.0 * kPi * r2 * r2 * r2;
  const double e_star_particles = 0.5 * 5e7 / (1.0 - 0.25 * 0.25);
  const double e_star_wall = 5e7 / (1.0 - 0.25 * 0.25);
  const double m_eff = c.sphere_sphere ? m1 * m2 / (m1 + m2) : m1;
  const double r_eff = c.sphere_sphere ? r1 * r2 / (r1 + r2) : r1;
  const double e_star = c.sphere_sphere ? e_star_particles : e_star_wall;
  ImpactResult out;
  out.e_requested = c.restitution;
  out.t_contact_hertz_s = c.law.normal == NormalModel::kHertz
                              ? hertz_contact_time_s(m_eff, r_eff, e_star, c.speed_m_s)
                              : linear_contact_time_s(m_eff, params.linear.normal_stiffness_n_m);
  // Reference duration of the damped contact: the overlap ODE scaled back to seconds (t0 as in verify.hpp).
  const bool hertz = c.law.normal == NormalModel::kHertz;
  const double damping = hertz ? hertz_damping_ratio(c.restitution) : linear_damping_ratio(c.restitution);
  const double k_hertz = 4.0 / 3.0 * std::sqrt(r_eff) * e_star;  // Eq. 16: F = k δ^{3/2}
  const double t0_s = hertz ? std::pow(m_eff / k_hertz, 0.4) * std::pow(c.speed_m_s, -0.2)
                            : std::sqrt(m_eff / params.linear.normal_stiffness_n_m);
  out.t_contact_ref_s = contact_reference(c.law, damping).duration * t0_s;
  params.dt_s = out.t_contact_hertz_s / c.contact_steps;
  DemEngine run({particle, wall}, {}, walls, params);

  Vec3 v_before1, v_before2 = Vec3::Zero();
  const double gap = 1e-6;  // start just apart: the first contact step is a true first touch
  if (c.sphere_sphere) {
    // Particle 1 moves +x, particle 2 −x; total momentum non-zero (unequal masses, equal speeds).
    v_before1 = Vec3(0.5 * c.speed_m_s, 0, 0);
    v_before2 = Vec3(-0.5 * c.speed_m_s, 0, 0);
    run.add_particle(Vec3(-r1 - gap, 0, 0), v_before1, r1, 0);
    run.add_particle(Vec3(r2 + gap, 0, 0), v_before2, r2, 0);
  } else {
    const double a = c.oblique_angle_rad;
    v_before1 = Vec3(c.speed_m_s * std::sin(a), 0, -c.speed_m_s * std::cos(a));
    run.add_particle(Vec3(0, 0, r1 + gap), v_before1, r1, 0);
  }
  const double energy_before = run.kinetic_energy_j();
  const Vec3 momentum_before = m1 * v_before1 + (c.sphere_sphere ? Vec3(m2 * v_before2) : Vec3(Vec3::Zero()));
  const double momentum_scale = m1 * v_before1.norm() + (c.sphere_sphere ? m2 * v_before2.norm() : 0.0);

  // Step until the bodies separate; count the steps in which the contact force acted.
  const auto& p = run.particles();
  std::size_t contact_steps = 0;
  bool touched = false;
  for (int s = 0; s < 100000; ++s) {
    const Vec3 v_old = p.velocity(0);
    run.step();
    const bool changed = (p.velocity(0) - v_old).squaredNorm() > 0.0;
    if (changed) { ++contact_steps; touched = true; }
    if (touched && !changed) {
      const double sep = c.sphere_sphere ? (p.position(1) - p.position(0)).norm() - r1 - r2 : p.z[0] - r1;
      if (sep > 0.0) break;
    }
  }
  out.t_contact_s = static_cast<double>(contact_steps) * run.dt_s();
  const Vec3 n = c.sphere_sphere ? Vec3::UnitX() : Vec3::UnitZ();
  if (c.sphere_sphere) {
    out.e_measured = (p.velocity(1) - p.velocity(0)).dot(n) / c.speed_m_s;
    const Vec3 momentum_after = m1 * p.velocity(0) + m2 * p.velocity(1);
    out.momentum_rel_error = (momentum_after - momentum_before).norm() / momentum_scale;
  } else {
    const Vec3 v = p.velocity(0);
    out.e_measured = v.dot(n) / (-v_before1.dot(n));
    const double vt_before = v_before1.x(), vt_after = v.x();
    out.tangential_speed_ratio = vt_before != 0.0 ? vt_after / vt_before : 0.0;
    const double jn = m1 * (v.z() - v_before1.z()), jt = m1 * (v.x() - v_before1.x());
    out.tangential_impulse_ratio = c.friction > 0.0 ? std::abs(jt) / (c.friction * std::abs(jn)) : 0.0;
    out.momentum_rel_error = 0.0;
  }
  out.energy_ratio = run.kinetic_energy_j() / energy_before;
  return out;
}

}  // namespace spread::dem
