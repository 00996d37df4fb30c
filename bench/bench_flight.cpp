// Cost and accuracy of one granule flight (libspread/physics/flight). Each benchmark iteration flies one
// trajectory from a fixed set of typical launches (3.2 mm, 1500 kg/m³, 25–35 m/s from 0.8 m,
// drag + magnus + spin_decay); the counter error_mm is the largest landing distance over that set from a
// tight Dormand–Prince reference (rtol = atol = 1e-12), computed outside the timed loop.
//   build-flight/bench/bench_flight --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "libspread/core/unit_uniform.hpp"
#include "libspread/physics/flight/flight.hpp"

namespace {

using namespace spread;
using namespace spread::flight;

constexpr EffectSet kDiscEffects = kDrag | kMagnus | kSpinDecay;
const Granule kGranule{3.2e-3, 1500.0};

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * spread::unit_uniform(rng());
}

// 256 launches off a disc rim of radius 0.3 m at 0.8 m height, mostly tangential, seeded.
const std::vector<State>& launches() {
  static const std::vector<State> set = [] {
    std::mt19937_64 rng(42);
    std::vector<State> out(256);
    for (State& s : out) {
      const double angle = uniform(rng, 0.0, 2.0 * kPi);
      const double speed = uniform(rng, 25.0, 35.0);
      const double elevation = uniform(rng, -0.05, 0.15);  // rad
      const double outward = uniform(rng, 0.3, 0.6);        // radial share of the horizontal speed
      const Vec3 radial(std::cos(angle), std::sin(angle), 0.0);
      const Vec3 tangential(-std::sin(angle), std::cos(angle), 0.0);
      const Vec3 horizontal = (outward * radial + std::sqrt(1.0 - outward * outward) * tangential);
      s.position_m = Vec3(0.3 * radial.x(), 0.3 * radial.y(), 0.8);
      s.velocity_m_s = speed * (std::cos(elevation) * horizontal + Vec3(0, 0, std::sin(elevation)));
      s.spin_rad_s = Vec3(uniform(rng, -200, 200), uniform(rng, -200, 200), uniform(rng, -800, 800));
    }
    return out;
  }();
  return set;
}

const std::vector<Landing>& reference() {
  static const std::vector<Landing> ref = [] {
    Settings tight;
    tight.rel_tol = 1e-12;
    tight.abs_tol = 1e-12;
    tight.dt_s = 1e-4;
    std::vector<Landing> out;
    for (const State& s : launches()) out.push_back(fly_to_ground(kGranule, s, 0.0, Air{}, kDiscEffects, tight));
    return out;
  }();
  return ref;
}

double max_error_mm(const Settings& settings) {
  double worst = 0.0;
  for (std::size_t i = 0; i < launches().size(); ++i) {
    const Landing l = fly_to_ground(kGranule, launches()[i], 0.0, Air{}, kDiscEffects, settings);
    worst = std::max(worst, 1e3 * (l.state.position_m - reference()[i].state.position_m).norm());
  }
  return worst;
}

void run(benchmark::State& state, const Settings& settings, EffectSet effects = kDiscEffects) {
  const auto& set = launches();
  std::size_t i = 0;
  long steps = 0;
  for (auto _ : state) {
    const Landing l = fly_to_ground(kGranule, set[i], 0.0, Air{}, effects, settings);
    benchmark::DoNotOptimize(l);
    steps += l.steps;
    i = (i + 1) % set.size();
  }
  state.counters["steps"] = static_cast<double>(steps) / static_cast<double>(state.iterations());
  if (effects == kDiscEffects) state.counters["error_mm"] = max_error_mm(settings);
}

void BM_Rk4(benchmark::State& state) {
  Settings settings;
  settings.scheme = Scheme::kRk4;
  settings.dt_s = static_cast<double>(state.range(0)) * 1e-4;  // argument in units of 0.1 ms
  run(state, settings);
}
BENCHMARK(BM_Rk4)->Arg(1)->Arg(10)->Arg(50)->Arg(200)->Arg(500)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_DormandPrince(benchmark::State& state) {
  Settings settings;
  settings.rel_tol = std::pow(10.0, -static_cast<double>(state.range(0)));
  settings.abs_tol = settings.rel_tol;
  run(state, settings);
}
BENCHMARK(BM_DormandPrince)->DenseRange(3, 9)->Unit(benchmark::kMicrosecond);

// The Settings defaults (rtol 1e-6, atol 1e-7, first trial step 1 ms).
void BM_DormandPrinceDefaults(benchmark::State& state) { run(state, Settings{}); }
BENCHMARK(BM_DormandPrinceDefaults)->Unit(benchmark::kMicrosecond);

// First trial step (ms) at rtol = atol = 1e-3: how much the start-up costs.
void BM_DormandPrinceFirstStep(benchmark::State& state) {
  Settings settings;
  settings.rel_tol = 1e-3;
  settings.abs_tol = 1e-3;
  settings.dt_s = static_cast<double>(state.range(0)) * 1e-3;
  run(state, settings);
}
BENCHMARK(BM_DormandPrinceFirstStep)->Arg(1)->Arg(10)->Arg(50)->Unit(benchmark::kMicrosecond);

// "An effect that is off costs nothing": DP 1e-3 with fewer effects.
void BM_DormandPrinceEffects(benchmark::State& state) {
  Settings settings;
  settings.rel_tol = 1e-3;
  settings.abs_tol = 1e-3;
  run(state, settings, static_cast<EffectSet>(state.range(0)));
}
BENCHMARK(BM_DormandPrinceEffects)
    ->Arg(0)
    ->Arg(kDrag)
    ->Arg(kDrag | kMagnus)
    ->Arg(kDrag | kMagnus | kSpinDecay)
    ->Unit(benchmark::kMicrosecond);

// A whole pattern: 256 launches in one call, one thread (the C API's budget is ≤ 1 ms for this, with
// landings within 1 cm): DP at rtol = atol = 1e-4 (1e-3 misses 1 cm on the worst launch).
void BM_Pattern256OneThread(benchmark::State& state) {
  Settings settings;
  settings.rel_tol = 1e-4;
  settings.abs_tol = 1e-4;
  std::vector<Landing> out(launches().size());
  for (auto _ : state) {
    fly_batch(std::span<const Granule>(&kGranule, 1), launches(), 0.0, Air{}, kDiscEffects, settings, out, 1);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["error_mm"] = max_error_mm(settings);
}
BENCHMARK(BM_Pattern256OneThread)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
