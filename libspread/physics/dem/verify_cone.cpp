// `spread verify cone`: the seed's Appendix 1 in the DEM — non-interacting spheres without spin on a
// spinning cone (analytic or meshed with element size ξ), compared with the ODE reference.
#include <cmath>
#include <stdexcept>
#include <vector>

#include "libspread/physics/dem/disc_generator.hpp"
#include "libspread/physics/dem/verify.hpp"

namespace spread::dem {

namespace {

// The case in the engine's units: the cone's radius R, its speed ω (γ = g/(ω²R), Eq. 62) and the
// spheres' radius.
struct ConeScale {
  double radius_m = 0.0, omega_rad_s = 0.0, particle_radius_m = 0.0;
};

// The engine: spheres of one material on the spinning cone, wall contact alone. The cone reaches past R so
// the particle stays supported until its centre crosses ρ = R.
DemEngine cone_engine(const ConeCase& c, const ConeScale& k, ConeResult& out) {
  Material particle;
  particle.name = "cone_particle";
  particle.density_kg_m3 = 1500.0;
  particle.youngs_modulus_pa = 1e8;
  particle.restitution = 0.2;  // seed Sect. 3.3
  particle.friction_wall = c.mu;  // cone only: no particle–particle contact
  Material wall = particle;
  wall.name = "cone_wall";
  wall.rigid = true;
  DiscGeometry geom;
  geom.radius_m = k.radius_m + 4.0 * k.particle_radius_m;
  geom.cone_angle_rad = c.alpha_rad;
  geom.mesh_size_m = c.mesh_size * k.radius_m;
  WallGroup cone = make_disc(geom, k.omega_rad_s * 60.0 / (2.0 * kPi), 1, k.particle_radius_m);
  if (!cone.meshes.empty()) out.triangles = cone.meshes[0].mesh().triangles.size();
  WallSet walls;
  walls.groups.push_back(std::move(cone));
  EngineParams params;
  params.effects = effect::kWallContact;
  params.min_particle_radius_m = k.particle_radius_m;
  params.impact_speed_m_s = 2.0;  // the particle slides: normal approach speeds stay small
  return DemEngine({particle, wall}, {}, walls, params);
}

// The spheres at ρ0 R, resting on the cone (surface point at ρ_q = ρ0 R + r sin α, centre r along the
// normal), their start angles spread over a sector so that they meet different triangles of a mesh.
void place_on_cone(DemEngine& engine, const ConeCase& c, const ConeScale& k, int n) {
  const double ca = std::cos(c.alpha_rad), sa = std::sin(c.alpha_rad), ta = std::tan(c.alpha_rad);
  const double rho_q = c.rho0 * k.radius_m + k.particle_radius_m * sa;
  const double z_c = ta * rho_q + k.particle_radius_m * ca;
  for (int j = 0; j < n; ++j) {
    const double phi = 2.0 * kPi * j / n + 0.37;
    const Vec3 er(std::cos(phi), std::sin(phi), 0.0), et(-std::sin(phi), std::cos(phi), 0.0);
    engine.add_particle(c.rho0 * k.radius_m * er + Vec3(0, 0, z_c), c.v0 * k.omega_rad_s * k.radius_m * et,
                        k.particle_radius_m, 0);
  }
}

// Steps until every sphere's centre has crossed ρ = R; the sum over the spheres of their state there,
// interpolated linearly within the step of the crossing (speed over ωR, elevation and angle from the
// tangent in degrees, exit time as ωt).
ConeState run_to_rim(DemEngine& engine, const ConeCase& c, const ConeScale& k, int n) {
  const double R = k.radius_m, omega = k.omega_rad_s;
  const auto& p = engine.particles();
  const auto count = static_cast<std::size_t>(n);
  std::vector<double> rho_prev(count, c.rho0 * R), t_exit(count, -1.0);
  std::vector<Vec3> v_prev(count), x_prev(count);
  for (std::size_t j = 0; j < count; ++j) {
    v_prev[j] = p.velocity(j);
    x_prev[j] = p.position(j);
  }
  ConeState sum;
  int done = 0;
  const double t_max = 400.0 / omega;  // the reference exits near ωt ≈ 47
  while (done < n) {
    engine.step();
    const double t = engine.time_s();
    if (t > t_max) throw std::runtime_error("cone verification: a particle did not reach the rim");
    for (std::size_t j = 0; j < count; ++j) {
      if (t_exit[j] >= 0.0) continue;
      const Vec3 x = p.position(j), v = p.velocity(j);
      const double rho = std::hypot(x.x(), x.y());
      if (rho >= R) {
        const double f = (R - rho_prev[j]) / (rho - rho_prev[j]);
        const Vec3 vc = v_prev[j] + f * (v - v_prev[j]);
        const Vec3 xc = x_prev[j] + f * (x - x_prev[j]);
        t_exit[j] = t - engine.dt_s() * (1.0 - f);
        const Vec3 er = Vec3(xc.x(), xc.y(), 0.0).normalized();
        const Vec3 et(-er.y(), er.x(), 0.0);
        const double vr = vc.dot(er), vt = vc.dot(et);
        sum.speed += vc.norm() / (omega * R);
        sum.elevation_deg += std::atan2(vc.z(), std::hypot(vr, vt)) * 180.0 / kPi;
        sum.angle_from_tangent_deg += std::atan2(vr, vt) * 180.0 / kPi;
        sum.t_exit += omega * t_exit[j];
        ++done;
      }
      rho_prev[j] = rho;
      v_prev[j] = v;
      x_prev[j] = x;
    }
  }
  return sum;
}

}  // namespace

ConeResult run_cone(const ConeCase& c) {
  ConeScale k;
  k.radius_m = c.radius_m;
  k.omega_rad_s = std::sqrt(kStandardGravity_m_s2 / (c.gamma * k.radius_m));  // γ = g/(ω²R), Eq. 62
  k.particle_radius_m = c.particle_radius * k.radius_m;
  ConeResult out;
  out.mu = c.mu;
  out.mesh_size = c.mesh_size;
  DemEngine engine = cone_engine(c, k, out);
  const int n = std::max(1, c.particles);
  place_on_cone(engine, c, k, n);
  const ConeState sum = run_to_rim(engine, c, k, n);
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
