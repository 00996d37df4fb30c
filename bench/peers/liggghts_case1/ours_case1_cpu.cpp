// libspread's side of the LIGGGHTS comparison, timed on CPU (getrusage), one simulate() call:
//   ours_case1_cpu                          the partitioned Case-1 run of bench/bench_dem.cpp (the same
//                                           bench/case1_config.hpp, ξ 5 mm mesh, one thread,
//                                           SPREAD_BENCH_DEM_DURATION seconds simulated, default 0.1)
//   ours_case1_cpu SCENE [key=value ...]    the scene as `spread simulate SCENE --set key=value ...` reads it
//                                           (compare.sh: scenes/case1.toml with the disc as an STL file)
// SPREAD_BENCH_REGISTERS=baseline|avx|avx512 limits the registers the run-time kernel choices may take
// (bench/bench_registers.hpp): the portable path's figure beside the widest on one machine.
// Prints particle-steps, launches, wall and CPU time of the simulation (the scene and mesh read excluded).
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/bench_registers.hpp"
#include "bench/case1_config.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/physics/dem/simulate.hpp"

using namespace spread;

static double cpu_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec + u.ru_stime.tv_sec + 1e-6 * u.ru_stime.tv_usec;
}

static dem::SimulationConfig config_from_args(int argc, char** argv) {
  if (argc < 2) {
    const char* env = std::getenv("SPREAD_BENCH_DEM_DURATION");
    dem::SimulationConfig c = bench::case1_config(env ? std::atof(env) : 0.1);
    if (std::getenv("SPREAD_PEER_ANALYTIC")) c.disc.mesh_size_m = 0.0;
    return c;
  }
  const std::vector<std::string> overrides(argv + 2, argv + argc);
  return dem::config_from_scene(scene::load_scene_file(argv[1], overrides));
}

int main(int argc, char** argv) {
  try {
    const std::string registers = bench::limit_registers_from_env();
    const dem::SimulationConfig c = config_from_args(argc, argv);
    const double cpu0 = cpu_s();
    const dem::SimulationResult r = dem::simulate(c);
    const double cpu = cpu_s() - cpu0;
    std::printf("registers %s\ndt_contact_s %.6g\nparticle_steps %.0f\nlaunched %zu\nwall_s %.3f\ncpu_s %.3f\n",
                registers.c_str(), r.dt_contact_s, static_cast<double>(r.particle_steps), r.launches.size(),
                r.wall_time_s, cpu);
    std::printf("particle_steps_per_s_wall %.4g\nparticle_steps_per_s_cpu %.4g\n", r.particle_steps / r.wall_time_s,
                r.particle_steps / cpu);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ours_case1_cpu: %s\n", e.what());
    return 1;
  }
}
