// Worst-case time of the C API's entry points over their legal inputs (docs/c-api.md "Worst-case time"),
// and the cost of a thread's state (handle or workspace).
//
// BM_PredictWorstCase/<tray_cm>/<height_dm>/<wind_m_s>/<kernel_dm>/<discs>: spread_predict on a real table file
// given in SPREAD_BENCH_TABLE (e.g. `lookup_builder scenes/default.toml --output X.sqlite`) at 560 rpm
// (between two rows: both rows' launches), over the edges of the legal domain: the narrowest legal trays
// (0.1 m) and 0.5 m, the disc at the stored height (0), 0.2 m and 2 m, still air and a lateral wind of
// 5 and 10 m/s (the right disc lands too and the pattern is skewed), the automatic kernel (0) and the
// widest legal one (10 m), both discs alike (0) or each at its own setting (1: the right disc 90 rpm
// faster, on rows of its own, its drop point turned 10°). Every request is answered from the grid
// (flights = 0).
// BM_PredictDomainWorst: the same sweep, every request timed alone in each iteration; prints the slowest
// (label) and its least time (counter worst_ms).
// BM_PredictDomainSweep/<registers>: spread_predict over the whole legal domain of the table, not one
// material at one rpm: every material; the disc speed on each row and at a quarter, half and three
// quarters between neighbouring rows; both discs alike, or the right disc set apart (0.38 of a row gap
// slower, or faster where that leaves the rows: on rows of its own where there are, its drop point
// turned 10°); the disc at the landing grid's lowest, the stored and the highest height; still air, a
// 5 m/s and the grid's strongest crosswind; the automatic and the widest legal kernel (10 m); 0.1 and
// 0.5 m trays. Each request timed alone in every iteration (the thread's CPU time and the wall clock); the
// label names the slowest request by its least CPU time over the iterations (worst_cpu_ms; worst_wall_ms
// its least wall time), p99_cpu_ms and median_cpu_ms those of the sweep's requests.
// registers: the widest registers the kernels may take, 0 the portable path (baseline x86-64), 1 AVX,
// 2 AVX-512 (skipped on a processor without it).
// BM_PredictOutsideDomain/<height_m>/<wind_m_s>: a request outside the domain that opts in to flying every
// launch sample (fly_outside_domain), at 0.5 m trays: what the opt-in costs.
// BM_TrajectoryWorstCase/<case>: spread_trajectory on the inputs that take longest: 0 = dust (1 µm,
// 1 kg/m³: the drag relaxation time is ~3 ns, so the explicit integrator's step is bounded by stability
// and the flight never lands), 1 = a 3 mm granule from 1000 m (the longest legal fall), 2 = a 3 mm
// granule held up by a 100 m/s updraught.
// BM_ExtraThreadState/<kind>: what one more predicting thread costs on the table in SPREAD_BENCH_TABLE:
// kind 0 = spread_open of the same file (one handle per thread), 1 = spread_workspace_create on one
// shared handle. Counter heap_bytes_per_thread = heap bytes still held afterwards (glibc mallinfo2).
// Run: SPREAD_BENCH_TABLE=X.sqlite taskset -c 1 build/bench/bench_capi
#include <benchmark/benchmark.h>

#include <malloc.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/predict_loop.hpp"
#include "libspread/core/cpu_features.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "spread/spread.h"

