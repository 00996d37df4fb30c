// Runs only the partitioned Case-1 simulation of bench/bench_dem.cpp (the same bench/case1_config.hpp,
// ξ 5 mm mesh, one thread, SPREAD_BENCH_DEM_DURATION seconds simulated, default 0.1) and prints
// particle-steps, wall and CPU time (getrusage), so the LIGGGHTS run can be compared on CPU time too.
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "bench/case1_config.hpp"
#include "libspread/physics/dem/simulate.hpp"

using namespace spread;

static double cpu_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec + u.ru_stime.tv_sec + 1e-6 * u.ru_stime.tv_usec;
}

int main() {
  const char* env = std::getenv("SPREAD_BENCH_DEM_DURATION");
  dem::SimulationConfig c = bench::case1_config(env ? std::atof(env) : 0.1);
  if (std::getenv("SPREAD_PEER_ANALYTIC")) c.disc.mesh_size_m = 0.0;
  const double cpu0 = cpu_s();
  const dem::SimulationResult r = dem::simulate(c);
  const double cpu = cpu_s() - cpu0;
  std::printf("dt_contact_s %.6g\nparticle_steps %.0f\nlaunched %zu\nwall_s %.3f\ncpu_s %.3f\n", r.dt_contact_s,
              static_cast<double>(r.particle_steps), r.launches.size(), r.wall_time_s, cpu);
  std::printf("particle_steps_per_s_wall %.4g\nparticle_steps_per_s_cpu %.4g\n", r.particle_steps / r.wall_time_s,
              r.particle_steps / cpu);
}
