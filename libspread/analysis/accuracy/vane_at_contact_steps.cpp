#include "libspread/analysis/accuracy/vane_at_contact_steps.hpp"

#include <cmath>
#include <stdexcept>

#include "libspread/physics/dem/analytic_wall.hpp"

namespace spread::accuracy::detail {

VaneExit run_vane_at(const dem::VaneCase& c, double contact_steps) {
  const double omega = c.rpm * 2.0 * kPi / 60.0;
  const double rp = c.particle_radius_m;
  dem::Material particle;
  particle.name = "vane_particle";
  particle.density_kg_m3 = 1500.0;
  particle.youngs_modulus_pa = 1e8;
  particle.restitution = 0.2;
  particle.friction_wall = c.friction;  // disc and vane only
  dem::Material wall = particle;
  wall.name = "vane_disc";
  wall.rigid = true;

  dem::WallGroup disc;
  disc.name = "disc";
  disc.pieces.push_back(dem::make_cone_disc(c.radius_m + 0.05, 0.0, 0.0));
  disc.pieces.push_back(
      dem::make_rectangle(Vec3::Zero(), Vec3::UnitX(), c.radius_m + 0.05, Vec3::UnitZ(), 0.02));
  disc.angular_velocity_rad_s = omega;
  disc.material = 1;
  dem::WallSet walls;
  walls.groups.push_back(disc);

  dem::EngineParams params;
  params.effects = effect::kWallContact;
  params.min_particle_radius_m = rp;
  params.impact_speed_m_s = 5.0;
  params.contact_steps = contact_steps;
  dem::DemEngine engine({particle, wall}, {}, walls, params);
  const Vec3 start(c.r0_m, rp, rp);
  engine.add_particle(start, Vec3(-omega * start.y(), omega * start.x(), 0.0), rp, 0);

  VaneExit out;
  out.dt_s = engine.dt_s();
  double t_exit_ref = 0.0, v_radial_ref = 0.0;
  dem::vane_reference(omega, c.friction, c.r0_m, c.radius_m, kStandardGravity_m_s2, t_exit_ref, v_radial_ref);
  out.speed_ref_m_s = std::hypot(v_radial_ref, omega * c.radius_m);

  const auto& p = engine.particles();
  auto along_vane = [&](double t, const Vec3& x) { return std::cos(omega * t) * x.x() + std::sin(omega * t) * x.y(); };
  double x_prev = along_vane(0.0, p.position(0));
  Vec3 v_prev = p.velocity(0);
  for (long s = 0; s < 50'000'000; ++s) {
    engine.step();
    ++out.steps;
    const double t = engine.time_s();
    const double x_now = along_vane(t, p.position(0));
    if (x_now >= c.radius_m) {
      const double f = (c.radius_m - x_prev) / (x_now - x_prev);
      const Vec3 v = v_prev + f * (p.velocity(0) - v_prev);
      out.speed_m_s = std::hypot(v.x(), v.y());
      out.rel_error = (out.speed_m_s - out.speed_ref_m_s) / out.speed_ref_m_s;
      return out;
    }
    if (p.z[0] < -0.1 || t > 10.0) throw std::runtime_error("accuracy vane case: the particle left the vane");
    x_prev = x_now;
    v_prev = p.velocity(0);
  }
  throw std::runtime_error("accuracy vane case: no exit within the step limit");
}

}  // namespace spread::accuracy::detail
