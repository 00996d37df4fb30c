// A whole field's as-applied map (libspread/analysis/field, docs/field.md): a 10 ha square field (316.2 m
// a side), one headland round and tramlines at 24 m bouts, 0.5 m cells, spread with one setting's ground
// pattern: the plan, the stamping of every 0.5 m step and the field's numbers. Target: <= 10 s on one core.
//   BM_FieldTenHectares/0: the synthetic table of the tests (tests/predict/synthetic_table.hpp: twin disc,
//     "can" at 650 rpm);
//   BM_FieldTenHectares/1: a real table file given in SPREAD_BENCH_TABLE (e.g. made by
//     `lookup_builder scenes/default.toml --output X.sqlite`; "Urea" at 600 rpm), skipped without it.
//   BM_FieldTenHectares/2: the cost at a commercial 24 m spreader's throw: a stamp of the same cells filled
//     over a 40 m × 30 m ellipse (4,700 cells; the two tables' machines throw 10–15 m), uniform — its
//     numbers mean nothing, its time is the stamping's at that width.
// The prediction and its stamp are made once, outside the timing (a field run reuses them at every step).
// Counters: steps (0.5 m pieces stamped), stamp_cells (cells of the stamp), field_cv, beyond_pct.
//   BM_FieldMachineTenHectares/0, /1: the same field and tables with the ECU in the loop (machine_in_loop.hpp):
//     8 sections under section control, border mode on the headland round, 12 km/h, the ECU's 50 ms loop,
//     the discs' lag and the gates' travel; the ECU's predictions over the C API (the synthetic table written
//     to a file first). Everything a run does is timed: the ECU's width curve and its planner's searches,
//     every disc state's stamp, the loop steps and the stamping. Counters: loop_steps, stamps (stamped
//     pieces), disc_states, searches, field_cv, beyond_pct.
// Run: SPREAD_BENCH_TABLE=X.sqlite taskset -c 1 build/bench/bench_field [--benchmark_filter=...] (docs/field.md "Speed")
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "capi/cpp/capi_spread_predictor.hpp"
#include "libspread/analysis/field/as_applied.hpp"
#include "libspread/analysis/field/machine_in_loop.hpp"
#include "libspread/analysis/field/field_summary.hpp"
#include "libspread/analysis/field/plan.hpp"
#include "libspread/analysis/field/stamp_pattern.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace {

using namespace spread::field;

constexpr double kBout_m = 24.0;

// The stamp of one setting: the synthetic table's, or the file's in SPREAD_BENCH_TABLE (null without it).
std::unique_ptr<StampPattern> wide_stamp() {
  auto s = std::make_unique<StampPattern>();
  for (double y = -29.75; y < 30.0; y += 0.5) {
    for (double x = -19.75; x < 20.0; x += 0.5) {
      if ((x / 20.0) * (x / 20.0) + (y / 15.0) * (y / 15.0) > 1.0) continue;
      s->x_m.push_back(x);
      s->y_m.push_back(y - 10.0);  // behind the discs
      s->fraction.push_back(1.0);
    }
  }
  for (double& f : s->fraction) f /= static_cast<double>(s->size());
  s->landed_fraction = 1.0;
  return s;
}

std::unique_ptr<StampPattern> stamp_of(bool real_table) {
  spread::tables::TableContents contents;
  spread::predict::PredictionRequest r;
  if (real_table) {
    const char* path = std::getenv("SPREAD_BENCH_TABLE");
    if (path == nullptr) return nullptr;
    contents = spread::tables::read_table_file(path);
    r.material = "Urea";
    r.rpm = 600.0;
  } else {
    contents = spread::testing::synthetic_contents();
    r.material = "can";
    r.rpm = 650.0;
  }
  r.bout_width_m = kBout_m;
  spread::predict::Predictor predictor(std::move(contents));
  spread::predict::Prediction p;
  if (predictor.predict(r, p) != spread::predict::PredictStatus::kOk) return nullptr;
  return std::make_unique<StampPattern>(stamp_pattern(p, 0.5));
}

void BM_FieldTenHectares(benchmark::State& state) {
  const auto pattern = state.range(0) == 2 ? wide_stamp() : stamp_of(state.range(0) == 1);
  if (!pattern) {
    state.SkipWithError("no table (set SPREAD_BENCH_TABLE to a table with Urea at 600 rpm)");
    return;
  }
  const double side_m = std::sqrt(1e5);
  const Boundary field = make_boundary({{0, 0}, {side_m, 0}, {side_m, side_m}, {0, side_m}}, "local", "bench");
  RunSettings run;
  run.target_rate_kg_ha = 200.0;
  run.bout_width_m = kBout_m;
  FieldSummary summary;
  std::size_t steps = 0;
  for (auto _ : state) {
    PlanSettings plan;
    plan.bout_width_m = kBout_m;
    plan.headland_passes = 1;
    const auto passes = plan_field(field, plan);
    const AsApplied applied = spread_passes(field, passes, {pattern.get(), 1}, run);
    summary = summarise(applied, field, run.target_rate_kg_ha);
    steps = applied.steps;
    benchmark::DoNotOptimize(summary);
  }
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["stamp_cells"] = static_cast<double>(pattern->size());
  state.counters["field_cv"] = summary.cv;
  state.counters["beyond_pct"] = 100.0 * summary.beyond_fraction;
}
BENCHMARK(BM_FieldTenHectares)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_FieldMachineTenHectares(benchmark::State& state) {
  const bool real_table = state.range(0) == 1;
  std::string path;
  if (real_table) {
    const char* given = std::getenv("SPREAD_BENCH_TABLE");
    if (given == nullptr) {
      state.SkipWithError("no table (set SPREAD_BENCH_TABLE to a table with Urea at 600 rpm)");
      return;
    }
    path = given;
  } else {
    path = (std::filesystem::temp_directory_path() / "spread_bench_field_machine.sqlite").string();
    spread::testing::write_synthetic_table(path);
  }
  spread::predict::Predictor predictor(spread::tables::read_table_file(path));
  spread::firmware::CapiSpreadPredictor ecu(path);
  spread::predict::PredictionRequest field;
  field.material = real_table ? "Urea" : "can";
  field.bout_width_m = kBout_m;
  MachineSettings s;
  s.target_rate_kg_ha = 200.0;
  s.bout_width_m = kBout_m;
  s.rpm = real_table ? 600.0 : 650.0;
  s.border = true;
  const double side_m = std::sqrt(1e5);
  const Boundary boundary = make_boundary({{0, 0}, {side_m, 0}, {side_m, side_m}, {0, side_m}}, "local", "bench");
  FieldSummary summary;
  MachineRun last;
  for (auto _ : state) {
    PlanSettings plan;
    plan.bout_width_m = kBout_m;
    plan.headland_passes = 1;
    last = run_machine(boundary, plan_field(boundary, plan), ecu, predictor, field, s);
    summary = summarise(last.applied, boundary, s.target_rate_kg_ha);
    benchmark::DoNotOptimize(summary);
  }
  state.counters["loop_steps"] = static_cast<double>(last.loop_steps);
  state.counters["stamps"] = static_cast<double>(last.applied.steps);
  state.counters["disc_states"] = static_cast<double>(last.stamps_built);
  state.counters["searches"] = static_cast<double>(last.planner_searches);
  state.counters["field_cv"] = summary.cv;
  state.counters["beyond_pct"] = 100.0 * summary.beyond_fraction;
}
BENCHMARK(BM_FieldMachineTenHectares)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
