// C API behaviour: queries, predictions, caller buffers and their bounds, every input error code,
// single trajectories, version and status names, and that docs/c-api.md carries the compiled example.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "capi/src/abi_layout.hpp"
#include "capi/src/fault_seam.hpp"
#include "libspread/analysis/predict/edge_spreading.hpp"
#include "libspread/analysis/predict/wind_compensation.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "spread/spread.h"
#include "tests/capi/capi_test_files.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace {

using spread::testing::temp_path;

class Capi : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    path_ = temp_path("api.sqlite");
    spread::testing::write_synthetic_table(path_);
  }
  void SetUp() override { ASSERT_EQ(spread_open(path_.c_str(), &tables_), SPREAD_OK); }
  void TearDown() override { spread_close(tables_); }

  static spread_prediction_def def(const char* material = "can", double rpm = 600.0) {
    spread_prediction_def d = spread_prediction_def_default();
    d.material = material;
    d.rpm = rpm;
    return d;
  }
  spread_status predict(const spread_prediction_def& d) {
    spread_prediction r{};
    return spread_predict(tables_, &d, &r, nullptr, 0);
  }

  static inline std::string path_;
  spread_tables* tables_ = nullptr;
};

TEST_F(Capi, QueriesMaterialsAndRanges) {
  int32_t count = 0;
  ASSERT_EQ(spread_material_count(tables_, &count), SPREAD_OK);
  ASSERT_EQ(count, 2);
  const char* name = nullptr;
  ASSERT_EQ(spread_material_name(tables_, 1, &name), SPREAD_OK);
  EXPECT_STREQ(name, "urea");
  double lo = 0, hi = 0;
  ASSERT_EQ(spread_material_rpm_range(tables_, 0, &lo, &hi), SPREAD_OK);
  EXPECT_EQ(lo, 500.0);
  EXPECT_EQ(hi, 800.0);
  double h = 0;
  ASSERT_EQ(spread_default_disc_height(tables_, &h), SPREAD_OK);
  EXPECT_EQ(h, 0.8);
  EXPECT_EQ(spread_material_name(tables_, 2, &name), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(spread_material_name(tables_, -1, &name), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(spread_material_rpm_range(tables_, 7, &lo, &hi), SPREAD_ERROR_OUT_OF_RANGE);
}

TEST_F(Capi, PredictsIntoCallerResultAndBuffer) {
  const spread_prediction_def d = def("can", 650.0);
  size_t bound = 0;
  ASSERT_EQ(spread_transverse_bound(tables_, d.tray_width_m, &bound), SPREAD_OK);
  std::vector<double> trays(bound, -1.0);
  spread_prediction r{};
  ASSERT_EQ(spread_predict(tables_, &d, &r, trays.data(), trays.size()), SPREAD_OK);
  EXPECT_GT(r.throw_width_m, 5.0);
  EXPECT_GT(r.working_width_to_and_fro_m, 0.0);
  EXPECT_GT(r.working_width_racetrack_m, 0.0);
  // The CV is at the widest whole-tray bout within the target, just below the (interpolated) working width.
  EXPECT_LE(r.bout_width_m, r.working_width_to_and_fro_m);
  EXPECT_GT(r.bout_width_m, r.working_width_to_and_fro_m - r.tray_width_m);
  EXPECT_LE(r.cv_percent, 15.0);
  // Appended fields: the Monte Carlo uncertainty and what ran.
  EXPECT_EQ(r.sample_count, 256);
  EXPECT_GT(r.working_width_to_and_fro_se_m, 0.0);
  EXPECT_GT(r.cv_se_percent, 0.0);
  EXPECT_GT(r.throw_width_se_m, 0.0);
  // The synthetic file records no flight effects, which means all; no wind today, so not the wind.
  EXPECT_EQ(r.effects, SPREAD_EFFECT_ALL & ~SPREAD_EFFECT_WIND);
  EXPECT_GT(r.kernel_half_width_m, 0.0);
  EXPECT_GT(r.mean_radius_m, 0.0);
  EXPECT_GT(r.radial_width_m, 0.0);
  EXPECT_EQ(r.disc_height_m, 0.8);
  EXPECT_EQ(r.tray_width_m, 0.5);
  EXPECT_EQ(r.flights, 256);
  ASSERT_GT(r.tray_count, 0);
  ASSERT_LE(static_cast<size_t>(r.tray_count), bound);
  const double sum = std::accumulate(trays.begin(), trays.begin() + r.tray_count, 0.0);
  EXPECT_NEAR(sum + r.lost_mass_fraction, 1.0, 1e-12);
  EXPECT_EQ(trays[static_cast<size_t>(r.tray_count)], -1.0);  // nothing written past tray_count
  EXPECT_NEAR(r.tray_left_edge_m, -0.5 * r.tray_count * r.tray_width_m, 1e-12);
  // Symmetric trays in still air.
  for (int k = 0; k < r.tray_count; ++k) EXPECT_NEAR(trays[k], trays[r.tray_count - 1 - k], 1e-15);
}

TEST_F(Capi, RequestedBoutWidthAndCvTarget) {
  spread_prediction_def d = def();
  d.bout_width_m = 10.0;
  d.cv_target_percent = 5.0;
  spread_prediction strict{};
  ASSERT_EQ(spread_predict(tables_, &d, &strict, nullptr, 0), SPREAD_OK);
  EXPECT_EQ(strict.bout_width_m, 10.0);
  EXPECT_TRUE(std::isfinite(strict.cv_percent));
  d.cv_target_percent = 30.0;
  spread_prediction lax{};
  ASSERT_EQ(spread_predict(tables_, &d, &lax, nullptr, 0), SPREAD_OK);
  EXPECT_GE(lax.working_width_to_and_fro_m, strict.working_width_to_and_fro_m);
  EXPECT_EQ(lax.cv_percent, strict.cv_percent);  // same bout width, same CV
}

TEST_F(Capi, BufferTooSmallStillReportsTheNeededSize) {
  const spread_prediction_def d = def();
  spread_prediction r{};
  double tiny[3] = {-1, -1, -1};
  EXPECT_EQ(spread_predict(tables_, &d, &r, tiny, 3), SPREAD_ERROR_BUFFER_TOO_SMALL);
  EXPECT_GT(r.tray_count, 3);
  EXPECT_EQ(tiny[0], -1.0);  // untouched
  std::vector<double> exact(static_cast<size_t>(r.tray_count));
  EXPECT_EQ(spread_predict(tables_, &d, &r, exact.data(), exact.size()), SPREAD_OK);
}

TEST_F(Capi, NullPointers) {
  spread_prediction_def d = def();
  spread_prediction r{};
  EXPECT_EQ(spread_predict(nullptr, &d, &r, nullptr, 0), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_predict(tables_, nullptr, &r, nullptr, 0), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_predict(tables_, &d, nullptr, nullptr, 0), SPREAD_ERROR_NULL_POINTER);
  d.material = nullptr;
  EXPECT_EQ(spread_predict(tables_, &d, &r, nullptr, 0), SPREAD_ERROR_NULL_POINTER);
  int32_t count = 0;
  const char* name = nullptr;
  double a = 0, b = 0;
  size_t n = 0;
  EXPECT_EQ(spread_material_count(nullptr, &count), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_material_count(tables_, nullptr), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_material_name(tables_, 0, nullptr), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_material_name(nullptr, 0, &name), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_material_rpm_range(tables_, 0, &a, nullptr), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_default_disc_height(nullptr, &a), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_transverse_bound(tables_, 0.5, nullptr), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_transverse_bound(nullptr, 0.5, &n), SPREAD_ERROR_NULL_POINTER);
  (void)b;
}

TEST_F(Capi, NotFiniteArguments) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  spread_prediction_def d = def();
  d.rpm = nan;
  EXPECT_EQ(predict(d), SPREAD_ERROR_NOT_FINITE);
  d = def();
  d.wind_m_s[0] = inf;
  EXPECT_EQ(predict(d), SPREAD_ERROR_NOT_FINITE);
  d = def();
  d.disc_height_m = inf;
  EXPECT_EQ(predict(d), SPREAD_ERROR_NOT_FINITE);
  d = def();
  d.cv_target_percent = nan;
  EXPECT_EQ(predict(d), SPREAD_ERROR_NOT_FINITE);
  d = def();
  d.tray_width_m = nan;
  EXPECT_EQ(predict(d), SPREAD_ERROR_NOT_FINITE);
  size_t n = 0;
  EXPECT_EQ(spread_transverse_bound(tables_, nan, &n), SPREAD_ERROR_NOT_FINITE);
  // NaN disc height is the documented "use the table's height", not an error.
  d = def();
  d.disc_height_m = nan;
  EXPECT_EQ(predict(d), SPREAD_OK);
}

TEST_F(Capi, OutOfRangeArguments) {
  spread_prediction_def d = def();
  d.disc_height_m = -0.5;
  EXPECT_EQ(predict(d), SPREAD_ERROR_OUT_OF_RANGE);
  d = def();
  d.cv_target_percent = 0.0;
  EXPECT_EQ(predict(d), SPREAD_ERROR_OUT_OF_RANGE);
  d = def();
  d.cv_target_percent = -5.0;
  EXPECT_EQ(predict(d), SPREAD_ERROR_OUT_OF_RANGE);
  d = def();
  d.bout_width_m = -1.0;
  EXPECT_EQ(predict(d), SPREAD_ERROR_OUT_OF_RANGE);
  d = def();
  d.tray_width_m = 0.0;
  EXPECT_EQ(predict(d), SPREAD_ERROR_OUT_OF_RANGE);
  d = def();
  d.struct_size = 8;  // not made by spread_prediction_def_default()
  EXPECT_EQ(predict(d), SPREAD_ERROR_OUT_OF_RANGE);
  // Finite but beyond the documented bounds (the fuzzer's bout width 3.55e59 m was SPREAD_ERROR_INTERNAL).
  for (double width : {3.55e59, 1000.5}) {
    d = def();
    d.bout_width_m = width;
    EXPECT_EQ(predict(d), SPREAD_ERROR_OUT_OF_RANGE) << width;
  }
  d = def();
  d.disc_height_m = 101.0;
  EXPECT_EQ(predict(d), SPREAD_ERROR_OUT_OF_RANGE);
  d = def();
  d.wind_m_s[1] = -100.5;
  EXPECT_EQ(predict(d), SPREAD_ERROR_OUT_OF_RANGE);
  d = def();
  d.cv_target_percent = 1000.5;
  EXPECT_EQ(predict(d), SPREAD_ERROR_OUT_OF_RANGE);
  d = def();
  d.bout_width_m = 1000.0;
  EXPECT_EQ(predict(d), SPREAD_OK);
  size_t n = 0;
  EXPECT_EQ(spread_transverse_bound(tables_, -0.5, &n), SPREAD_ERROR_OUT_OF_RANGE);
}

// A refusal's detail names the one field at fault, its value and its range, and no other field.
TEST_F(Capi, OutOfRangeDetailNamesOnlyTheOffendingField) {
  struct Bad {
    spread_prediction_def def;
    spread_status status;
    const char* detail;
  };
  spread_prediction_def height = def(), cv = def(), tray = def(), wind = def(), kernel = def(), turn = def(),
                        infinite = def();
  height.disc_height_m = -0.5;
  cv.cv_target_percent = 0.0;
  tray.tray_width_m = 0.01;
  wind.wind_m_s[1] = -100.5;
  kernel.kernel_half_width_m = 11.0;
  turn.drop_point_turn_rad = 4.0;
  infinite.bout_width_m = INFINITY;
  spread_prediction_def infinite_disc = def();
  infinite_disc.disc_rpm[1] = INFINITY;
  for (const Bad& b : {Bad{height, SPREAD_ERROR_OUT_OF_RANGE, "disc_height_m -0.5 outside [0, 100] m"},
                       Bad{cv, SPREAD_ERROR_OUT_OF_RANGE, "cv_target_percent 0 outside (0, 1000] percent"},
                       Bad{tray, SPREAD_ERROR_OUT_OF_RANGE, "tray_width_m 0.01 outside [0.1, 100] m"},
                       Bad{wind, SPREAD_ERROR_OUT_OF_RANGE, "wind_m_s[1] -100.5 outside [-100, 100] m/s"},
                       Bad{kernel, SPREAD_ERROR_OUT_OF_RANGE, "kernel_half_width_m 11 outside [0, 10] m"},
                       Bad{turn, SPREAD_ERROR_OUT_OF_RANGE, "drop_point_turn_rad 4 outside [-3.14159, 3.14159] rad"},
                       Bad{infinite, SPREAD_ERROR_NOT_FINITE, "bout_width_m is inf"},
                       Bad{infinite_disc, SPREAD_ERROR_NOT_FINITE, "disc_rpm[1] is inf"}}) {
    EXPECT_EQ(predict(b.def), b.status) << b.detail;
    const std::string detail = spread_last_error_detail();
    EXPECT_NE(detail.find(b.detail), std::string::npos) << detail;
    std::size_t fields = 0;
    for (const char* field : {"disc_height_m", "cv_target_percent", "tray_width_m", "wind_m_s", "kernel_half_width_m",
                              "drop_point_turn_rad", "bout_width_m", "rpm ", "disc_rpm"}) {
      if (detail.find(field) != std::string::npos) ++fields;
    }
    EXPECT_EQ(fields, 1u) << detail;
  }
}

TEST_F(Capi, RpmOutsideTable) {
  EXPECT_EQ(predict(def("can", 499.0)), SPREAD_ERROR_RPM_OUTSIDE_TABLE);
  EXPECT_EQ(predict(def("urea", 750.0)), SPREAD_ERROR_RPM_OUTSIDE_TABLE);  // inside can's range only
  EXPECT_EQ(predict(def("urea", 700.0)), SPREAD_OK);
}

TEST_F(Capi, UnknownMaterial) {
  EXPECT_EQ(predict(def("potash", 600.0)), SPREAD_ERROR_UNKNOWN_MATERIAL);
  EXPECT_EQ(predict(def("", 600.0)), SPREAD_ERROR_UNKNOWN_MATERIAL);
}

TEST_F(Capi, UnknownEffectBits) {
  spread_prediction_def d = def();
  d.effects = SPREAD_EFFECT_ALL | 0x100u;
  EXPECT_EQ(predict(d), SPREAD_ERROR_UNKNOWN_EFFECT);
  spread_trajectory_def t = spread_trajectory_def_default();
  t.effects = 0x20u;
  spread_landing l{};
  EXPECT_EQ(spread_trajectory(&t, &l), SPREAD_ERROR_UNKNOWN_EFFECT);
}

TEST_F(Capi, FewerEffectsChangeThePrediction) {
  spread_prediction_def d = def();
  spread_prediction all{}, vacuum{};
  ASSERT_EQ(spread_predict(tables_, &d, &all, nullptr, 0), SPREAD_OK);
  d.effects = 0;  // gravity only
  ASSERT_EQ(spread_predict(tables_, &d, &vacuum, nullptr, 0), SPREAD_OK);
  EXPECT_GT(vacuum.mean_radius_m, all.mean_radius_m);  // no drag: much further
}

TEST_F(Capi, LateralWindShiftsThePattern) {
  spread_prediction_def d = def();
  d.wind_m_s[0] = 4.0;
  size_t bound = 0;
  ASSERT_EQ(spread_transverse_bound(tables_, 0.5, &bound), SPREAD_OK);
  std::vector<double> trays(bound);
  spread_prediction r{};
  ASSERT_EQ(spread_predict(tables_, &d, &r, trays.data(), trays.size()), SPREAD_OK);
  EXPECT_EQ(r.flights, 512);  // right disc flown, not mirrored
  double centroid = 0;
  for (int k = 0; k < r.tray_count; ++k) centroid += trays[k] * (r.tray_left_edge_m + (k + 0.5) * r.tray_width_m);
  EXPECT_GT(centroid, 0.3);
}

// The documented threading model: one handle per thread, same results as one thread alone.
TEST_F(Capi, OneHandlePerThreadGivesIdenticalResults) {
  const spread_prediction_def d = def("urea", 633.0);
  spread_prediction alone{};
  ASSERT_EQ(spread_predict(tables_, &d, &alone, nullptr, 0), SPREAD_OK);
  std::vector<spread_prediction> results(4);
  std::vector<spread_status> statuses(4, SPREAD_ERROR_INTERNAL);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < results.size(); ++i) {
    threads.emplace_back([&, i] {
      spread_tables* own = nullptr;
      statuses[i] = spread_open(path_.c_str(), &own);
      for (int repeat = 0; repeat < 3 && statuses[i] == SPREAD_OK; ++repeat) {
        statuses[i] = spread_predict(own, &d, &results[i], nullptr, 0);
      }
      spread_close(own);
    });
  }
  for (auto& t : threads) t.join();
  for (std::size_t i = 0; i < results.size(); ++i) {
    EXPECT_EQ(statuses[i], SPREAD_OK);
    EXPECT_EQ(results[i].throw_width_m, alone.throw_width_m);
    EXPECT_EQ(results[i].mean_radius_m, alone.mean_radius_m);
    EXPECT_EQ(results[i].working_width_racetrack_m, alone.working_width_racetrack_m);
  }
}

