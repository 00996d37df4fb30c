// `spread verify cone`: the seed's Appendix 1 in the DEM — non-interacting spheres without spin on a
// spinning cone (analytic or meshed with element size ξ), compared with the ODE reference.
#include <cmath>
#include <stdexcept>

#include "libspread/physics/dem/disc_generator.hpp"
#include "libspread/physics/dem/verify.hpp"

namespace spread::dem {

ConeResult run_cone(const ConeCase& c) {
  const double R = c.radius_m;
  const double omega = std::sqrt(kStandardGravity_m_s2 / (c.gamma * R));  // γ = g/(ω²R), Eq. 62
  const double rp = c.particle_radius * R;
  Material particle;
  particle.name = "cone_particle";
  particle.density_kg_m3 = 1500.0;
  particle.youngs_modulus_pa = 1e8;
  particle.restitution = 0.2;  // seed Sect. 3.3
  particle.friction_wall = c.mu;  // cone only: no particle–particle contact
  Material wall = particle;
  wall.name = "cone_wall";
  wall.rigid = true;

  // The cone reaches past R so the particle stays supported until its centre crosses ρ = R.
  DiscGeometry geom;
  geom.radius_m = R + 4.0 * rp;
  geom.cone_angle_rad = c.alpha_rad;
  geom.mesh_size_m = c.mesh_size * R;
  WallGroup cone = make_disc(geom, omega * 60.0 / (2.0 * kPi), 1, rp);
  ConeResult out;
  out.mu = c.mu;
  out.mesh_size = c.mesh_size;
  if (!cone.meshes.empty()) out.triangles = cone.meshes[0].mesh().triangles.size();
  WallSet walls;
  walls.groups.push_back(std::move(cone));

  EngineParams params;
  params.effects = effect::kWallContact;
  params.min_particle_radius_m = rp;
  params.impact_speed_m_s = 2.0;  // the particle slides: normal approach speeds stay small
  DemEngine engine({particle, wall}, {}, walls, params);

  const double ca = std::cos(c.alpha_rad), sa = std::sin(c.alpha_rad), ta = std::tan(c.alpha_rad);
  // Centre at ρ0 R, resting on the cone: surface point at ρ_q = ρ0 R + r sin α, centre r along the normal.
  const double rho_q = c.rho0 * R + rp * sa;
  const double z_c = ta * rho_q + rp * ca;
  const int n = std::max(1, c.particles);
  for (int k = 0; k < n; ++k) {
    // Start angles spread over a sector so the particles meet different triangles of the mesh.
    const double phi = 2.0 * kPi * k / n + 0.37;
    const Vec3 er(std::cos(phi), std::sin(phi), 0.0), et(-std::sin(phi), std::cos(phi), 0.0);
    engine.add_particle(c.rho0 * R * er + Vec3(0, 0, z_c), c.v0 * omega * R * et, rp, 0);
  }
  const auto& p = engine.particles();
  std::vector<double> rho_prev(static_cast<std::size_t>(n)), t_exit(static_cast<std::size_t>(n), -1.0);
  std::vector<Vec3> v_prev(static_cast<std::size_t>(n)), x_prev(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) {
    rho_prev[k] = c.rho0 * R;
    v_prev[k] = p.velocity(k);
    x_prev[k] = p.position(k);
  }
  ConeState sum;
  int done = 0;
  const double t_max = 400.0 / omega;  // the reference exits near ωt ≈ 47
  while (done < n) {
    engine.step();
    const double t = engine.time_s();
    if (t > t_max) throw std::runtime_error("cone verification: a particle did not reach the rim");
    for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) {
      if (t_exit[k] >= 0.0) continue;
      const Vec3 x = p.position(k), v = p.velocity(k);
      const double rho = std::hypot(x.x(), x.y());
      if (rho >= R) {
        const double f = (R - rho_prev[k]) / (rho - rho_prev[k]);
        const Vec3 vc = v_prev[k] + f * (v - v_prev[k]);
        const Vec3 xc = x_prev[k] + f * (x - x_prev[k]);
        t_exit[k] = t - engine.dt_s() * (1.0 - f);
        const Vec3 er = Vec3(xc.x(), xc.y(), 0.0).normalized();
        const Vec3 et(-er.y(), er.x(), 0.0);
        const double vr = vc.dot(er), vt = vc.dot(et);
        sum.speed += vc.norm() / (omega * R);
        sum.elevation_deg += std::atan2(vc.z(), std::hypot(vr, vt)) * 180.0 / kPi;
        sum.angle_from_tangent_deg += std::atan2(vr, vt) * 180.0 / kPi;
        sum.t_exit += omega * t_exit[k];
        ++done;
      }
      rho_prev[k] = rho;
      v_prev[k] = v;
      x_prev[k] = x;
    }
  }
  out.simulated.speed = sum.speed / n;
  out.simulated.elevation_deg = sum.elevation_deg / n;
  out.simulated.angle_from_tangent_deg = sum.angle_from_tangent_deg / n;
  out.simulated.t_exit = sum.t_exit / n;
  out.reference = cone_reference(c);
  auto rel = [](double a, double b) { return (a - b) / b; };
  out.rel_error_speed = rel(out.simulated.speed, out.reference.speed);
  out.rel_error_elevation = rel(out.simulated.elevation_deg, out.reference.elevation_deg);
  out.rel_error_angle = rel(out.simulated.angle_from_tangent_deg, out.reference.angle_from_tangent_deg);
  out.rel_error_t_exit = rel(out.simulated.t_exit, out.reference.t_exit);
  return out;
}

}  // namespace spread::dem