namespace {

const char* table_path() {
  const char* path = std::getenv("SPREAD_BENCH_TABLE");
  return (path != nullptr && *path != '\0') ? path : nullptr;
}

// The table in SPREAD_BENCH_TABLE opened, and a definition for its first material at 560 rpm (between two
// rows of the default sweep; the middle of its range otherwise). Null, with the benchmark skipped, when
// there is no table.
spread_tables* open_bench_table(benchmark::State& state, spread_prediction_def& def) {
  const char* path = table_path();
  if (path == nullptr) {
    state.SkipWithError("set SPREAD_BENCH_TABLE to a table file (lookup_builder scenes/default.toml --output X)");
    return nullptr;
  }
  spread_tables* tables = nullptr;
  if (spread_open(path, &tables) != SPREAD_OK) {
    state.SkipWithError("spread_open failed");
    return nullptr;
  }
  const char* material = nullptr;
  double min_rpm = 0.0, max_rpm = 0.0;
  spread_material_name(tables, 0, &material);
  spread_material_rpm_range(tables, 0, &min_rpm, &max_rpm);
  def = spread_prediction_def_default();
  def.material = material;
  def.rpm = 560.0 >= min_rpm && 560.0 <= max_rpm ? 560.0 : 0.5 * (min_rpm + max_rpm);
  return tables;
}

// The request at one of the domain's edges: trays tray_cm wide, the disc at height_dm (0: the stored
// height), a lateral wind, the kernel's half width (0: automatic) and the discs alike (discs = 0) or each
// at its own setting (1: the right disc 90 rpm faster, on rows of its own, its drop point turned 10°).
spread_prediction_def edge_request(spread_prediction_def def, long tray_cm, long height_dm, long wind_m_s,
                                   long kernel_dm, long discs) {
  def.tray_width_m = 0.01 * static_cast<double>(tray_cm);
  if (height_dm > 0) def.disc_height_m = 0.1 * static_cast<double>(height_dm);
  def.wind_m_s[0] = static_cast<double>(wind_m_s);
  if (kernel_dm > 0) def.kernel_half_width_m = 0.1 * static_cast<double>(kernel_dm);
  if (discs != 0) {
    def.disc_rpm[1] = def.rpm + 90.0;
    def.disc_drop_point_turn_rad[1] = 10.0 * 3.14159265358979323846 / 180.0;
  }
  return def;
}
const std::vector<long> kEdgeTrays_cm = {10, 50}, kEdgeHeights_dm = {0, 2, 20}, kEdgeWinds_m_s = {0, 5, 10},
                        kEdgeKernels_dm = {0, 100}, kEdgeDiscs = {0, 1};

void BM_PredictWorstCase(benchmark::State& state) {
  spread_prediction_def def;
  spread_tables* tables = open_bench_table(state, def);
  if (tables == nullptr) return;
  def = edge_request(def, state.range(0), state.range(1), state.range(2), state.range(3), state.range(4));
  spread_prediction result{};
  if (spread::bench::time_spread_predict(state, tables, def, result)) {
    state.counters["trays"] = result.tray_count;
    state.counters["flights"] = result.flights;
    state.counters["working_width_m"] = result.working_width_to_and_fro_m;
    state.counters["kernel_m"] = result.kernel_half_width_m;
  }
  spread_close(tables);
}
BENCHMARK(BM_PredictWorstCase)
    ->ArgsProduct({kEdgeTrays_cm, kEdgeHeights_dm, kEdgeWinds_m_s, kEdgeKernels_dm, kEdgeDiscs})
    ->ArgNames({"tray_cm", "height_dm", "wind_m_s", "kernel_dm", "discs"})
    ->Unit(benchmark::kMillisecond);

// Every request of BM_PredictWorstCase's sweep, each timed alone (steady clock) in every iteration: the
// label names the slowest, counter worst_ms its least time over the iterations (the least is the one
// the VM's noise leaves alone), median_ms the middle request's. The time is the whole sweep's.
void BM_PredictDomainWorst(benchmark::State& state) {
  spread_prediction_def base;
  spread_tables* tables = open_bench_table(state, base);
  if (tables == nullptr) return;
  std::vector<spread_prediction_def> requests;
  std::vector<std::string> names;
  for (long tray : kEdgeTrays_cm) {
    for (long height : kEdgeHeights_dm) {
      for (long wind : kEdgeWinds_m_s) {
        for (long kernel : kEdgeKernels_dm) {
          for (long discs : kEdgeDiscs) {
            requests.push_back(edge_request(base, tray, height, wind, kernel, discs));
            names.push_back("tray_cm:" + std::to_string(tray) + "/height_dm:" + std::to_string(height) +
                            "/wind_m_s:" + std::to_string(wind) + "/kernel_dm:" + std::to_string(kernel) +
                            "/discs:" + std::to_string(discs));
          }
        }
      }
    }
  }
  size_t capacity = 0;
  spread_transverse_bound(tables, 0.01 * static_cast<double>(kEdgeTrays_cm.front()), &capacity);
  std::vector<double> trays(capacity);
  spread_prediction result{};
  for (const spread_prediction_def& def : requests) {
    if (spread_predict(tables, &def, &result, trays.data(), trays.size()) != SPREAD_OK) {
      state.SkipWithError("spread_predict failed");
      spread_close(tables);
      return;
    }
  }
  std::vector<double> least_ms(requests.size(), 1e300);
  for (auto _ : state) {
    for (std::size_t i = 0; i < requests.size(); ++i) {
      const auto start = std::chrono::steady_clock::now();
      spread_predict(tables, &requests[i], &result, trays.data(), trays.size());
      const auto end = std::chrono::steady_clock::now();
      least_ms[i] = std::min(least_ms[i], std::chrono::duration<double, std::milli>(end - start).count());
    }
  }
  const auto worst = std::max_element(least_ms.begin(), least_ms.end());
  std::vector<double> sorted = least_ms;
  std::sort(sorted.begin(), sorted.end());
  state.counters["worst_ms"] = *worst;
  state.counters["median_ms"] = sorted[sorted.size() / 2];
  state.counters["requests"] = static_cast<double>(requests.size());
  state.SetLabel("worst: " + names[static_cast<std::size_t>(worst - least_ms.begin())]);
  spread_close(tables);
}
BENCHMARK(BM_PredictDomainWorst)->Iterations(10)->Unit(benchmark::kMillisecond);

struct SweepRequest {
  spread_prediction_def def;
  std::string name;
};

// The requests of BM_PredictDomainSweep on `tables`, opened from the file `contents` were read from; the
// material names belong to the handle.
std::vector<SweepRequest> domain_sweep(spread_tables* tables, const spread::tables::TableContents& contents) {
  std::vector<SweepRequest> out;
  int32_t materials = 0;
  spread_material_count(tables, &materials);
  double stored_height_m = 0.0;
  spread_default_disc_height(tables, &stored_height_m);
  for (int32_t m = 0; m < materials; ++m) {
    const char* material = nullptr;
    double min_rpm = 0.0, max_rpm = 0.0, min_height_m = 0.0, max_height_m = 0.0, max_wind_m_s = 0.0;
    spread_material_name(tables, m, &material);
    spread_material_rpm_range(tables, m, &min_rpm, &max_rpm);
    if (spread_landing_domain(tables, m, &min_height_m, &max_height_m, &max_wind_m_s) != SPREAD_OK) continue;
    // The material's rows, as the file lists them.
    std::vector<double> rows;
    for (const auto& run : contents.runs) {
      if (run.material == material) rows.push_back(run.rpm);
    }
    std::sort(rows.begin(), rows.end());
    if (rows.empty()) continue;
    std::vector<double> speeds;
    for (std::size_t r = 0; r + 1 < rows.size(); ++r) {
      for (double f : {0.0, 0.25, 0.5, 0.75}) speeds.push_back(rows[r] + f * (rows[r + 1] - rows[r]));
    }
    speeds.push_back(rows.back());
    const double gap = rows.size() > 1 ? rows[1] - rows[0] : 0.0;
    for (double rpm : speeds) {
      for (int discs = 0; discs < 2; ++discs) {
        for (double height : {min_height_m, stored_height_m, max_height_m}) {
          for (double wind : {0.0, 5.0, max_wind_m_s}) {
            for (double kernel : {0.0, 10.0}) {
              for (double tray : {0.1, 0.5}) {
                SweepRequest q;
                q.def = spread_prediction_def_default();
                q.def.material = material;
                q.def.rpm = rpm;
                q.def.disc_height_m = height;
                q.def.wind_m_s[0] = std::min(wind, max_wind_m_s);
                if (kernel > 0.0) q.def.kernel_half_width_m = kernel;
                q.def.tray_width_m = tray;
                double right_rpm = rpm;
                if (discs != 0) {
                  right_rpm = rpm - 0.38 * gap >= min_rpm ? rpm - 0.38 * gap : rpm + 0.38 * gap;
                  q.def.disc_rpm[1] = right_rpm;
                  q.def.disc_drop_point_turn_rad[1] = 10.0 * 3.14159265358979323846 / 180.0;
                }
                char name[256];
                std::snprintf(name, sizeof name, "%s %.1f rpm%s, disc %.2f m, wind %.1f m/s, kernel %s, trays %.1f m",
                              material, rpm,
                              discs != 0 ? (std::string(", right disc ") + std::to_string(static_cast<int>(std::lround(right_rpm))) +
                                            " rpm turned 10 deg").c_str()
                                         : "",
                              height, q.def.wind_m_s[0], kernel > 0.0 ? "10 m" : "automatic", tray);
                q.name = name;
                out.push_back(q);
              }
            }
          }
        }
      }
    }
  }
  return out;
}

void BM_PredictDomainSweep(benchmark::State& state) {
  const auto registers = static_cast<spread::Registers>(state.range(0));
  if (registers == spread::Registers::kAvx512 && !spread::detail::cpu_features().avx512f) {
    state.SkipWithError("the processor has no AVX-512");
    return;
  }
  if (registers == spread::Registers::kAvx && !spread::detail::cpu_features().avx) {
    state.SkipWithError("the processor has no AVX");
    return;
  }
  // Limited before the table is opened: an object that chooses its registers at construction keeps them.
  spread::limit_registers(registers);
  spread_prediction_def unused;
  spread_tables* tables = open_bench_table(state, unused);
  if (tables == nullptr) {
    spread::limit_registers(spread::Registers::kAvx512);
    return;
  }
  const std::vector<SweepRequest> requests = domain_sweep(tables, spread::tables::read_table_file(table_path()));
  size_t capacity = 0;
  spread_transverse_bound(tables, 0.1, &capacity);
  std::vector<double> trays(capacity);
  spread_prediction result{};
  for (const SweepRequest& q : requests) {
    if (spread_predict(tables, &q.def, &result, trays.data(), trays.size()) != SPREAD_OK) {
      state.SkipWithError((q.name + ": " + spread_last_error_detail()).c_str());
      spread_close(tables);
      spread::limit_registers(spread::Registers::kAvx512);
      return;
    }
  }
  // The thread's CPU time as well as the wall clock: on a machine shared with other jobs a request can be
  // preempted in every iteration, which the wall clock counts and the CPU time does not; the slowest is
  // named by its CPU time, and its wall time reported beside it.
  const auto thread_cpu_ms = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
  };
  std::vector<double> least_ms(requests.size(), 1e300), least_cpu_ms(requests.size(), 1e300);
  for (auto _ : state) {
    for (std::size_t i = 0; i < requests.size(); ++i) {
      const double cpu_start = thread_cpu_ms();
      const auto start = std::chrono::steady_clock::now();
      spread_predict(tables, &requests[i].def, &result, trays.data(), trays.size());
      const auto end = std::chrono::steady_clock::now();
      least_cpu_ms[i] = std::min(least_cpu_ms[i], thread_cpu_ms() - cpu_start);
      least_ms[i] = std::min(least_ms[i], std::chrono::duration<double, std::milli>(end - start).count());
    }
  }
  const auto worst = std::max_element(least_cpu_ms.begin(), least_cpu_ms.end());
  const auto worst_index = static_cast<std::size_t>(worst - least_cpu_ms.begin());
  std::vector<double> sorted = least_cpu_ms;
  std::sort(sorted.begin(), sorted.end());
  state.counters["worst_cpu_ms"] = *worst;
  state.counters["worst_wall_ms"] = least_ms[worst_index];
  state.counters["p99_cpu_ms"] = sorted[sorted.size() * 99 / 100];
  state.counters["median_cpu_ms"] = sorted[sorted.size() / 2];
  state.counters["requests"] = static_cast<double>(requests.size());
  state.SetLabel("slowest: " + requests[worst_index].name);
  spread_close(tables);
  spread::limit_registers(spread::Registers::kAvx512);
}
BENCHMARK(BM_PredictDomainSweep)->DenseRange(0, 2)->ArgName("registers")->Iterations(5)->Unit(benchmark::kMillisecond);

