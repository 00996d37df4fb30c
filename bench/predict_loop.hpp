#pragma once
// spread_predict timed in a loop on an open table (bench_capi, bench_predict): the tray buffer sized by the
// bounds query, one untimed call that must succeed, then the timed calls. `result` holds the last prediction.
// Returns false, with the benchmark marked failed, when the untimed call fails; the caller closes the table.
#include <benchmark/benchmark.h>

#include <vector>

#include "spread/spread.h"

namespace spread::bench {

inline bool time_spread_predict(benchmark::State& state, spread_tables* tables, const spread_prediction_def& def,
                                spread_prediction& result) {
  size_t capacity = 0;
  spread_transverse_bound(tables, def.tray_width_m, &capacity);
  std::vector<double> trays(capacity);
  if (spread_predict(tables, &def, &result, trays.data(), trays.size()) != SPREAD_OK) {
    state.SkipWithError("spread_predict failed");
    return false;
  }
  for (auto _ : state) {
    spread_predict(tables, &def, &result, trays.data(), trays.size());
    double cv = result.cv_percent;
    benchmark::DoNotOptimize(cv);
  }
  return true;
}

}  // namespace spread::bench