TEST(CapiTrajectory, FallsStraightDownInStillAir) {
  spread_trajectory_def t = spread_trajectory_def_default();
  t.position_m[2] = 2.0;
  spread_landing l{};
  ASSERT_EQ(spread_trajectory(&t, &l), SPREAD_OK);
  EXPECT_NEAR(l.position_m[0], 0.0, 1e-12);
  EXPECT_NEAR(l.position_m[2], 0.0, 1e-9);
  // Slower than in vacuum (drag), but not by much over 2 m.
  EXPECT_GT(l.flight_time_s, std::sqrt(2.0 * 2.0 / 9.80665));
  EXPECT_LT(l.flight_time_s, 1.2 * std::sqrt(2.0 * 2.0 / 9.80665));
  EXPECT_GT(l.steps, 0);
}

TEST(CapiTrajectory, VacuumThrowMatchesClosedForm) {
  spread_trajectory_def t = spread_trajectory_def_default();
  t.effects = 0;
  t.position_m[2] = 1.0;
  t.velocity_m_s[0] = 20.0;
  spread_landing l{};
  ASSERT_EQ(spread_trajectory(&t, &l), SPREAD_OK);
  const double time = std::sqrt(2.0 / 9.80665);
  EXPECT_NEAR(l.flight_time_s, time, 1e-6);
  EXPECT_NEAR(l.position_m[0], 20.0 * time, 1e-5);
}

