// `spread verify vane`: Patterson & Reece (1962). A particle released at rest (relative to the disc) at
// r0 against a radial vane of a flat disc spinning at ω slides out under the centrifugal force, with
// friction μ against the disc (μ g) and against the vane (μ × the Coriolis push 2ω ṙ):
//   r̈ + 2μω ṙ − ω² r = −μ g.
// Particle spin is off (pure sliding, as the theory assumes).
#include <cmath>
#include <stdexcept>

#include "libspread/physics/dem/verify.hpp"

namespace spread::dem {

void vane_reference(double omega, double mu, double r0, double radius, double g, double& t_exit, double& v_radial) {
  // r = A e^{λ1 t} + B e^{λ2 t} + μg/ω², λ = ω(−μ ± sqrt(1 + μ²)); r(0) = r0, ṙ(0) = 0.
  const double root = std::sqrt(1.0 + mu * mu);
  const double l1 = omega * (-mu + root), l2 = omega * (-mu - root);
  const double rp = mu * g / (omega * omega);
  const double a = (r0 - rp) * (-l2) / (l1 - l2);
  const double b = (r0 - rp) - a;
  if (!(r0 > rp)) throw std::invalid_argument("vane reference: friction holds the particle (r0 <= μg/ω²)");
  auto r = [&](double t) { return a * std::exp(l1 * t) + b * std::exp(l2 * t) + rp; };
  auto rd = [&](double t) { return a * l1 * std::exp(l1 * t) + b * l2 * std::exp(l2 * t); };
  // r(t) is increasing; bracket then Newton-safeguarded bisection.
  double lo = 0.0, hi = 1.0 / omega;
  while (r(hi) < radius) hi *= 2.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (r(mid) < radius) lo = mid; else hi = mid;
  }
  t_exit = 0.5 * (lo + hi);
  v_radial = rd(t_exit);
}

VaneResult run_vane(const VaneCase& c) {
  const double omega = c.rpm * 2.0 * kPi / 60.0;
  const double rp = c.particle_radius_m;
  Material particle;
  particle.name = "vane_particle";
  particle.density_kg_m3 = 1500.0;
  particle.youngs_modulus_pa = 1e8;
  particle.restitution = 0.2;  // settles quickly onto the disc
  particle.friction_wall = c.friction;  // disc and vane only
  Material wall = particle;
  wall.name = "vane_disc";
  wall.rigid = true;

  WallGroup disc;
  disc.name = "disc";
  disc.pieces.push_back(make_cone_disc(c.radius_m + 0.05, 0.0, 0.0));
  // Radial vane along +x of the disc frame, from the centre past R, standing on the disc.
  disc.pieces.push_back(make_rectangle(Vec3::Zero(), Vec3::UnitX(), c.radius_m + 0.05, Vec3::UnitZ(), 0.02));
  disc.angular_velocity_rad_s = omega;
  disc.material = 1;
  WallSet walls;
  walls.groups.push_back(disc);

  EngineParams params;
  params.effects = effect::kWallContact;
  params.min_particle_radius_m = rp;
  params.impact_speed_m_s = 5.0;  // sliding contacts: normal approach speeds stay small
  DemEngine engine({particle, wall}, {}, walls, params);
  // Leading side of the vane (+y in the disc frame for counter-clockwise spin), touching disc and vane,
  // moving with the disc.
  const Vec3 start(c.r0_m, rp, rp);
  engine.add_particle(start, Vec3(-omega * start.y(), omega * start.x(), 0.0), rp, 0);

  VaneResult out;
  out.rpm = c.rpm;
  out.mu = c.friction;
  vane_reference(omega, c.friction, c.r0_m, c.radius_m, kStandardGravity_m_s2, out.t_exit_ref_s, out.v_radial_ref);
  out.v_tangential_ref = omega * c.radius_m;

  const auto& p = engine.particles();
  auto along_vane = [&](double t, const Vec3& x) {
    return std::cos(omega * t) * x.x() + std::sin(omega * t) * x.y();
  };
  double x_prev = along_vane(0.0, p.position(0));
  double t_prev = 0.0;
  Vec3 v_prev = p.velocity(0);
  for (int s = 0; s < 50'000'000; ++s) {
    engine.step();
    const double t = engine.time_s();
    const double x_now = along_vane(t, p.position(0));
    if (x_now >= c.radius_m) {
      // Linear interpolation to the crossing; velocity decomposed along the vane (radial) and
      // perpendicular to it in the horizontal plane (tangential), inertial frame.
      const double f = (c.radius_m - x_prev) / (x_now - x_prev);
      const double tc = t_prev + f * (t - t_prev);
      const Vec3 v = v_prev + f * (p.velocity(0) - v_prev);
      const double ca = std::cos(omega * tc), sa = std::sin(omega * tc);
      out.v_radial = ca * v.x() + sa * v.y();
      out.v_tangential = -sa * v.x() + ca * v.y();
      out.t_exit_s = tc;
      break;
    }
    if (p.z[0] < -0.1 || t > 10.0) throw std::runtime_error("vane verification: the particle left the vane");
    x_prev = x_now;
    t_prev = t;
    v_prev = p.velocity(0);
  }
  out.rel_error_radial = (out.v_radial - out.v_radial_ref) / out.v_radial_ref;
  out.rel_error_tangential = (out.v_tangential - out.v_tangential_ref) / out.v_tangential_ref;
  return out;
}

}  // namespace spread::dem