void BM_PredictOutsideDomain(benchmark::State& state) {
  spread_prediction_def def;
  spread_tables* tables = open_bench_table(state, def);
  if (tables == nullptr) return;
  def.disc_height_m = static_cast<double>(state.range(0));
  def.wind_m_s[0] = static_cast<double>(state.range(1));
  def.fly_outside_domain = 1;
  spread_prediction result{};
  if (spread::bench::time_spread_predict(state, tables, def, result)) {
    state.counters["flights"] = result.flights;
    state.counters["samples"] = result.sample_count;
  }
  spread_close(tables);
}
BENCHMARK(BM_PredictOutsideDomain)
    ->Args({3, 0})
    ->Args({50, 20})
    ->ArgNames({"height_m", "wind_m_s"})
    ->Unit(benchmark::kMillisecond);

void BM_TrajectoryWorstCase(benchmark::State& state) {
  spread_trajectory_def def = spread_trajectory_def_default();
  switch (state.range(0)) {
    case 0:
      def.diameter_m = 1e-6;
      def.density_kg_m3 = 1.0;
      break;
    case 1:
      def.position_m[2] = 1000.0;
      break;
    default:
      def.wind_m_s[2] = 100.0;
      break;
  }
  spread_landing landing{};
  spread_status status = SPREAD_OK;
  for (auto _ : state) {
    status = spread_trajectory(&def, &landing);
    // On a copy: DoNotOptimize on a struct member was seen to clobber it with this toolchain.
    double time_s = landing.flight_time_s;
    benchmark::DoNotOptimize(time_s);
  }
  state.counters["landed"] = status == SPREAD_OK ? 1 : 0;
  state.counters["steps"] = landing.steps;
  state.counters["flight_time_s"] = landing.flight_time_s;
}
BENCHMARK(BM_TrajectoryWorstCase)->DenseRange(0, 2)->ArgName("case")->Unit(benchmark::kMillisecond);

void BM_ExtraThreadState(benchmark::State& state) {
  const char* path = table_path();
  if (path == nullptr) {
    state.SkipWithError("set SPREAD_BENCH_TABLE to a table file (lookup_builder scenes/default.toml --output X)");
    return;
  }
  const bool workspace_kind = state.range(0) == 1;
  spread_tables* shared = nullptr;
  if (spread_open(path, &shared) != SPREAD_OK) {
    state.SkipWithError("spread_open failed");
    return;
  }
  double held_bytes = 0.0;
  for (auto _ : state) {
    const auto before = mallinfo2().uordblks;
    spread_tables* tables = nullptr;
    spread_workspace* workspace = nullptr;
    if (workspace_kind) {
      spread_workspace_create(shared, &workspace);
    } else {
      spread_open(path, &tables);
    }
    held_bytes = static_cast<double>(mallinfo2().uordblks) - static_cast<double>(before);
    state.PauseTiming();
    spread_workspace_free(workspace);
    spread_close(tables);
    state.ResumeTiming();
  }
  state.counters["heap_bytes_per_thread"] = held_bytes;
  spread_close(shared);
}
BENCHMARK(BM_ExtraThreadState)->DenseRange(0, 1)->ArgName("workspace")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