TEST(CapiTrajectory, InputErrors) {
  spread_landing l{};
  spread_trajectory_def t = spread_trajectory_def_default();
  EXPECT_EQ(spread_trajectory(nullptr, &l), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_trajectory(&t, nullptr), SPREAD_ERROR_NULL_POINTER);
  t.velocity_m_s[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(spread_trajectory(&t, &l), SPREAD_ERROR_NOT_FINITE);
  t = spread_trajectory_def_default();
  t.diameter_m = -1e-3;
  EXPECT_EQ(spread_trajectory(&t, &l), SPREAD_ERROR_OUT_OF_RANGE);
  t = spread_trajectory_def_default();
  t.position_m[2] = -0.1;  // below the ground
  EXPECT_EQ(spread_trajectory(&t, &l), SPREAD_ERROR_OUT_OF_RANGE);
  t = spread_trajectory_def_default();
  t.struct_size = 0;
  EXPECT_EQ(spread_trajectory(&t, &l), SPREAD_ERROR_OUT_OF_RANGE);
}

TEST(CapiTrajectory, StrongUpdraughtNeverLands) {
  spread_trajectory_def t = spread_trajectory_def_default();
  t.wind_m_s[2] = 50.0;  // far above the terminal velocity of a 3 mm granule
  spread_landing l{};
  EXPECT_EQ(spread_trajectory(&t, &l), SPREAD_ERROR_NOT_LANDED);
  EXPECT_GT(l.position_m[2], 1.0);
}

// A caller compiled against the first release's header passes its smaller struct_size: the library
// reads only that version's definition fields and writes only that version's result fields.
TEST_F(Capi, OlderDefinitionIsReadAndAnsweredAsItsVersion) {
  spread_prediction current{};
  spread_prediction_def d = def();
  ASSERT_EQ(spread_predict(tables_, &d, &current, nullptr, 0), SPREAD_OK);
  // Point masses instead of the automatic kernel: a different result, if the field were read.
  d.kernel_half_width_m = 0.0;
  spread_prediction point{};
  ASSERT_EQ(spread_predict(tables_, &d, &point, nullptr, 0), SPREAD_OK);
  ASSERT_NE(point.cv_percent, current.cv_percent);

  // Every size from the first release's up to (not including) the current one is the first version.
  for (std::size_t size : {spread::capi::kPredictionDefV1Size, spread::capi::kPredictionDefV2Size - 1}) {
    d.struct_size = static_cast<uint32_t>(size);
    spread_prediction older;
    std::memset(&older, 0xAB, sizeof older);
    ASSERT_EQ(spread_predict(tables_, &d, &older, nullptr, 0), SPREAD_OK) << size;
    EXPECT_EQ(older.cv_percent, current.cv_percent) << "kernel_half_width_m read from a " << size << "-byte definition";
    EXPECT_EQ(older.flights, current.flights);
    const auto* bytes = reinterpret_cast<const unsigned char*>(&older);
    for (std::size_t i = spread::capi::kPredictionV1Size; i < sizeof older; ++i) {
      ASSERT_EQ(bytes[i], 0xAB) << "result byte " << i << " written for a " << size << "-byte definition";
    }
  }
  d.struct_size = static_cast<uint32_t>(spread::capi::kPredictionDefV1Size - 1);
  EXPECT_EQ(spread_predict(tables_, &d, &current, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE);
}

// A 0.2 caller (definition up to kernel_half_width_m) gets the 0.2 result and nothing beyond it; from 0.3
// on the definition's result_size decides, so a caller whose result is a 0.2 one is answered as such.
TEST_F(Capi, BandsAreWrittenOnlyForACallerWhoseResultHasThem) {
  spread_prediction_def d = def();
  spread_prediction current{};
  ASSERT_EQ(spread_predict(tables_, &d, &current, nullptr, 0), SPREAD_OK);
  ASSERT_GE(current.band_count_to_and_fro, 1);
  ASSERT_GE(current.headline_band_to_and_fro, 0);
  EXPECT_EQ(current.working_width_to_and_fro_m, current.bands_to_and_fro[current.headline_band_to_and_fro].upper_m);
  EXPECT_EQ(current.first_band_width_to_and_fro_m, current.bands_to_and_fro[0].upper_m);
  for (int b = std::min(current.band_count_to_and_fro, SPREAD_MAX_BANDS); b < SPREAD_MAX_BANDS; ++b) {
    EXPECT_EQ(current.bands_to_and_fro[b].upper_m, 0.0) << "unused band slot " << b << " not zeroed";
  }
  struct Case {
    uint32_t def_size, result_size;
  };
  for (const Case c : {Case{static_cast<uint32_t>(spread::capi::kPredictionDefV2Size), static_cast<uint32_t>(sizeof current)},
                       Case{static_cast<uint32_t>(sizeof d), static_cast<uint32_t>(spread::capi::kPredictionV2Size)},
                       Case{static_cast<uint32_t>(sizeof d), static_cast<uint32_t>(spread::capi::kPredictionV3Size - 1)}}) {
    d.struct_size = c.def_size;
    d.result_size = c.result_size;
    spread_prediction older;
    std::memset(&older, 0xAB, sizeof older);
    ASSERT_EQ(spread_predict(tables_, &d, &older, nullptr, 0), SPREAD_OK);
    EXPECT_EQ(older.kernel_half_width_m, current.kernel_half_width_m);
    const auto* bytes = reinterpret_cast<const unsigned char*>(&older);
    for (std::size_t i = spread::capi::kPredictionV2Size; i < sizeof older; ++i) {
      ASSERT_EQ(bytes[i], 0xAB) << "result byte " << i << " written for def " << c.def_size << ", result " << c.result_size;
    }
  }
}

// Each disc's own speed and drop point (0.4): the result says what each disc ran at; a 0.3 definition's
// caller is answered as before, and a 0.3 result gets nothing beyond its size; refusals name the disc.
TEST_F(Capi, EachDiscAtItsOwnSettingAndRefusalsNameTheDisc) {
  spread_prediction_def d = def("can", 0.0);
  d.disc_rpm[0] = 600.0;
  d.disc_rpm[1] = 700.0;
  d.disc_drop_point_turn_rad[1] = 0.2;
  spread_prediction own{};
  ASSERT_EQ(spread_predict(tables_, &d, &own, nullptr, 0), SPREAD_OK) << spread_last_error_detail();
  EXPECT_EQ(own.disc_rpm[0], 600.0);
  EXPECT_EQ(own.disc_rpm[1], 700.0);
  EXPECT_EQ(own.disc_drop_point_turn_rad[0], 0.0);
  EXPECT_EQ(own.disc_drop_point_turn_rad[1], 0.2);
  spread_prediction alike{};
  spread_prediction_def both = def("can", 600.0);
  ASSERT_EQ(spread_predict(tables_, &both, &alike, nullptr, 0), SPREAD_OK);
  EXPECT_NE(own.throw_width_m, alike.throw_width_m);
  EXPECT_TRUE(std::isnan(alike.disc_drop_point_turn_rad[0]) == false);

  // A 0.3 definition: the per-disc fields are not read (here, whatever the bytes beyond its size hold).
  spread_prediction_def older = both;
  older.disc_rpm[1] = 700.0;
  older.struct_size = static_cast<uint32_t>(spread::capi::kPredictionDefV3Size);
  older.result_size = static_cast<uint32_t>(spread::capi::kPredictionV3Size);
  spread_prediction older_result;
  std::memset(&older_result, 0xAB, sizeof older_result);
  ASSERT_EQ(spread_predict(tables_, &older, &older_result, nullptr, 0), SPREAD_OK);
  EXPECT_EQ(older_result.throw_width_m, alike.throw_width_m);
  const auto* bytes = reinterpret_cast<const unsigned char*>(&older_result);
  for (std::size_t i = spread::capi::kPredictionV3Size; i < sizeof older_result; ++i) {
    ASSERT_EQ(bytes[i], 0xAB) << "result byte " << i << " written for a 0.3 result";
  }

  struct Refusal {
    double rpm, disc_rpm[2], turn_rad, disc_turn_rad[2];
    spread_status status;
    const char* detail;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Refusal& r : {
           Refusal{600.0, {nan, 900.0}, 0.0, {nan, nan}, SPREAD_ERROR_RPM_OUTSIDE_TABLE, "right disc's speed 900 rpm (disc_rpm[1])"},
           Refusal{100.0, {nan, 600.0}, 0.0, {nan, nan}, SPREAD_ERROR_RPM_OUTSIDE_TABLE, "left disc's speed 100 rpm (rpm)"},
           Refusal{600.0, {650.0, 600.0}, 0.0, {nan, nan}, SPREAD_ERROR_OUT_OF_RANGE, "rpm 600 given while every disc"},
           Refusal{600.0, {nan, nan}, 0.0, {4.0, nan}, SPREAD_ERROR_OUT_OF_RANGE, "left disc's drop point disc_drop_point_turn_rad[0] 4"},
           Refusal{600.0, {nan, nan}, 0.1, {0.1, 0.2}, SPREAD_ERROR_OUT_OF_RANGE, "drop_point_turn_rad 0.1 given while"},
       }) {
    spread_prediction_def bad = def("can", r.rpm);
    bad.disc_rpm[0] = r.disc_rpm[0];
    bad.disc_rpm[1] = r.disc_rpm[1];
    bad.drop_point_turn_rad = r.turn_rad;
    bad.disc_drop_point_turn_rad[0] = r.disc_turn_rad[0];
    bad.disc_drop_point_turn_rad[1] = r.disc_turn_rad[1];
    EXPECT_EQ(predict(bad), r.status) << r.detail;
    EXPECT_NE(std::string(spread_last_error_detail()).find(r.detail), std::string::npos)
        << spread_last_error_detail();
  }
}

// spread_compensate_wind: the per-disc setting in the result, the CV no higher than the present
// setting's, and the requests it cannot answer refused with the reason.
TEST_F(Capi, CompensateWindAnswersAPerDiscSetting) {
  spread_prediction_def d = def("can", 650.0);
  d.bout_width_m = 12.0;
  d.wind_m_s[0] = 3.0;
  spread_prediction present{}, compensated{};
  ASSERT_EQ(spread_predict(tables_, &d, &present, nullptr, 0), SPREAD_OK);
  ASSERT_EQ(spread_compensate_wind(tables_, &d, &compensated, nullptr, 0), SPREAD_OK) << spread_last_error_detail();
  EXPECT_LT(compensated.cv_percent, present.cv_percent);
  // Each disc its own setting: not both alike.
  EXPECT_TRUE(compensated.disc_rpm[0] != compensated.disc_rpm[1] ||
              compensated.disc_drop_point_turn_rad[0] != compensated.disc_drop_point_turn_rad[1]);

  spread_prediction_def no_bout = d;
  no_bout.bout_width_m = 0.0;
  EXPECT_EQ(spread_compensate_wind(tables_, &no_bout, &compensated, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_NE(std::string(spread_last_error_detail()).find("bout_width_m"), std::string::npos);
  spread_prediction_def older = d;
  older.result_size = static_cast<uint32_t>(spread::capi::kPredictionV3Size);
  EXPECT_EQ(spread_compensate_wind(tables_, &older, &compensated, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_NE(std::string(spread_last_error_detail()).find("older than 0.4"), std::string::npos);
  EXPECT_EQ(spread_compensate_wind(nullptr, &d, &compensated, nullptr, 0), SPREAD_ERROR_NULL_POINTER);
  spread_prediction_def outside = d;
  outside.rpm = 950.0;
  EXPECT_EQ(spread_compensate_wind(tables_, &outside, &compensated, nullptr, 0), SPREAD_ERROR_RPM_OUTSIDE_TABLE);
}

// spread_compensate_wind_within: without a limit (0, or a budget above the search's count) the answer is
// spread_compensate_wind's bit for bit and finished; within a few predictions (the library's count says
// how many were made, and the C answer is the library's) it is never above the present setting's CV, and
// not finished; a budget below the three fixed predictions is refused.
TEST_F(Capi, CompensateWindWithinABudget) {
  spread_prediction_def d = def("can", 650.0);
  d.bout_width_m = 12.0;
  d.wind_m_s[0] = 3.0;
  spread_prediction present{}, whole{};
  ASSERT_EQ(spread_predict(tables_, &d, &present, nullptr, 0), SPREAD_OK);
  ASSERT_EQ(spread_compensate_wind(tables_, &d, &whole, nullptr, 0), SPREAD_OK);
  for (int32_t budget : {0, 1000000}) {
    spread_prediction within{};
    int32_t finished = -1;
    ASSERT_EQ(spread_compensate_wind_within(tables_, &d, budget, &within, nullptr, 0, &finished), SPREAD_OK)
        << spread_last_error_detail();
    EXPECT_EQ(finished, 1) << budget;
    EXPECT_EQ(std::memcmp(&within, &whole, sizeof within), 0) << budget;
  }
  spread::predict::Predictor predictor(spread::tables::read_table_file(path_));
  spread::predict::PredictionRequest request;
  request.material = "can";
  request.rpm = 650.0;
  request.bout_width_m = 12.0;
  request.wind_x_m_s = 3.0;
  for (int32_t budget : {3, 6, 12, 24}) {
    SCOPED_TRACE(budget);
    spread_prediction within{};
    int32_t finished = -1;
    ASSERT_EQ(spread_compensate_wind_within(tables_, &d, budget, &within, nullptr, 0, &finished), SPREAD_OK)
        << spread_last_error_detail();
    EXPECT_EQ(finished, 0);
    EXPECT_LE(within.cv_percent, present.cv_percent);
    spread::predict::WindCompensationLimits limits;
    limits.max_predictions = budget;
    spread::predict::Prediction out;
    const spread::predict::WindCompensation found =
        spread::predict::compensate_wind(predictor, request, out, predictor.own_workspace(), limits);
    EXPECT_LE(found.predictions, budget);
    EXPECT_FALSE(found.finished);
    EXPECT_EQ(found.discs[0].rpm, within.disc_rpm[0]);
    EXPECT_EQ(found.discs[1].drop_point_turn_rad, within.disc_drop_point_turn_rad[1]);
  }
  spread_prediction within{};
  int32_t finished = 0;
  EXPECT_EQ(spread_compensate_wind_within(tables_, &d, 2, &within, nullptr, 0, &finished), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_NE(std::string(spread_last_error_detail()).find("max_predictions 2"), std::string::npos);
  EXPECT_EQ(spread_compensate_wind_within(tables_, &d, 10, &within, nullptr, 0, nullptr), SPREAD_ERROR_NULL_POINTER);
}

// spread_predict_edge: the profile of the last bout is the library's (the setting `spread border` finds
// meets its thresholds through the C API too), an edge on the left mirrors one on the right, and the
// definitions out of their domain are refused with the field named.
TEST_F(Capi, PredictEdgeGivesTheLastBoutsProfile) {
  spread::predict::Predictor predictor(spread::tables::read_table_file(path_));
  spread::predict::PredictionRequest field;
  field.material = "can";
  field.rpm = 650.0;
  field.bout_width_m = 18.0;
  const spread::predict::EdgeResult found = spread::predict::find_edge_setting(predictor, field, {});
  ASSERT_TRUE(found.profile.meets);

  spread_prediction_def d = def("can", 650.0);
  d.bout_width_m = 18.0;
  d.disc_rpm[1] = found.setting.disc.rpm;
  d.disc_drop_point_turn_rad[1] = found.setting.disc.drop_point_turn_rad;
  spread_edge_def edge = spread_edge_def_default();
  edge.flow_fraction = found.setting.flow_fraction;
  spread_edge_result result{};
  std::vector<double> rate(2000);
  ASSERT_EQ(spread_predict_edge(tables_, &d, &edge, &result, rate.data(), rate.size()), SPREAD_OK)
      << spread_last_error_detail();
  EXPECT_EQ(result.meets, 1);
  EXPECT_EQ(result.edge_line_m, 9.0);
  EXPECT_DOUBLE_EQ(result.mass_beyond_percent, 100.0 * found.profile.mass_beyond_fraction);
  EXPECT_LE(result.mass_beyond_percent, 0.1);
  ASSERT_EQ(static_cast<std::size_t>(result.tray_count), found.profile.rate.size());
  for (int k = 0; k < result.tray_count; ++k) EXPECT_DOUBLE_EQ(rate[k], 100.0 * found.profile.rate[k]);
  // The edge on the left, that disc set apart: the mirror image.
  spread_prediction_def mirrored = def("can", 650.0);
  mirrored.bout_width_m = 18.0;
  mirrored.disc_rpm[0] = d.disc_rpm[1];
  mirrored.disc_drop_point_turn_rad[0] = d.disc_drop_point_turn_rad[1];
  spread_edge_def left = edge;
  left.side = 0;
  spread_edge_result left_result{};
  ASSERT_EQ(spread_predict_edge(tables_, &mirrored, &left, &left_result, nullptr, 0), SPREAD_OK);
  EXPECT_NEAR(left_result.mass_beyond_percent, result.mass_beyond_percent, 1e-9);
  // The normal setting on the edge side throws over the line.
  spread_prediction_def normal = def("can", 650.0);
  normal.bout_width_m = 18.0;
  spread_edge_result normal_result{};
  spread_edge_def full_flow = spread_edge_def_default();
  ASSERT_EQ(spread_predict_edge(tables_, &normal, &full_flow, &normal_result, nullptr, 0), SPREAD_OK);
  EXPECT_GT(normal_result.mass_beyond_percent, 0.1);
  EXPECT_EQ(normal_result.meets, 0);

  struct Bad {
    const char* what;
    spread_edge_def edge;
    spread_status status;
  };
  spread_edge_def gap = spread_edge_def_default(), kind = gap, flow = gap, share = gap, side = gap;
  gap.gap_m = 9.0;
  kind.kind = 7;
  flow.flow_fraction = 1.5;
  share.max_beyond_percent = 0.0;
  side.side = 2;
  for (const Bad& b : {Bad{"gap_m 9", gap, SPREAD_ERROR_OUT_OF_RANGE}, Bad{"kind 7", kind, SPREAD_ERROR_OUT_OF_RANGE},
                       Bad{"flow_fraction 1.5", flow, SPREAD_ERROR_OUT_OF_RANGE},
                       Bad{"max_beyond_percent 0", share, SPREAD_ERROR_OUT_OF_RANGE},
                       Bad{"side 2", side, SPREAD_ERROR_OUT_OF_RANGE}}) {
    EXPECT_EQ(spread_predict_edge(tables_, &normal, &b.edge, &result, nullptr, 0), b.status) << b.what;
    EXPECT_NE(std::string(spread_last_error_detail()).find(b.what), std::string::npos) << spread_last_error_detail();
  }
  spread_prediction_def no_bout = def("can", 650.0);
  EXPECT_EQ(spread_predict_edge(tables_, &no_bout, &edge, &result, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE);
  spread_prediction_def other = normal;
  other.disc_rpm[0] = 600.0;  // the disc away from the edge keeps the field's speed
  EXPECT_EQ(spread_predict_edge(tables_, &other, &edge, &result, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_NE(std::string(spread_last_error_detail()).find("disc_rpm[0]"), std::string::npos);
  // ... but may turn its drop point on the last pass: the library's profile at that setting.
  spread_prediction_def turned = d;
  turned.disc_drop_point_turn_rad[0] = -0.5;
  spread::predict::EdgeSetting setting = found.setting;
  setting.field_side_drop_point_turn_rad = -0.5;
  spread::predict::EdgeProfile expected;
  ASSERT_EQ(spread::predict::edge_profile(predictor, field, {}, setting, expected), spread::predict::PredictStatus::kOk);
  spread_edge_result turned_result{};
  ASSERT_EQ(spread_predict_edge(tables_, &turned, &edge, &turned_result, nullptr, 0), SPREAD_OK)
      << spread_last_error_detail();
  EXPECT_DOUBLE_EQ(turned_result.mass_beyond_percent, 100.0 * expected.mass_beyond_fraction);
  EXPECT_DOUBLE_EQ(turned_result.max_rate_inside_percent, 100.0 * expected.max_rate_inside);
  EXPECT_NE(turned_result.max_rate_inside_percent, result.max_rate_inside_percent);
  turned.disc_drop_point_turn_rad[0] = 4.0;  // beyond half a turn
  EXPECT_EQ(spread_predict_edge(tables_, &turned, &edge, &turned_result, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_NE(std::string(spread_last_error_detail()).find("disc_drop_point_turn_rad[0] 4 outside"), std::string::npos)
      << spread_last_error_detail();
  EXPECT_EQ(spread_predict_edge(tables_, &normal, &edge, &result, rate.data(), 3), SPREAD_ERROR_BUFFER_TOO_SMALL);
}

// spread_find_edge_setting: the library's search through the C API — the same setting and profile as
// predict::find_edge_setting, a setting spread_predict_edge confirms — and definitions it would silently
// override are refused.
TEST_F(Capi, FindEdgeSettingIsTheLibrarysSearch) {
  spread::predict::Predictor predictor(spread::tables::read_table_file(path_));
  spread::predict::PredictionRequest field;
  field.material = "can";
  field.rpm = 650.0;
  field.bout_width_m = 18.0;
  spread::predict::EdgeRequest request;
  request.gap_m = 3.0;
  const spread::predict::EdgeResult expected = spread::predict::find_edge_setting(predictor, field, request);

  spread_prediction_def d = def("can", 650.0);
  d.bout_width_m = 18.0;
  spread_edge_def edge = spread_edge_def_default();
  edge.gap_m = 3.0;
  spread_edge_setting setting{};
  spread_edge_result result{};
  std::vector<double> rate(2000);
  ASSERT_EQ(spread_find_edge_setting(tables_, &d, &edge, &setting, &result, rate.data(), rate.size()), SPREAD_OK)
      << spread_last_error_detail();
  EXPECT_EQ(setting.disc_rpm, expected.setting.disc.rpm);
  EXPECT_EQ(setting.disc_drop_point_turn_rad, expected.setting.disc.drop_point_turn_rad);
  EXPECT_EQ(setting.flow_fraction, expected.setting.flow_fraction);
  EXPECT_EQ(std::isnan(setting.field_side_drop_point_turn_rad), std::isnan(expected.setting.field_side_drop_point_turn_rad));
  EXPECT_EQ(setting.predictions, expected.predictions);
  EXPECT_GT(setting.predictions, 100);
  EXPECT_EQ(result.meets, expected.profile.meets ? 1 : 0);
  EXPECT_EQ(result.edge_line_m, 6.0);
  ASSERT_EQ(static_cast<std::size_t>(result.tray_count), expected.profile.rate.size());
  for (int k = 0; k < result.tray_count; ++k) EXPECT_DOUBLE_EQ(rate[k], 100.0 * expected.profile.rate[k]);

  // The setting found, given to spread_predict_edge, gives the same profile.
  spread_prediction_def at = d;
  at.disc_rpm[1] = setting.disc_rpm;
  at.disc_drop_point_turn_rad[1] = setting.disc_drop_point_turn_rad;
  at.disc_drop_point_turn_rad[0] = setting.field_side_drop_point_turn_rad;
  spread_edge_def with_flow = edge;
  with_flow.flow_fraction = setting.flow_fraction;
  spread_edge_result confirmed{};
  ASSERT_EQ(spread_predict_edge(tables_, &at, &with_flow, &confirmed, nullptr, 0), SPREAD_OK) << spread_last_error_detail();
  EXPECT_DOUBLE_EQ(confirmed.mass_beyond_percent, result.mass_beyond_percent);

  // A disc's own setting in the definition would be overridden by the search: refused, naming it.
  spread_prediction_def own = d;
  own.disc_drop_point_turn_rad[0] = 0.2;
  EXPECT_EQ(spread_find_edge_setting(tables_, &own, &edge, &setting, &result, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_NE(std::string(spread_last_error_detail()).find("disc_drop_point_turn_rad[0] 0.2"), std::string::npos)
      << spread_last_error_detail();
  EXPECT_EQ(spread_find_edge_setting(tables_, &d, &edge, nullptr, &result, nullptr, 0), SPREAD_ERROR_NULL_POINTER);
  spread_edge_def flow = edge;
  flow.flow_fraction = 0.5;  // the search sets the flow: a value here would be dropped
  EXPECT_EQ(spread_find_edge_setting(tables_, &d, &flow, &setting, &result, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_NE(std::string(spread_last_error_detail()).find("edge->flow_fraction 0.5"), std::string::npos)
      << spread_last_error_detail();
  spread_edge_def gap = edge;
  gap.gap_m = 9.0;
  EXPECT_EQ(spread_find_edge_setting(tables_, &d, &gap, &setting, &result, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_NE(std::string(spread_last_error_detail()).find("spread_find_edge_setting: edge->gap_m 9"), std::string::npos)
      << spread_last_error_detail();
}

// spread_find_edge_setting_within: without a limit (0, or a budget the whole search's count fits) the answer is
// spread_find_edge_setting's bit for bit and finished; with a budget of a few predictions it stops there
// with a usable setting — one spread_predict_edge confirms; with the three fixed predictions alone the
// normal setting at its best flow — and says it did not finish; a budget below those three is refused.
TEST_F(Capi, FindEdgeSettingWithinABudget) {
  spread_prediction_def d = def("can", 650.0);
  d.bout_width_m = 18.0;
  spread_edge_def edge = spread_edge_def_default();
  edge.gap_m = 3.0;
  spread_edge_setting whole{};
  spread_edge_result whole_result{};
  std::vector<double> whole_rate(2000), rate(2000);
  ASSERT_EQ(spread_find_edge_setting(tables_, &d, &edge, &whole, &whole_result, whole_rate.data(), whole_rate.size()),
            SPREAD_OK);
  for (int32_t budget : {0, 1000000}) {
    spread_edge_setting setting{};
    spread_edge_result result{};
    int32_t finished = -1;
    ASSERT_EQ(spread_find_edge_setting_within(tables_, &d, &edge, budget, &setting, &result, rate.data(), rate.size(),
                                              &finished),
              SPREAD_OK)
        << spread_last_error_detail();
    EXPECT_EQ(finished, 1) << budget;
    EXPECT_EQ(std::memcmp(&setting, &whole, sizeof setting), 0) << budget;
    EXPECT_EQ(std::memcmp(&result, &whole_result, sizeof result), 0) << budget;
    EXPECT_EQ(std::memcmp(rate.data(), whole_rate.data(), sizeof(double) * static_cast<std::size_t>(result.tray_count)), 0);
  }
  // The normal setting's profile: what a search that finds nothing better answers.
  spread_edge_result normal{};
  ASSERT_EQ(spread_predict_edge(tables_, &d, &edge, &normal, nullptr, 0), SPREAD_OK);
  for (int32_t budget : {3, 5, 10, 40}) {
    SCOPED_TRACE(budget);
    spread_edge_setting setting{};
    spread_edge_result result{};
    int32_t finished = -1;
    ASSERT_EQ(spread_find_edge_setting_within(tables_, &d, &edge, budget, &setting, &result, nullptr, 0, &finished),
              SPREAD_OK)
        << spread_last_error_detail();
    EXPECT_EQ(finished, 0);
    EXPECT_LE(setting.predictions, budget);
    EXPECT_GE(setting.predictions, 3);
    // The setting found, given to spread_predict_edge, gives the same profile.
    spread_prediction_def at = d;
    at.disc_rpm[1] = setting.disc_rpm;
    at.disc_drop_point_turn_rad[1] = setting.disc_drop_point_turn_rad;
    at.disc_drop_point_turn_rad[0] = setting.field_side_drop_point_turn_rad;
    spread_edge_def with_flow = edge;
    with_flow.flow_fraction = setting.flow_fraction;
    spread_edge_result confirmed{};
    ASSERT_EQ(spread_predict_edge(tables_, &at, &with_flow, &confirmed, nullptr, 0), SPREAD_OK) << spread_last_error_detail();
    EXPECT_DOUBLE_EQ(confirmed.mass_beyond_percent, result.mass_beyond_percent);
    EXPECT_DOUBLE_EQ(confirmed.missing_inside_m, result.missing_inside_m);
    if (budget == 3) {
      // Nothing but the fixed predictions: the normal setting at its best flow.
      EXPECT_EQ(setting.disc_rpm, 650.0);
      EXPECT_EQ(setting.disc_drop_point_turn_rad, 0.0);
      EXPECT_TRUE(std::isnan(setting.field_side_drop_point_turn_rad));
      EXPECT_LT(setting.flow_fraction, 1.0);
      EXPECT_LT(result.mass_beyond_percent, normal.mass_beyond_percent);
    }
  }
  spread_edge_setting setting{};
  spread_edge_result result{};
  int32_t finished = 0;
  EXPECT_EQ(spread_find_edge_setting_within(tables_, &d, &edge, 2, &setting, &result, nullptr, 0, &finished),
            SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_NE(std::string(spread_last_error_detail()).find("max_predictions 2"), std::string::npos);
  EXPECT_EQ(spread_find_edge_setting_within(tables_, &d, &edge, 10, &setting, &result, nullptr, 0, nullptr),
            SPREAD_ERROR_NULL_POINTER);
}

TEST(CapiAbi, ReservedFieldsAreZeroedAndNeverRead) {
  spread_trajectory_def t = spread_trajectory_def_default();
  EXPECT_EQ(t.reserved, 0u);
  t.velocity_m_s[0] = 12.0;
  spread_landing clean;
  std::memset(&clean, 0xAB, sizeof clean);
  ASSERT_EQ(spread_trajectory(&t, &clean), SPREAD_OK);
  EXPECT_EQ(clean.reserved, 0);

  // What an older caller has there is padding: anything at all. The landing must not change.
  t.reserved = 0xDEADBEEFu;
  spread_landing dirty{};
  ASSERT_EQ(spread_trajectory(&t, &dirty), SPREAD_OK);
  EXPECT_EQ(std::memcmp(&dirty, &clean, sizeof clean), 0);

  // A definition without the reserved field (the first release where doubles are 4-byte aligned):
  // accepted, and the landing's reserved field, which that caller may not have, is not written.
  t.struct_size = static_cast<uint32_t>(spread::capi::kTrajectoryDefV1Size);
  spread_landing older;
  std::memset(&older, 0xAB, sizeof older);
  ASSERT_EQ(spread_trajectory(&t, &older), SPREAD_OK);
  EXPECT_EQ(older.flight_time_s, clean.flight_time_s);
  EXPECT_EQ(older.reserved, static_cast<int32_t>(0xABABABABu));
  t.struct_size = static_cast<uint32_t>(spread::capi::kTrajectoryDefV1Size - 1);
  EXPECT_EQ(spread_trajectory(&t, &older), SPREAD_ERROR_OUT_OF_RANGE);
}

TEST_F(Capi, UnexpectedExceptionIsInternalNotACrash) {
  // No input reaches the catch-all by design (the fuzzer's bout width 3.55e59 m once did: a bug, fixed);
  // the internal seam throws inside each entry point's try block instead.
  spread_prediction_def d = def();
  spread_prediction r{};
  spread::capi::detail::arm_internal_fault_for_test();
  EXPECT_EQ(spread_predict(tables_, &d, &r, nullptr, 0), SPREAD_ERROR_INTERNAL);
  EXPECT_EQ(spread_predict(tables_, &d, &r, nullptr, 0), SPREAD_OK);  // the handle is still usable

  spread_trajectory_def t = spread_trajectory_def_default();
  spread_landing landing{};
  spread::capi::detail::arm_internal_fault_for_test();
  EXPECT_EQ(spread_trajectory(&t, &landing), SPREAD_ERROR_INTERNAL);
  EXPECT_EQ(spread_trajectory(&t, &landing), SPREAD_OK);

  spread_tables* other = reinterpret_cast<spread_tables*>(0x1);
  spread::capi::detail::arm_internal_fault_for_test();
  EXPECT_EQ(spread_open(path_.c_str(), &other), SPREAD_ERROR_INTERNAL);
  EXPECT_EQ(other, nullptr);
}

TEST(CapiVersion, RunTimeMatchesCompileTime) {
  EXPECT_EQ(spread_version(), static_cast<uint32_t>(SPREAD_VERSION_NUMBER));
  EXPECT_STREQ(spread_version_string(), SPREAD_VERSION_STRING);
}

TEST(CapiStatus, EveryCodeHasItsOwnName) {
  std::set<std::string> names;
  // SPREAD_ERROR_BAD_HANDLE is the last code.
  for (int s = SPREAD_OK; s <= SPREAD_ERROR_BAD_HANDLE; ++s) {
    const std::string name = spread_status_str(static_cast<spread_status>(s));
    EXPECT_EQ(name.rfind("SPREAD_", 0), 0u) << s;
    names.insert(name);
  }
  EXPECT_EQ(names.size(), static_cast<size_t>(SPREAD_ERROR_BAD_HANDLE) + 1);
  EXPECT_STREQ(spread_status_str(static_cast<spread_status>(31)), "unknown status");
}

std::string read_all(const char* path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(CapiDocs, GuideCarriesTheCompiledExampleVerbatim) {
  const std::string doc = read_all(SPREAD_DOC_C_API);
  const std::string example = read_all(SPREAD_EXAMPLE_C);
  ASSERT_FALSE(example.empty());
  EXPECT_NE(doc.find(example), std::string::npos)
      << "docs/c-api.md must contain tests/capi/c_api_example.c verbatim";
}

}  // namespace
