// Rotating drum throughput (issue 7): particle–particle contact steps per second on one core, a drum of
// ≥ 20,000 particles. Short run: the grid is packed with neighbours just touching (spacing 0.999 d) so
// every particle starts with its ~6 contacts, as in a settled bed, and the drum turns at Fr 0.1.
// Counter `particle_steps_per_s` = particles × steps / wall time. SPREAD_BENCH_DRUM_STEPS sets the steps.
#include <benchmark/benchmark.h>

#include <cstdlib>

#include "libspread/drum/drum_packing.hpp"
#include "libspread/drum/drum_simulation.hpp"

namespace {

spread::drum::DrumScene bench_scene(spread::dem::Integrator integrator) {
  spread::drum::DrumScene s;
  s.source_name = "bench_drum";
  s.radius_m = 0.1;
  s.length_m = 0.09;
  s.fill_fraction = 0.4;
  s.species = {spread::drum::Species{0.004, 2500.0, 1.0}};
  s.normal_stiffness_n_m = 1000.0;
  s.integrator = integrator;
  s.contact_steps = 12.0;
  s.angular_velocity_rad_s = spread::drum::omega_from_froude(0.1, s.radius_m);
  return s;
}

void run(benchmark::State& state, spread::dem::Integrator integrator) {
  const auto s = bench_scene(integrator);
  const char* env = std::getenv("SPREAD_BENCH_DRUM_STEPS");
  const int steps = env ? std::atoi(env) : 200;
  double particle_steps = 0.0;
  std::size_t n = 0, pairs = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto engine = spread::drum::make_drum_engine(s, s.angular_velocity_rad_s);
    for (const auto& q : spread::drum::grid_packing(s, 0.999)) engine.add_particle(q.position_m, spread::Vec3::Zero(), q.radius_m, q.species);
    engine.step();  // first pair-list build outside the timing
    state.ResumeTiming();
    for (int k = 0; k < steps; ++k) engine.step();
    n = engine.active_count();
    pairs = engine.pair_count();
    particle_steps += static_cast<double>(n) * steps;
  }
  state.counters["particles"] = static_cast<double>(n);
  state.counters["pair_list"] = static_cast<double>(pairs);
  state.counters["particle_steps_per_s"] = benchmark::Counter(particle_steps, benchmark::Counter::kIsRate);
}

void BM_DrumVerlet(benchmark::State& state) { run(state, spread::dem::Integrator::kVelocityVerlet); }
void BM_DrumGear5(benchmark::State& state) { run(state, spread::dem::Integrator::kGear5); }
BENCHMARK(BM_DrumVerlet)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_DrumGear5)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
