// `spread verify impact`: head-on (and oblique) impacts measured against the requested restitution, the
// damped model's own contact duration (contact_reference, verify_impact_reference.cpp) and the elastic
// Hertz duration. Gravity is off so every velocity change comes from the contact.
#include <cmath>

#include "libspread/physics/dem/restitution.hpp"
#include "libspread/physics/dem/time_step.hpp"
#include "libspread/physics/dem/verify.hpp"

namespace spread::dem {

namespace {

constexpr double kRadius1_m = 1.5e-3, kRadius2_m = 1.0e-3;  // the moving sphere's, the sphere it meets
constexpr double kDensity_kg_m3 = 1500.0;

double sphere_mass_kg(double radius_m) { return kDensity_kg_m3 * 4.0 / 3.0 * kPi * radius_m * radius_m * radius_m; }

// The engine for the case: one material (and its rigid copy for the plane), gravity off, its step set so that
// N_c steps resolve this very contact (the automatic step is set by the smallest radius against an equal
// particle). Fills the requested restitution and both reference durations.
DemEngine impact_engine(const ImpactCase& c, ImpactResult& out) {
  Material particle;
  particle.name = "impact_particle";
  particle.density_kg_m3 = kDensity_kg_m3;
  particle.youngs_modulus_pa = 5e7;
  particle.poisson_ratio = 0.25;
  particle.restitution = c.restitution;
  particle.friction_particle = particle.friction_wall = c.friction;
  Material wall = particle;
  wall.name = "impact_wall";
  wall.rigid = true;
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
  params.min_particle_radius_m = c.sphere_sphere ? kRadius2_m : kRadius1_m;
  params.max_particle_radius_m = kRadius1_m;
  params.gravity_m_s2 = Vec3::Zero();
  params.linear.normal_stiffness_n_m = 2e3;
  const double m1 = sphere_mass_kg(kRadius1_m), m2 = sphere_mass_kg(kRadius2_m);
  const double e_star_particles = 0.5 * 5e7 / (1.0 - 0.25 * 0.25);
  const double e_star_wall = 5e7 / (1.0 - 0.25 * 0.25);
  const double m_eff = c.sphere_sphere ? m1 * m2 / (m1 + m2) : m1;
  const double r_eff = c.sphere_sphere ? kRadius1_m * kRadius2_m / (kRadius1_m + kRadius2_m) : kRadius1_m;
  const double e_star = c.sphere_sphere ? e_star_particles : e_star_wall;
  const bool hertz = c.law.normal == NormalModel::kHertz;
  out.e_requested = c.restitution;
  out.t_contact_hertz_s = hertz ? hertz_contact_time_s(m_eff, r_eff, e_star, c.speed_m_s)
                                : linear_contact_time_s(m_eff, params.linear.normal_stiffness_n_m);
  // Reference duration of the damped contact: the overlap ODE scaled back to seconds (t0 as in verify.hpp).
  const double damping = hertz ? hertz_damping_ratio(c.restitution) : linear_damping_ratio(c.restitution);
  const double k_hertz = 4.0 / 3.0 * std::sqrt(r_eff) * e_star;  // Eq. 16: F = k δ^{3/2}
  const double t0_s = hertz ? std::pow(m_eff / k_hertz, 0.4) * std::pow(c.speed_m_s, -0.2)
                            : std::sqrt(m_eff / params.linear.normal_stiffness_n_m);
  out.t_contact_ref_s = contact_reference(c.law, damping).duration * t0_s;
  params.dt_s = out.t_contact_hertz_s / c.contact_steps;
  return DemEngine({particle, wall}, {}, walls, params);
}

// The bodies just apart (the first contact step is a true first touch): two spheres approaching along x
// (unequal masses, equal speeds: total momentum not zero), or one sphere onto the plane at the case's angle.
// Returns the first sphere's velocity before, and the second's in `v_before2`.
Vec3 place_impact(DemEngine& run, const ImpactCase& c, Vec3& v_before2) {
  const double gap = 1e-6;
  v_before2 = Vec3::Zero();
  if (c.sphere_sphere) {
    const Vec3 v_before1(0.5 * c.speed_m_s, 0, 0);
    v_before2 = Vec3(-0.5 * c.speed_m_s, 0, 0);
    run.add_particle(Vec3(-kRadius1_m - gap, 0, 0), v_before1, kRadius1_m, 0);
    run.add_particle(Vec3(kRadius2_m + gap, 0, 0), v_before2, kRadius2_m, 0);
    return v_before1;
  }
  const double a = c.oblique_angle_rad;
  const Vec3 v_before1(c.speed_m_s * std::sin(a), 0, -c.speed_m_s * std::cos(a));
  run.add_particle(Vec3(0, 0, kRadius1_m + gap), v_before1, kRadius1_m, 0);
  return v_before1;
}

// Steps until the bodies separate; the time in which the contact force acted (steps that changed the
// first sphere's velocity).
double measured_contact_time_s(DemEngine& run, const ImpactCase& c) {
  const auto& p = run.particles();
  std::size_t contact_steps = 0;
  bool touched = false;
  for (int s = 0; s < 100000; ++s) {
    const Vec3 v_old = p.velocity(0);
    run.step();
    const bool changed = (p.velocity(0) - v_old).squaredNorm() > 0.0;
    if (changed) { ++contact_steps; touched = true; }
    if (touched && !changed) {
      const double sep = c.sphere_sphere ? (p.position(1) - p.position(0)).norm() - kRadius1_m - kRadius2_m
                                         : p.z[0] - kRadius1_m;
      if (sep > 0.0) break;
    }
  }
  return static_cast<double>(contact_steps) * run.dt_s();
}

}  // namespace

ImpactResult run_impact(const ImpactCase& c) {
  ImpactResult out;
  DemEngine run = impact_engine(c, out);
  Vec3 v_before2;
  const Vec3 v_before1 = place_impact(run, c, v_before2);
  const double m1 = sphere_mass_kg(kRadius1_m), m2 = sphere_mass_kg(kRadius2_m);
  const double energy_before = run.kinetic_energy_j();
  const Vec3 momentum_before = m1 * v_before1 + (c.sphere_sphere ? Vec3(m2 * v_before2) : Vec3(Vec3::Zero()));
  const double momentum_scale = m1 * v_before1.norm() + (c.sphere_sphere ? m2 * v_before2.norm() : 0.0);
  out.t_contact_s = measured_contact_time_s(run, c);
  const auto& p = run.particles();
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
