// One row of the bundled table (scenes/default.toml, the main job's `lookup_builder` sweep) computed as
// `lookup_builder --jobs 2` computes each: one DEM thread, the scene's stopping rule (at least
// sweep.samples_per_run launches and the working width known). What a table's builder pays per row.
//
//   taskset -c 1 build/bench/bench_table_row                               # Urea @ 600 rpm (tens of s)
//   taskset -c 1 build/bench/bench_table_row --benchmark_filter='DAP/750'   # another row
//
// Counters: launches, CPU seconds per 1,000 launches (the figure lookup_builder prints per run,
// docs/building-tables.md "What a row costs"), simulated time.
#include <benchmark/benchmark.h>

#include <string>

#include "bench/bench_registers.hpp"
#include "libspread/io/scene/scene.hpp"
#include "lookup_builder/run_source.hpp"

namespace {
using namespace spread;

void BM_TableRow(benchmark::State& state, const std::string& material_name, double rpm) {
  state.SetLabel("registers: " + bench::limit_registers_from_env());
  const scene::Scene scene = scene::load_scene_file(SPREAD_SOURCE_DIR "/scenes/default.toml", {});
  const scene::Material* material = scene.find_material(material_name);
  if (material == nullptr) {
    state.SkipWithError(("no material " + material_name + " in scenes/default.toml").c_str());
    return;
  }
  const lookup::RunSource source = lookup::make_run_source(scene, 1);
  std::size_t launches = 0;
  for (auto _ : state) {
    const std::vector<tables::Run> runs = source(*material, rpm);
    launches = runs.front().samples.size();
    benchmark::DoNotOptimize(launches);
  }
  state.counters["launches"] = static_cast<double>(launches);
  // Thousands of launches per CPU second of the run (Google Benchmark's own clock), inverted: CPU seconds
  // per 1,000 launches.
  state.counters["cpu_s_per_1000_launches"] =
      benchmark::Counter(static_cast<double>(launches) / 1000.0, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK_CAPTURE(BM_TableRow, Urea/600, std::string("Urea"), 600.0)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_TableRow, DAP/750, std::string("DAP"), 750.0)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
