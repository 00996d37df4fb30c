// Rotating drum throughput: particle–particle contact steps per second on one core, a drum of
// ≥ 20,000 particles. Short run: the grid is packed with neighbours just touching (spacing 0.999 d) so
// every particle starts with its ~6 contacts, as in a settled bed, and the drum turns at Fr 0.1.
// Counter `particle_steps_per_s` = particles × steps / wall time; where the timed steps went (s): the pair
// pass with the closing half kick (`pairs_s`), the wall pass (`walls_s`), the opening kick and drift
// (`integrate_s`), the pair- and near-list upkeep (`lists_s`). SPREAD_BENCH_DRUM_STEPS sets the steps,
// SPREAD_BENCH_DRUM_THREADS the OpenMP threads (default 1; bench/peers/lammps_drum/compare.sh uses 2).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>

#include "libspread/physics/drum/drum_packing.hpp"
#include "libspread/physics/drum/drum_simulation.hpp"

namespace {

spread::drum::DrumScene bench_scene(spread::dem::Integrator integrator, double froude) {
  spread::drum::DrumScene s;
  s.source_name = "bench_drum";
  s.radius_m = 0.1;
  s.length_m = 0.09;
  s.fill_fraction = 0.4;
  s.species = {spread::drum::Species{0.004, 2500.0, 1.0}};
  s.normal_stiffness_n_m = 1000.0;
  s.integrator = integrator;
  s.contact_steps = 12.0;
  s.angular_velocity_rad_s = froude > 0.0 ? spread::drum::omega_from_froude(froude, s.radius_m) : 0.0;
  return s;
}

void run(benchmark::State& state, spread::dem::Integrator integrator, double froude = 0.1) {
  auto s = bench_scene(integrator, froude);
  if (const char* threads = std::getenv("SPREAD_BENCH_DRUM_THREADS")) s.threads = std::max(1, std::atoi(threads));
  const char* env = std::getenv("SPREAD_BENCH_DRUM_STEPS");
  const int steps = env ? std::atoi(env) : 200;
  double particle_steps = 0.0;
  std::size_t n = 0, pairs = 0;
  long long builds = 0, near_builds = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto engine = spread::drum::make_drum_engine(s, s.angular_velocity_rad_s);
    for (const auto& q : spread::drum::grid_packing(s, 0.999)) engine.add_particle(q.position_m, spread::Vec3::Zero(), q.radius_m, q.species);
    engine.step();  // first pair-list build outside the timing
    const spread::dem::EngineStats before = engine.stats();
    state.ResumeTiming();
    engine.steps(static_cast<std::size_t>(steps));
    const spread::dem::EngineStats& after = engine.stats();
    builds = static_cast<long long>(after.pair_list_builds - before.pair_list_builds);
    near_builds = static_cast<long long>(after.near_list_builds - before.near_list_builds);
    const double walls_s = after.walls_s - before.walls_s;
    state.counters["walls_s"] = walls_s;
    state.counters["pairs_s"] = after.forces_s - before.forces_s - walls_s;
    state.counters["integrate_s"] = after.integrate_s - before.integrate_s;
    state.counters["lists_s"] = after.pair_search_s - before.pair_search_s;
    n = engine.active_count();
    pairs = engine.pair_count();
    particle_steps += static_cast<double>(n) * steps;
  }
  state.counters["particles"] = static_cast<double>(n);
  state.counters["pair_list"] = static_cast<double>(pairs);
  state.counters["list_builds"] = static_cast<double>(builds);  // within the timed steps
  state.counters["near_builds"] = static_cast<double>(near_builds);  // near lists rebuilt between them
  state.counters["particle_steps_per_s"] = benchmark::Counter(particle_steps, benchmark::Counter::kIsRate);
}

void BM_DrumVerlet(benchmark::State& state) { run(state, spread::dem::Integrator::kVelocityVerlet); }
void BM_DrumGear5(benchmark::State& state) { run(state, spread::dem::Integrator::kGear5); }
// The same bed in a drum at rest: the mantle of LAMMPS' side-by-side input (bench/peers/lammps_drum,
// in.drum) does not turn, so this is the like-for-like case (in.drum_rotating turns both).
void BM_DrumVerletStatic(benchmark::State& state) { run(state, spread::dem::Integrator::kVelocityVerlet, 0.0); }
BENCHMARK(BM_DrumVerlet)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_DrumGear5)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_DrumVerletStatic)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
