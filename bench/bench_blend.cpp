// A blend's answer (libspread/analysis/blends: each component predicted from its row, the patterns added,
// the blend's, nutrients' and components' CVs, the separation index and the widest common bout) against
// its components' own predictions alone: what a blend costs per component over a single product. The
// table: scenes/blend_npk.toml's urea-DAP-potash blend from the analytic source (built here, in memory,
// by lookup_builder's run source), 2,000 launch samples per component.
//
//   taskset -c 1 build/bench/bench_blend --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true
//   SPREAD_BENCH_REGISTERS=baseline taskset -c 1 build/bench/bench_blend ...   # the portable path
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "bench/bench_registers.hpp"
#include "libspread/analysis/blends/blend_patterns.hpp"
#include "libspread/io/scene/scene.hpp"
#include "lookup_builder/run_source.hpp"

namespace {
using namespace spread;

struct BlendTable {
  tables::TableContents contents;
  tables::Blend blend;
};

const BlendTable& blend_table() {
  static const BlendTable table = [] {
    const scene::Scene scene = scene::load_scene_file(SPREAD_SOURCE_DIR "/scenes/blend_npk.toml",
                                                      {"sweep.source=analytic", "sweep.samples_per_run=2000"});
    const scene::Material& blend = scene.materials.front();
    BlendTable t;
    t.contents.machine = scene::table_machine(scene.machine);
    t.blend.name = blend.name;
    for (const tables::BlendComponent& c : blend.components) {
      tables::Material row = c.material;
      row.name = tables::blend_component_name(blend.name, c.material.name);
      t.contents.materials.push_back(row);
      t.blend.components.push_back({row.name, c.mass_fraction, c.n_pct, c.p2o5_pct, c.k2o_pct});
    }
    t.contents.runs = lookup::make_run_source(scene, 1)(blend, 600.0);
    t.contents.blends = {t.blend};
    return t;
  }();
  return table;
}

predict::PredictionRequest request_at_600() {
  predict::PredictionRequest r;
  r.rpm = 600.0;
  return r;
}

void BM_BlendAnswer(benchmark::State& state) {
  state.SetLabel("registers: " + bench::limit_registers_from_env());
  predict::Predictor predictor(blend_table().contents);
  const predict::PredictionRequest request = request_at_600();
  for (auto _ : state) {
    const blends::BlendPatterns b = blends::blend_patterns(predictor, blend_table().blend, request);
    benchmark::DoNotOptimize(b.separation_index);
  }
  state.counters["components"] = static_cast<double>(blend_table().blend.components.size());
}

// The same components' own predictions, one after the other: the single-product cost the blend's is
// compared with.
void BM_ComponentsAlone(benchmark::State& state) {
  state.SetLabel("registers: " + bench::limit_registers_from_env());
  predict::Predictor predictor(blend_table().contents);
  predict::PredictionRequest request = request_at_600();
  predict::Prediction p;
  for (auto _ : state) {
    for (const tables::BlendRowComponent& c : blend_table().blend.components) {
      request.material = c.material;
      benchmark::DoNotOptimize(predictor.predict(request, p));
    }
  }
  state.counters["components"] = static_cast<double>(blend_table().blend.components.size());
}

BENCHMARK(BM_BlendAnswer)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ComponentsAlone)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
