// Runs only the partitioned Case-1 simulation of bench/bench_dem.cpp (same config, ξ 5 mm mesh, one
// thread, SPREAD_BENCH_DEM_DURATION seconds simulated, default 0.1) and prints particle-steps, wall and
// CPU time (getrusage), so the LIGGGHTS run can be compared on CPU time too.
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "libspread/dem/simulate.hpp"

using namespace spread;

static double cpu_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec + u.ru_stime.tv_sec + 1e-6 * u.ru_stime.tv_usec;
}

int main() {
  const char* env = std::getenv("SPREAD_BENCH_DEM_DURATION");
  dem::SimulationConfig c;  // copied from bench/bench_dem.cpp case1()
  dem::Material granule;
  granule.name = "case1 granule";
  granule.density_kg_m3 = 1800;
  granule.young_modulus_pa = 5e7;
  granule.poisson_ratio = 0.25;
  granule.restitution = 0.5;
  granule.friction = 0.35;
  dem::Material disc = granule;
  disc.name = "disc";
  disc.rigid = true;
  c.materials = {granule, disc};
  c.disc.radius_m = 0.29;
  c.disc.cone_angle_rad = 0.157;
  c.disc.z_apex_m = -0.29 * std::tan(0.157);
  c.disc.vane_count = 2;
  c.disc.vane_height_m = 0.036;
  c.disc.mesh_size_m = std::getenv("SPREAD_PEER_ANALYTIC") ? 0.0 : 0.005;
  c.rpm = 500;
  c.disc_height_m = 0.28;
  c.inlet.radius_m = 0.0145;
  c.inlet.mass_rate_kg_s = 0.11;
  c.inlet.diameter_mean_m = 3.2e-3;
  c.inlet.diameter_sd_m = 0.6e-3;
  c.inlet.release_speed_m_s = 0.5;
  const double surface = c.disc.z_apex_m + std::tan(0.157) * 0.1;
  c.inlet.centre_m = Vec3(0.1 * std::cos(1.0), 0.1 * std::sin(1.0), surface + 0.05);
  c.engine.contact_steps = 15;
  c.engine.threads = 1;
  c.duration_s = env ? std::atof(env) : 0.1;
  c.flight_effects = flight::kDrag;
  c.flight_threads = 1;
  const double cpu0 = cpu_s();
  const dem::SimulationResult r = dem::simulate(c);
  const double cpu = cpu_s() - cpu0;
  std::printf("dt_contact_s %.6g\nparticle_steps %.0f\nlaunched %zu\nwall_s %.3f\ncpu_s %.3f\n", r.dt_contact_s,
              static_cast<double>(r.particle_steps), r.launches.size(), r.wall_time_s, cpu);
  std::printf("particle_steps_per_s_wall %.4g\nparticle_steps_per_s_cpu %.4g\n", r.particle_steps / r.wall_time_s,
              r.particle_steps / cpu);
}
