// One full prediction: twin disc, 0.5 m trays, N launch samples per row from the
// analytic launch model of the bundled scene (scenes/default.toml, material "Urea"), at an rpm between
// two rows (pairwise interpolation). Target: <= 1 ms on one core with every landing within 1 cm of a
// tight-tolerance reference (Dormand–Prince rel/abs 1e-11). Beside it, in the same run, plain fixed-step
// RK4 at Δt = 1 ms and its landing error. Counters:
//   max_landing_error_m  largest distance between a landing and its reference landing (both discs)
//   flights              trajectories per prediction
//   working_width_m      to-and-fro working width at CV 15 % (sanity: the same for every integrator)
//
// The product's default table (2000 DEM launch samples per row, runs recording "flight_effects":"drag")
// through the C API with the default effects (SPREAD_EFFECTS_AS_TABLE), still air and a 3 m/s lateral
// crosswind (which flies the right disc too): BM_PredictCApiDrag/<samples per row>/<wind m/s>/<dem>.
// dem = 0: analytic rows (pairwise interpolation: one flight per sample and disc). dem = 1: the same
// launches marked as DEM rows, so the prediction interpolates by quantile cells as it does on a real DEM
// table: every granule of both rows lands (n_a + n_b samples per disc).
// BM_PredictCApiFile: a real table file given in SPREAD_BENCH_TABLE (e.g. made by
// `lookup_builder scenes/default.toml --output X.sqlite`), skipped without it. On a drag-only table in
// the landing grid's domain the landings come from the landing grid (flights = 0).
// BM_PredictLandingGrid/<wind m/s>/<grid>: the same file through the Predictor with the
// grid on (1) and off (0: every granule flown), at 560 rpm, with max_landing_error_m against every
// granule flown at the tight reference tolerance.
// Run: build-<dir>/bench/bench_predict [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "libspread/physics/launch/analytic_launch.hpp"
#include "libspread/analysis/predict/flight_defaults.hpp"
#include "libspread/analysis/predict/landing_grid.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "bench/predict_loop.hpp"
#include "spread/spread.h"

