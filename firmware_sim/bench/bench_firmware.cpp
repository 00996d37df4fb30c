// Loop-step cost of the simulated ECU against its 50 ms period (20 Hz).
//
// BM_LoopStepAutomaticSolve is the worst case: every step the width set-point changes, so the step
// solves for rpm (curve scan + refinement predictions) and re-predicts the pattern at the moving disc
// speed. Each step is timed on its own; the counters report the median and the worst step and the
// worst as a fraction of the loop period.
//
// Predictions come from the C API over a real launch table: by default one built at bench start from
// scenes/default.toml by the same library code lookup_builder runs (spread::lookup::build_tables, into
// a temporary file), so the automatic-mode worst case is the one a deployed ECU sees. SPREAD_FIRMWARE_TABLES
// names another table file instead; SPREAD_FIRMWARE_MATERIAL another material (default: the table's first).
// Only a build without the C API falls back to an analytic stand-in, and the benchmark label says so.
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "firmware_sim/can/can_ecu_link.hpp"
#include "libspread/control/ecu.hpp"
#include "isobus/isobus_id.hpp"
#include "tests/firmware/analytic_predictor.hpp"
#ifdef SPREAD_FIRMWARE_HAS_CAPI
#include <unistd.h>

#include <filesystem>

#include "capi/cpp/capi_spread_predictor.hpp"
#include "libspread/io/scene/scene.hpp"
#include "lookup_builder/table_build.hpp"
#endif

