// Cost of the spread metrics in one prediction: 512 left-disc landings of a twin-disc machine
// accumulated into 0.5 m trays, the CV(W) curves (to-and-fro and racetrack) on the tray grid, the
// effective working widths, the throw width and R̄/ξ. The metrics should be a negligible part of a
// prediction (the flight of the samples dominates).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "libspread/core/unit_uniform.hpp"
#include "libspread/analysis/metrics/metrics.hpp"

namespace sm = spread::metrics;

namespace {

struct Landings {
  std::vector<double> x_m, y_m, mass_kg;
};

// A plausible left-disc throw: a ring sector behind and to the left of the disc.
Landings make_landings(int count) {
  std::mt19937_64 rng(2024);
  auto uniform = [&rng] { return spread::unit_uniform(rng()); };
  Landings l;
  for (int i = 0; i < count; ++i) {
    const double r_m = 12.0 + 5.0 * (uniform() + uniform() + uniform() - 1.5);
    const double angle_rad = (150.0 + 100.0 * uniform()) * 3.14159265358979323846 / 180.0;
    l.x_m.push_back(r_m * std::cos(angle_rad));
    l.y_m.push_back(r_m * std::sin(angle_rad));
    l.mass_kg.push_back(1e-4);
  }
  return l;
}

void BM_MetricsOfOnePrediction(benchmark::State& state) {
  const Landings l = make_landings(static_cast<int>(state.range(0)));
  const sm::MachineLayout twin{2, 0.9};
  const sm::TrayLayout trays = sm::tray_layout_covering(25.0, 0.5);
  std::vector<double> tray(static_cast<std::size_t>(trays.tray_count));
  std::vector<double> widths_m, cv_tf, cv_rt;
  for (int n = 2; n <= trays.tray_count; ++n) widths_m.push_back(0.5 * n);
  cv_tf.resize(widths_m.size());
  cv_rt.resize(widths_m.size());
  for (auto _ : state) {
    std::fill(tray.begin(), tray.end(), 0.0);
    sm::accumulate_transverse(l.x_m, l.mass_kg, twin, trays, tray);
    sm::cv_curve(tray, trays, widths_m, sm::Overlap::kToAndFro, cv_tf);
    sm::cv_curve(tray, trays, widths_m, sm::Overlap::kRacetrack, cv_rt);
    double w_tf = sm::effective_working_width(tray, trays, sm::Overlap::kToAndFro, 0.15);
    double w_rt = sm::effective_working_width(tray, trays, sm::Overlap::kRacetrack, 0.15);
    double throw_m = sm::throw_width(tray, trays);
    sm::RadialStats radial = sm::radial_statistics(l.x_m, l.y_m, l.mass_kg);
    benchmark::DoNotOptimize(w_tf);
    benchmark::DoNotOptimize(w_rt);
    benchmark::DoNotOptimize(throw_m);
    benchmark::DoNotOptimize(radial);
    benchmark::DoNotOptimize(cv_tf.data());
    benchmark::DoNotOptimize(cv_rt.data());
  }
  state.counters["trays"] = trays.tray_count;
  state.counters["widths"] = static_cast<double>(widths_m.size());
}
BENCHMARK(BM_MetricsOfOnePrediction)->Arg(512)->Unit(benchmark::kMicrosecond);

// What a prediction's summary needs (the C API path): trays, both effective widths, the CV at the
// to-and-fro width, throw width and R̄/ξ — without the full CV(W) curves.
void BM_PredictionSummary(benchmark::State& state) {
  const Landings l = make_landings(512);
  const sm::MachineLayout twin{2, 0.9};
  const sm::TrayLayout trays = sm::tray_layout_covering(25.0, 0.5);
  std::vector<double> tray(static_cast<std::size_t>(trays.tray_count));
  for (auto _ : state) {
    std::fill(tray.begin(), tray.end(), 0.0);
    sm::accumulate_transverse(l.x_m, l.mass_kg, twin, trays, tray);
    double w_tf = sm::effective_working_width(tray, trays, sm::Overlap::kToAndFro, 0.15);
    double w_rt = sm::effective_working_width(tray, trays, sm::Overlap::kRacetrack, 0.15);
    double cv = sm::cv_at_width(tray, trays, w_tf, sm::Overlap::kToAndFro);
    double throw_m = sm::throw_width(tray, trays);
    sm::RadialStats radial = sm::radial_statistics(l.x_m, l.y_m, l.mass_kg);
    benchmark::DoNotOptimize(w_tf);
    benchmark::DoNotOptimize(w_rt);
    benchmark::DoNotOptimize(cv);
    benchmark::DoNotOptimize(throw_m);
    benchmark::DoNotOptimize(radial);
  }
}
BENCHMARK(BM_PredictionSummary)->Unit(benchmark::kMicrosecond);

void BM_AccumulateTransverse(benchmark::State& state) {
  const Landings l = make_landings(512);
  const sm::TrayLayout trays = sm::tray_layout_covering(25.0, 0.5);
  std::vector<double> tray(static_cast<std::size_t>(trays.tray_count));
  for (auto _ : state) {
    std::fill(tray.begin(), tray.end(), 0.0);
    double lost = sm::accumulate_transverse(l.x_m, l.mass_kg, sm::MachineLayout{2, 0.9}, trays, tray);
    benchmark::DoNotOptimize(lost);
    benchmark::DoNotOptimize(tray.data());
  }
}
BENCHMARK(BM_AccumulateTransverse)->Unit(benchmark::kMicrosecond);

void BM_EffectiveWorkingWidth(benchmark::State& state) {
  const Landings l = make_landings(512);
  const sm::TrayLayout trays = sm::tray_layout_covering(25.0, 0.5);
  std::vector<double> tray(static_cast<std::size_t>(trays.tray_count), 0.0);
  sm::accumulate_transverse(l.x_m, l.mass_kg, sm::MachineLayout{2, 0.9}, trays, tray);
  for (auto _ : state) {
    double w = sm::effective_working_width(tray, trays, sm::Overlap::kToAndFro, 0.15);
    benchmark::DoNotOptimize(w);
  }
}
BENCHMARK(BM_EffectiveWorkingWidth)->Unit(benchmark::kMicrosecond);

// Both working widths by the O(T log T) search, the to-and-fro one with the outgoing pattern mirrored (still
// air: one FFT pair) against a return pass of its own (wind: the racetrack FFT pair and the two-pattern
// pair), at 0.5 m and at 0.05 m trays (T = 100 and 1,000 over ±25 m). Arg: 0 one pattern, 1 with the
// return pass; the second arg the tray width in cm.
void BM_WorkingWidthsWithReturnPass(benchmark::State& state) {
  const Landings l = make_landings(512);
  const double tray_width_m = 0.01 * static_cast<double>(state.range(1));
  const sm::TrayLayout trays = sm::tray_layout_covering(25.0, tray_width_m);
  std::vector<double> out(static_cast<std::size_t>(trays.tray_count), 0.0), back(out.size(), 0.0);
  sm::accumulate_transverse_kernel(l.x_m, l.mass_kg, trays, 1.0, out);
  std::vector<double> shifted(l.x_m);  // the return pass: its own pattern, shifted by its own wind
  for (double& x : shifted) x = -x - 0.8;
  sm::accumulate_transverse_kernel(shifted, l.mass_kg, trays, 1.0, back);
  std::vector<double> scratch(sm::working_widths_scratch_size(trays.tray_count));
  const bool own_return = state.range(0) != 0;
  for (auto _ : state) {
    const sm::WorkingWidths w = own_return ? sm::working_widths(out, back, trays, 0.15, scratch)
                                           : sm::working_widths(out, trays, 0.15, scratch);
    benchmark::DoNotOptimize(w.to_and_fro.width_m);
  }
  state.counters["trays"] = trays.tray_count;
}
BENCHMARK(BM_WorkingWidthsWithReturnPass)->Args({0, 50})->Args({1, 50})->Args({0, 5})->Args({1, 5})->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