namespace {

constexpr const char* kMaterial = "Urea";
constexpr double kRpm = 560.0;  // between the 525 and 600 rpm rows

std::string scene_path() {
  return (std::filesystem::path(__FILE__).parent_path().parent_path() / "scenes" / "default.toml").string();
}

// The bundled scene's table, with `samples` launch samples per row, in memory. stats_json "{}" records no
// flight effects (a prediction then flies all of them, the meaning of tables made before runs recorded
// them); `source` "dem" makes the predictor interpolate by quantile cells.
spread::tables::TableContents make_contents(int samples, const std::string& stats_json = "{}",
                                            const std::string& source = "analytic") {
  const auto scene = spread::scene::load_scene_file(scene_path());
  spread::tables::TableContents c;
  c.machine.name = scene.machine.name;
  c.machine.disc_radius_m = scene.machine.disc_radius_m;
  c.machine.disc_height_m = scene.machine.disc_height_m;
  c.machine.disc_spacing_m = scene.machine.disc_spacing_m;
  c.machine.disc_count = scene.machine.disc_count;
  c.machine.vane_count = scene.machine.vane_count;
  c.machine.cone_angle_rad = scene.machine.cone_angle_rad;
  c.machine.rotation_sense = scene.machine.rotation_sense;
  const auto* material = scene.find_material(kMaterial);
  c.materials.push_back(*material);
  for (double rpm : scene.sweep_rpms()) {
    spread::tables::Run run;
    run.material = material->name;
    run.rpm = rpm;
    run.source = source;
    run.samples = spread::launch::analytic_launch_samples(scene.machine, *material, rpm, scene.inlet, samples,
                                                          scene.numerics.seed);
    run.scene_text = "bench";
    run.scene_hash = "0";
    run.software_version = SPREAD_VERSION_STRING;
    run.created_utc = "2024-01-01T00:00:00Z";
    run.stats_json = stats_json;
    run.convergence_json = "[]";
    c.runs.push_back(std::move(run));
  }
  return c;
}

spread::predict::PredictionRequest request() {
  spread::predict::PredictionRequest r;
  r.material = kMaterial;
  r.rpm = kRpm;
  return r;
}

struct Landings {
  std::vector<double> x, y;
};
Landings landings_with(spread::predict::Predictor& p, const spread::flight::Settings& settings) {
  p.set_flight_settings(settings);
  spread::predict::Prediction out;
  p.predict(request(), out);
  return {{out.landing_x_m.begin(), out.landing_x_m.end()}, {out.landing_y_m.begin(), out.landing_y_m.end()}};
}

double max_distance(const Landings& a, const Landings& b) {
  double worst = 0.0;
  for (std::size_t k = 0; k < a.x.size(); ++k) worst = std::max(worst, std::hypot(a.x[k] - b.x[k], a.y[k] - b.y[k]));
  return worst;
}

void run_predictor(benchmark::State& state, const spread::flight::Settings& settings) {
  spread::predict::Predictor p(make_contents(static_cast<int>(state.range(0))));
  const Landings reference = landings_with(p, spread::predict::reference_flight_settings());
  const Landings tested = landings_with(p, settings);
  spread::predict::Prediction out;
  for (auto _ : state) {
    p.predict(request(), out);
    // On a copy: DoNotOptimize's "+r,m" asm constraint on a struct member was seen to clobber it (a
    // double in a general register) with this toolchain.
    double width_m = out.working_width_to_and_fro_m;
    benchmark::DoNotOptimize(width_m);
  }
  const double error_m = max_distance(tested, reference);
  state.counters["max_landing_error_m"] = error_m;
  state.counters["flights"] = out.flights;
  state.counters["working_width_m"] = out.working_width_to_and_fro_m;
}

void BM_PredictDormandPrince(benchmark::State& state) { run_predictor(state, spread::predict::default_flight_settings()); }
void BM_PredictRk4Fixed1ms(benchmark::State& state) { run_predictor(state, spread::predict::fixed_step_rk4_settings(1e-3)); }

// One table file through the C API: spread_predict in a loop with `def`.
void predict_file(benchmark::State& state, const std::string& path, spread_prediction_def def) {
  spread_tables* tables = nullptr;
  if (spread_open(path.c_str(), &tables) != SPREAD_OK) {
    state.SkipWithError("spread_open failed");
    return;
  }
  spread_prediction result{};
  if (!spread::bench::time_spread_predict(state, tables, def, result)) {
    spread_close(tables);
    return;
  }
  state.counters["flights"] = result.flights;
  state.counters["samples"] = static_cast<double>(result.sample_count);
  state.counters["working_width_m"] = result.working_width_to_and_fro_m;
  spread_close(tables);
}

// The table in memory written to a temporary file with the tables writer.
std::string write_table(const spread::tables::TableContents& contents, const std::string& name) {
  const std::string path = (std::filesystem::temp_directory_path() / (name + ".sqlite")).string();
  std::filesystem::remove(path);
  spread::tables::TableWriter writer(path);
  writer.write_machine(contents.machine);
  writer.write_materials(contents.materials);
  for (const auto& run : contents.runs) writer.write_run(run);
  return path;
}

spread_prediction_def capi_request() {
  spread_prediction_def def = spread_prediction_def_default();
  def.material = kMaterial;
  def.rpm = kRpm;
  return def;
}

// The same prediction through the C API (file written with the tables writer, then spread_open).
void BM_PredictCApi(benchmark::State& state) {
  const std::string path =
      write_table(make_contents(static_cast<int>(state.range(0))), "bench_predict_" + std::to_string(state.range(0)));
  predict_file(state, path, capi_request());
  std::filesystem::remove(path);
}

// The default table's setting: runs record "flight_effects":"drag", the request keeps the default
// effects (SPREAD_EFFECTS_AS_TABLE); range(1) = lateral wind (m/s), range(2) = 1 for DEM-marked rows.
void BM_PredictCApiDrag(benchmark::State& state) {
  const int samples = static_cast<int>(state.range(0));
  const bool dem = state.range(2) != 0;
  const std::string path = write_table(make_contents(samples, R"({"flight_effects":"drag"})", dem ? "dem" : "analytic"),
                                       "bench_predict_drag_" + std::to_string(samples) + (dem ? "_dem" : ""));
  spread_prediction_def def = capi_request();
  def.wind_m_s[0] = static_cast<double>(state.range(1));
  predict_file(state, path, def);
  std::filesystem::remove(path);
}

// SPREAD_BENCH_TABLE, or null after marking the benchmark skipped.
const char* bench_table(benchmark::State& state) {
  const char* path = std::getenv("SPREAD_BENCH_TABLE");
  if (path == nullptr || *path == '\0') {
    state.SkipWithError("set SPREAD_BENCH_TABLE to a table file (lookup_builder scenes/default.toml --output X)");
    return nullptr;
  }
  return path;
}

// spread_open of a real table file (SPREAD_BENCH_TABLE) with a counting allocator: the time to open
// and close it, and counters handle_bytes (every block the handle holds after spread_open, its own
// workspace included) and workspace_bytes (one more workspace, spread_workspace_create).
struct CountingMemory {
  std::size_t held = 0;
  static void* alloc(void* user, std::size_t size, std::size_t alignment) {
    static_cast<CountingMemory*>(user)->held += size;
    return std::aligned_alloc(alignment < alignof(std::max_align_t) ? alignof(std::max_align_t) : alignment,
                              (size + alignment - 1) / alignment * alignment);
  }
  static void release(void* user, void* pointer, std::size_t size) {
    static_cast<CountingMemory*>(user)->held -= size;
    std::free(pointer);
  }
};

void BM_OpenFile(benchmark::State& state) {
  const char* path = bench_table(state);
  if (path == nullptr) return;
  CountingMemory memory;
  const spread_allocator allocator{&CountingMemory::alloc, &CountingMemory::release, &memory};
  std::size_t handle_bytes = 0, workspace_bytes = 0;
  for (auto _ : state) {
    spread_tables* tables = nullptr;
    if (spread_open_with_allocator(path, &allocator, &tables) != SPREAD_OK) {
      state.SkipWithError(spread_last_error_detail());
      return;
    }
    handle_bytes = memory.held;
    spread_workspace* workspace = nullptr;
    spread_workspace_create(tables, &workspace);
    workspace_bytes = memory.held - handle_bytes;
    spread_workspace_free(workspace);
    spread_close(tables);
  }
  state.counters["handle_bytes"] = static_cast<double>(handle_bytes);
  state.counters["workspace_bytes"] = static_cast<double>(workspace_bytes);
}

// A real table file (SPREAD_BENCH_TABLE); range(0) = lateral wind (m/s), range(1) = rpm (560: between two
// rows of the default scene's sweep, both rows fly; 600: on a row, that row alone).
void BM_PredictCApiFile(benchmark::State& state) {
  const char* path = bench_table(state);
  if (path == nullptr) return;
  spread_prediction_def def = capi_request();
  def.wind_m_s[0] = static_cast<double>(state.range(0));
  def.rpm = static_cast<double>(state.range(1));
  predict_file(state, path, def);
}

// Each disc at its own setting against both discs alike, on a real table file (SPREAD_BENCH_TABLE):
// range(0) = lateral wind (m/s); range(1) = 0: both discs at 560 rpm, 1: the right disc at 580 rpm (the
// same rows), 2: the right disc's drop point turned 10 degrees, 3: the right disc at 650 rpm (rows of its
// own).
void BM_PredictCApiFileDiscs(benchmark::State& state) {
  const char* path = bench_table(state);
  if (path == nullptr) return;
  spread_prediction_def def = capi_request();
  def.wind_m_s[0] = static_cast<double>(state.range(0));
  def.rpm = 560.0;
  if (state.range(1) == 1) def.disc_rpm[1] = 580.0;
  if (state.range(1) == 2) def.disc_drop_point_turn_rad[1] = 10.0 * std::numbers::pi / 180.0;
  if (state.range(1) == 3) def.disc_rpm[1] = 650.0;
  predict_file(state, path, def);
}

// The C API handle of the benchmark's table file (SPREAD_BENCH_TABLE), or null with the benchmark skipped.
spread_tables* open_bench_table(benchmark::State& state) {
  const char* path = bench_table(state);
  if (path == nullptr) return nullptr;
  spread_tables* tables = nullptr;
  if (spread_open(path, &tables) != SPREAD_OK) {
    state.SkipWithError("spread_open failed");
    return nullptr;
  }
  return tables;
}

// spread_compensate_wind on a real table file (SPREAD_BENCH_TABLE): Urea at 600 rpm, 11 m bout against
// CV <= 10 % (the bundled machine's stated setting), range(0) = lateral wind (m/s). Counter cv_percent: the CV at the setting found.
void BM_CompensateWindCApiFile(benchmark::State& state) {
  spread_tables* tables = open_bench_table(state);
  if (tables == nullptr) return;
  spread_prediction_def def = capi_request();
  def.rpm = 600.0;
  def.bout_width_m = 11.0;  // the bundled machine's stated setting (scenes/default.toml)
  def.cv_target_percent = 10.0;
  def.wind_m_s[0] = static_cast<double>(state.range(0));
  spread_prediction result{};
  for (auto _ : state) {
    const spread_status status = spread_compensate_wind(tables, &def, &result, nullptr, 0);
    benchmark::DoNotOptimize(status);
  }
  state.counters["cv_percent"] = result.cv_percent;
  state.counters["left_rpm"] = result.disc_rpm[0];
  state.counters["right_rpm"] = result.disc_rpm[1];
  spread_close(tables);
}

// spread_compensate_wind_within on the same request in a 5 m/s crosswind, range(0) = the budget in
// predictions (0: none): what a control loop's call costs at each budget. Counters: the CV at the answer
// and whether the search finished.
void BM_CompensateWindWithinCApiFile(benchmark::State& state) {
  spread_tables* tables = open_bench_table(state);
  if (tables == nullptr) return;
  spread_prediction_def def = capi_request();
  def.rpm = 600.0;
  def.bout_width_m = 11.0;
  def.cv_target_percent = 10.0;
  def.wind_m_s[0] = 5.0;
  spread_prediction result{};
  int32_t finished = 0;
  for (auto _ : state) {
    const spread_status status =
        spread_compensate_wind_within(tables, &def, static_cast<int32_t>(state.range(0)), &result, nullptr, 0, &finished);
    if (status != SPREAD_OK) state.SkipWithError(spread_last_error_detail());
    benchmark::DoNotOptimize(status);
  }
  state.counters["cv_percent"] = result.cv_percent;
  state.counters["finished"] = finished;
  spread_close(tables);
}

// spread_predict_edge on a real table file (SPREAD_BENCH_TABLE): Urea at 600 rpm, 11 m bouts, border
// spreading with the right disc at 462.5 rpm, -5 degrees, 58 % of its flow and the left disc's drop point
// turned -90 degrees (the setting `spread border` finds there on the main job's table).
void BM_PredictEdgeCApiFile(benchmark::State& state) {
  spread_tables* tables = open_bench_table(state);
  if (tables == nullptr) return;
  spread_prediction_def def = capi_request();
  def.rpm = 600.0;
  def.bout_width_m = 11.0;
  def.disc_rpm[1] = 462.5;
  def.disc_drop_point_turn_rad[1] = -5.0 * std::numbers::pi / 180.0;
  def.disc_drop_point_turn_rad[0] = -90.0 * std::numbers::pi / 180.0;
  spread_edge_def edge = spread_edge_def_default();
  edge.flow_fraction = 0.58;
  spread_edge_result result{};
  for (auto _ : state) {
    const spread_status status = spread_predict_edge(tables, &def, &edge, &result, nullptr, 0);
    benchmark::DoNotOptimize(status);
  }
  state.counters["mass_beyond_percent"] = result.mass_beyond_percent;
  state.counters["trays"] = result.tray_count;
  spread_close(tables);
}

// spread_find_edge_setting on a real table file (SPREAD_BENCH_TABLE): the border search for Urea at 600
// rpm on 12 m bouts, the edge line on the right at 4.5 m (range(0) = 0) or at the bout's edge (1) — what
// the ECU plans when section 8 of 8 is switched off, or for a right border. Counters: the setting found
// and the predictions it took.
void BM_FindEdgeSettingCApiFile(benchmark::State& state) {
  spread_tables* tables = open_bench_table(state);
  if (tables == nullptr) return;
  spread_prediction_def def = capi_request();
  def.rpm = 600.0;
  def.bout_width_m = 12.0;
  spread_edge_def edge = spread_edge_def_default();
  edge.gap_m = state.range(0) == 0 ? 1.5 : 0.0;
  spread_edge_setting setting{};
  spread_edge_result result{};
  for (auto _ : state) {
    const spread_status status = spread_find_edge_setting(tables, &def, &edge, &setting, &result, nullptr, 0);
    if (status != SPREAD_OK) state.SkipWithError(spread_last_error_detail());
    benchmark::DoNotOptimize(status);
  }
  state.counters["rpm"] = setting.disc_rpm;
  state.counters["turn_deg"] = setting.disc_drop_point_turn_rad * 180.0 / std::numbers::pi;
  state.counters["flow"] = setting.flow_fraction;
  state.counters["predictions"] = setting.predictions;
  state.counters["meets"] = result.meets;
  spread_close(tables);
}

// spread_find_edge_setting_within on the same border search (edge line at 4.5 m), range(0) = the budget in
// predictions (0: none): what a control loop's call costs at each budget. Counters: the predictions made,
// whether the search finished, and the mass over the line at the answer (percent of the pass's).
void BM_FindEdgeSettingWithinCApiFile(benchmark::State& state) {
  spread_tables* tables = open_bench_table(state);
  if (tables == nullptr) return;
  spread_prediction_def def = capi_request();
  def.rpm = 600.0;
  def.bout_width_m = 12.0;
  spread_edge_def edge = spread_edge_def_default();
  edge.gap_m = 1.5;
  spread_edge_setting setting{};
  spread_edge_result result{};
  int32_t finished = 0;
  for (auto _ : state) {
    const spread_status status = spread_find_edge_setting_within(
        tables, &def, &edge, static_cast<int32_t>(state.range(0)), &setting, &result, nullptr, 0, &finished);
    if (status != SPREAD_OK) state.SkipWithError(spread_last_error_detail());
    benchmark::DoNotOptimize(status);
  }
  state.counters["predictions"] = setting.predictions;
  state.counters["finished"] = finished;
  state.counters["beyond_percent"] = result.mass_beyond_percent;
  state.counters["meets"] = result.meets;
  spread_close(tables);
}

// The landing grid's interpolation error over its whole domain on a real table file (SPREAD_BENCH_TABLE):
// every 5th launch sample of every row of the material range(0) indexes (sorted by name), at a random
// disc height and wind across the domain (one in three at the stored height in still air), the grid's
// landing against the sample flown at the tight reference tolerance. Counters rms_error_m, max_error_m;
// the time is one grid evaluation.
void BM_LandingGridError(benchmark::State& state) {
  const char* path = bench_table(state);
  if (path == nullptr) return;
  auto contents = spread::tables::read_table_file(path);
  if (static_cast<std::size_t>(state.range(0)) >= contents.materials.size()) {
    state.SkipWithError("no such material");
    return;
  }
  std::sort(contents.materials.begin(), contents.materials.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  const auto& material = contents.materials[static_cast<std::size_t>(state.range(0))];
  const auto domain = spread::predict::landing_domain_for(contents.machine.disc_height_m);
  std::vector<spread::tables::LaunchSample> samples;
  double max_rim_speed_m_s = 0.0;
  for (const auto& run : contents.runs) {
    if (run.material != material.name) continue;
    samples.insert(samples.end(), run.samples.begin(), run.samples.end());
    max_rim_speed_m_s = std::max(max_rim_speed_m_s, run.rpm * 2.0 * std::numbers::pi / 60.0 * contents.machine.disc_radius_m);
  }
  spread::predict::LandingGrid grid;
  auto settings = spread::predict::default_flight_settings();
  settings.rel_tol = settings.abs_tol = 1e-7;  // as the Predictor flies its grids
  if (samples.empty() ||
      !grid.build(spread::predict::landing_grid_axes(samples, max_rim_speed_m_s, domain), material.density_kg_m3, spread::flight::kDrag, settings, {})) {
    state.SkipWithError("no grid");
    return;
  }
  std::mt19937 random(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double sum_squares = 0.0, worst_m = 0.0;
  std::size_t count = 0;
  for (const auto& run : contents.runs) {
    if (run.material != material.name) continue;
    const double rim_speed_m_s = run.rpm * 2.0 * std::numbers::pi / 60.0 * contents.machine.disc_radius_m;
    for (std::size_t i = 0; i < run.samples.size(); i += 5) {
      const auto& s = run.samples[i];
      double height_m = domain.min_disc_height_m + unit(random) * (domain.max_disc_height_m - domain.min_disc_height_m);
      double wind_m_s = unit(random) * domain.max_wind_m_s;
      const double direction = 2.0 * std::numbers::pi * unit(random);
      if (i % 3 == 0) {
        height_m = contents.machine.disc_height_m;
        wind_m_s = 0.0;
      }
      spread::flight::State launch;
      launch.position_m = spread::Vec3(s.x_m, s.y_m, s.z_m + height_m);
      launch.velocity_m_s = rim_speed_m_s * spread::Vec3(s.vx_norm, s.vy_norm, s.vz_norm);
      spread::flight::Air air;
      air.wind_m_s = spread::Vec3(wind_m_s * std::cos(direction), wind_m_s * std::sin(direction), 0.0);
      const auto flown = spread::flight::fly_to_ground({s.diameter_m, material.density_kg_m3}, launch, 0.0, air,
                                                       spread::flight::kDrag | spread::flight::kWind,
                                                       spread::predict::reference_flight_settings());
      double x = 0.0, y = 0.0;
      grid.landing(s.diameter_m, s.x_m, s.y_m, launch.position_m.z(), launch.velocity_m_s.x(), launch.velocity_m_s.y(),
                   launch.velocity_m_s.z(), air.wind_m_s.x(), air.wind_m_s.y(), x, y);
      const double error_m = std::hypot(x - flown.state.position_m.x(), y - flown.state.position_m.y());
      sum_squares += error_m * error_m;
      worst_m = std::max(worst_m, error_m);
      ++count;
    }
  }
  const auto& s = samples[samples.size() / 2];
  for (auto _ : state) {
    double x = 0.0, y = 0.0;
    grid.landing(s.diameter_m, s.x_m, s.y_m, 0.85, 20.0 * s.vx_norm, 20.0 * s.vy_norm, 20.0 * s.vz_norm, 1.0, 2.0, x, y);
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(y);
  }
  state.SetLabel(material.name);
  state.counters["rms_error_m"] = std::sqrt(sum_squares / static_cast<double>(count));
  state.counters["max_error_m"] = worst_m;
  state.counters["grid_bytes"] = static_cast<double>(grid.bytes());
}

// The landing grid alone on a real table file (SPREAD_BENCH_TABLE): both discs' landings of the Urea rows
// around 560 rpm (what a prediction between them lands) at 560 rpm from the machine's disc height, in a
// lateral wind of range(0) m/s. The time is one pass over the samples (LandingGrid::sample_landings).
void BM_GridSampleLandings(benchmark::State& state) {
  const char* path = bench_table(state);
  if (path == nullptr) return;
  const auto contents = spread::tables::read_table_file(path);
  std::vector<spread::tables::LaunchSample> samples, between;
  double max_rim_speed_m_s = 0.0, density_kg_m3 = 0.0;
  const double rim_speed_m_s = kRpm * 2.0 * std::numbers::pi / 60.0 * contents.machine.disc_radius_m;
  for (const auto& m : contents.materials) {
    if (m.name == kMaterial) density_kg_m3 = m.density_kg_m3;
  }
  for (const auto& run : contents.runs) {
    if (run.material != kMaterial) continue;
    samples.insert(samples.end(), run.samples.begin(), run.samples.end());
    max_rim_speed_m_s = std::max(max_rim_speed_m_s, run.rpm * 2.0 * std::numbers::pi / 60.0 * contents.machine.disc_radius_m);
    if (std::abs(run.rpm - kRpm) < 150.0) between.insert(between.end(), run.samples.begin(), run.samples.end());
  }
  spread::predict::LandingGrid grid;
  auto settings = spread::predict::default_flight_settings();
  settings.rel_tol = settings.abs_tol = 1e-7;  // as the Predictor flies its grids
  const auto domain = spread::predict::landing_domain_for(contents.machine.disc_height_m);
  if (between.empty() ||
      !grid.build(spread::predict::landing_grid_axes(samples, max_rim_speed_m_s, domain), density_kg_m3, spread::flight::kDrag, settings, {})) {
    state.SkipWithError("no grid");
    return;
  }
  auto block = std::make_unique<spread::predict::LandingGrid::StencilBlock>();
  std::vector<double> xs(2 * between.size()), ys(2 * between.size());
  for (auto _ : state) {
    grid.sample_landings(between, rim_speed_m_s, contents.machine.disc_height_m, static_cast<double>(state.range(0)), 0.0,
                         spread::predict::LandingGrid::Sides::kBoth, *block, xs, ys);
    benchmark::DoNotOptimize(xs.data());
    benchmark::ClobberMemory();
  }
  state.counters["samples"] = static_cast<double>(between.size());
}

// The landing grid's cost and error on a real table file (SPREAD_BENCH_TABLE).
void BM_PredictLandingGrid(benchmark::State& state) {
  const char* path = bench_table(state);
  if (path == nullptr) return;
  spread::predict::Predictor p(spread::tables::read_table_file(path));
  spread::predict::Predictor reference(spread::tables::read_table_file(path));
  reference.set_flight_settings(spread::predict::reference_flight_settings());
  p.set_landing_grid_enabled(state.range(1) != 0);
  spread::predict::PredictionRequest r;
  r.material = p.material(p.find_material(kMaterial).value_or(0)).name;
  r.rpm = kRpm;
  r.wind_x_m_s = static_cast<double>(state.range(0));
  spread::predict::Prediction out, truth;
  if (p.predict(r, out) != spread::predict::PredictStatus::kOk || reference.predict(r, truth) != spread::predict::PredictStatus::kOk) {
    state.SkipWithError("predict failed");
    return;
  }
  double error_m = 0.0;
  for (std::size_t k = 0; k < out.landing_x_m.size(); ++k) {
    error_m = std::max(error_m, std::hypot(out.landing_x_m[k] - truth.landing_x_m[k], out.landing_y_m[k] - truth.landing_y_m[k]));
  }
  for (auto _ : state) {
    p.predict(r, out);
    double width_m = out.working_width_to_and_fro_m;
    benchmark::DoNotOptimize(width_m);
  }
  state.counters["max_landing_error_m"] = error_m;
  state.counters["flights"] = out.flights;
  state.counters["working_width_m"] = out.working_width_to_and_fro_m;
  state.counters["grid_bytes"] = static_cast<double>(p.landing_grid_bytes());
}

BENCHMARK(BM_PredictDormandPrince)->Arg(256)->Arg(512)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PredictCApi)->Arg(256)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PredictCApiDrag)
    ->ArgsProduct({{512, 2000}, {0, 3}, {0, 1}})
    ->ArgNames({"samples", "wind", "dem"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OpenFile)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PredictCApiFile)
    ->ArgsProduct({{0, 3}, {560, 600}})
    ->ArgNames({"wind", "rpm"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PredictCApiFileDiscs)
    ->ArgsProduct({{0, 3}, {0, 1, 2, 3}})
    ->ArgNames({"wind", "discs"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CompensateWindCApiFile)->Arg(3)->Arg(5)->ArgName("wind")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CompensateWindWithinCApiFile)
    ->Arg(3)->Arg(5)->Arg(8)->Arg(20)->Arg(0)
    ->ArgName("budget")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PredictEdgeCApiFile)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FindEdgeSettingCApiFile)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FindEdgeSettingWithinCApiFile)
    ->Arg(3)->Arg(5)->Arg(10)->Arg(50)
    ->ArgName("budget")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LandingGridError)->DenseRange(0, 2)->ArgName("material")->Unit(benchmark::kNanosecond);
BENCHMARK(BM_GridSampleLandings)->Arg(0)->Arg(3)->ArgName("wind")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PredictLandingGrid)
    ->ArgsProduct({{0, 3, 10}, {0, 1}})
    ->ArgNames({"wind", "grid"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PredictRk4Fixed1ms)->Arg(256)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