namespace {

using namespace spread;  // the clock (core)
using namespace spread::firmware;
using SteadyTime = std::chrono::steady_clock;

struct PredictorChoice {
  std::unique_ptr<SpreadPredictor> predictor;
  std::string material;
  std::string label;
};

#ifdef SPREAD_FIRMWARE_HAS_CAPI
// The default scene's table, built once per process (about a second) into the temporary directory.
const std::string& default_scene_table() {
  static const std::string path = [] {
    const std::string out =
        (std::filesystem::temp_directory_path() / ("bench_firmware_default_" + std::to_string(::getpid()) + ".sqlite"))
            .string();
    const spread::scene::Scene scene = spread::scene::load_scene_file(SPREAD_DEFAULT_SCENE);
    spread::lookup::BuildOptions options;
    options.output_path = out;
    options.rebuild = true;
    spread::lookup::build_tables(scene, options);
    std::atexit([] { std::filesystem::remove(default_scene_table()); });
    return out;
  }();
  return path;
}
#endif

PredictorChoice choose_predictor() {
  PredictorChoice c;
#ifdef SPREAD_FIRMWARE_HAS_CAPI
  const char* given = std::getenv("SPREAD_FIRMWARE_TABLES");
  const std::string path = given != nullptr ? std::string(given) : default_scene_table();
  auto capi = std::make_unique<CapiSpreadPredictor>(path, 15.0);
  const char* material = std::getenv("SPREAD_FIRMWARE_MATERIAL");
  c.material = material != nullptr ? std::string(material) : capi->materials().front();
  c.label = "C API, " + (given != nullptr ? "tables " + path : std::string("scenes/default.toml table")) +
            ", material " + c.material;
  c.predictor = std::move(capi);
  return c;
#else
  c.predictor = std::make_unique<testing::AnalyticPredictor>();
  c.material = "urea";
  c.label = "analytic stand-in (this build has no C API)";
  return c;
#endif
}

// Thread CPU time [us]: on a loaded machine wall time mostly measures waiting for a core.
double thread_cpu_us() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

void report(benchmark::State& state, std::vector<double>& step_us, std::vector<double>& cpu_us, double period_us) {
  if (step_us.empty()) return;
  std::sort(step_us.begin(), step_us.end());
  std::sort(cpu_us.begin(), cpu_us.end());
  state.counters["median_us"] = step_us[step_us.size() / 2];
  state.counters["worst_us"] = step_us.back();
  state.counters["worst_per_period"] = step_us.back() / period_us;
  state.counters["median_cpu_us"] = cpu_us[cpu_us.size() / 2];
  state.counters["worst_cpu_us"] = cpu_us.back();
}

EcuCommand command(Mode mode, double width_m, const std::string& material) {
  EcuCommand c;
  c.sequence = 1;
  c.mode = static_cast<std::int32_t>(mode);
  c.rate_setpoint_kg_ha = 200.0;
  c.width_setpoint_m = width_m;
  c.ground_speed_m_s = 3.0;
  c.rpm_setpoint = 600.0;
  c.material = material;
  c.section_count = 8;
  c.section_on.fill(true);
  c.work_state = true;
  return c;
}

void BM_LoopStepAutomaticSolve(benchmark::State& state) {
  PredictorChoice choice = choose_predictor();
  ManualClock clock;
  EcuParameters parameters;
  parameters.command_timeout = std::chrono::seconds(0);
  Ecu ecu(clock, parameters, choice.predictor.get());
  // Two set-points whose first crossing lies strictly inside the curve, so each solve refines
  // (max_bisections predictions) instead of stopping at a range end: the most expensive solve.
  const RpmRange range = choice.predictor->rpm_range(choice.material);
  const WidthCurve curve = sample_width_curve(
      *choice.predictor, choice.material,
      {std::max(range.min_rpm, parameters.auto_rpm_min), std::min(range.max_rpm, parameters.auto_rpm_max)},
      parameters.solver.curve_rpm_step);
  std::vector<double> inner_widths;
  double widest_so_far = curve.width_m.front();
  for (std::size_t i = 1; i < curve.width_m.size(); ++i) {
    if (curve.width_m[i] > widest_so_far) inner_widths.push_back(curve.width_m[i]);
    widest_so_far = std::max(widest_so_far, curve.width_m[i]);
  }
  if (inner_widths.size() < 2) {
    state.SkipWithError("width curve has fewer than two inner crossings");
    return;
  }
  const double narrow_m = inner_widths.front();
  const double wide_m = inner_widths.back();
  if (ecu.apply_command(command(Mode::kAutomatic, narrow_m, choice.material))) {
    state.SkipWithError("automatic command rejected");
    return;
  }
  std::vector<double> step_us;
  std::vector<double> cpu_us;
  step_us.reserve(100000);
  cpu_us.reserve(100000);
  bool wide = false;
  for (auto _ : state) {
    // Alternate the set-point so every step re-solves and the disc keeps moving (re-prediction).
    wide = !wide;
    ecu.set_width_setpoint(wide ? wide_m : narrow_m);
    clock.advance(std::chrono::milliseconds(50));
    const auto t0 = SteadyTime::now();
    const double c0 = thread_cpu_us();
    ecu.step(0.05);
    benchmark::DoNotOptimize(ecu.status());
    cpu_us.push_back(thread_cpu_us() - c0);
    step_us.push_back(std::chrono::duration<double, std::micro>(SteadyTime::now() - t0).count());
  }
  state.SetLabel(choice.label);
  report(state, step_us, cpu_us, 50000.0);
}
BENCHMARK(BM_LoopStepAutomaticSolve)->Unit(benchmark::kMicrosecond)->Iterations(400);

void BM_LoopStepManualSteady(benchmark::State& state) {
  PredictorChoice choice = choose_predictor();
  ManualClock clock;
  EcuParameters parameters;
  parameters.command_timeout = std::chrono::seconds(0);
  Ecu ecu(clock, parameters, choice.predictor.get());
  ecu.apply_command(command(Mode::kManual, 12.0, choice.material));
  for (int i = 0; i < 400; ++i) {  // settle the disc: no re-prediction in the timed steps
    clock.advance(std::chrono::milliseconds(50));
    ecu.step(0.05);
  }
  std::vector<double> step_us;
  std::vector<double> cpu_us;
  step_us.reserve(1000000);
  cpu_us.reserve(1000000);
  for (auto _ : state) {
    clock.advance(std::chrono::milliseconds(50));
    const auto t0 = SteadyTime::now();
    const double c0 = thread_cpu_us();
    ecu.step(0.05);
    benchmark::DoNotOptimize(ecu.status());
    cpu_us.push_back(thread_cpu_us() - c0);
    step_us.push_back(std::chrono::duration<double, std::micro>(SteadyTime::now() - t0).count());
  }
  state.SetLabel(choice.label);
  report(state, step_us, cpu_us, 50000.0);
}
BENCHMARK(BM_LoopStepManualSteady)->Unit(benchmark::kMicrosecond)->Iterations(100000);

// One ISOBUS request answered (decode, status snapshot, encode, write into a recording sink).
void BM_CanRequestAnswered(benchmark::State& state) {
  ManualClock clock;
  Ecu ecu(clock, EcuParameters{});
  class CountingSink final : public isobus::can::CanFrameSink {
   public:
    bool send(const can_frame&) override { return ++sent > 0; }
    std::uint64_t sent = 0;
  } sink;
  can::CanEcuProcessor processor(ecu, clock, sink);
  // The requester is the ECU's partner task controller (its claim with a TC's NAME, then its status):
  // the ECU answers no other node.
  isobus::IsoName tc;
  tc.self_configurable = true;
  tc.device_class = isobus::kDeviceClassNonSpecific;
  tc.function = isobus::kFunctionTaskController;
  const auto tc_name = isobus::name_to_bytes(isobus::encode_name(tc));
  using isobus::can::make_frame;
  processor.handle_frame(make_frame(isobus::encode_id({6, can::kAddressClaimedPgn, 0xFF, 0x81}), tc_name.data(), 8));
  const auto status = isobus::encode_tc_status(true);
  processor.handle_frame(make_frame(isobus::encode_id({3, isobus::kProcessDataPgn, 0xFF, 0x81}), status.data(), 8));
  const isobus::ProcessDataBytes b = isobus::encode_process_data({2, 0, 390, 0});
  const can_frame request = make_frame(isobus::encode_id({3, isobus::kProcessDataPgn, 0x80, 0x81}), b.data(), 8);
  for (auto _ : state) processor.handle_frame(request);
  state.counters["answers"] = static_cast<double>(sink.sent);
}
BENCHMARK(BM_CanRequestAnswered);

}  // namespace

BENCHMARK_MAIN();
