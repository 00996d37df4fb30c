// The setting chart on the main job's table (the DEM table of scenes/default.toml, built by the ctest
// fixture capi.fixture.default_scene): for every material and tramline widths 6–24 m, no disc speed of a
// scan in 25 rpm steps has a CV lower by more than half a point than the chart's choice, and a width is
// "not reachable" only when no scanned setting meets the target. Run through ctest (the fixture builds
// the file).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "libspread/analysis/predict/setting_chart.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace {

namespace pr = spread::predict;

TEST(DefaultChart, NoScanSettingBeatsTheChart) {
  if (!std::filesystem::exists(SPREAD_DEFAULT_TABLE)) {
    GTEST_SKIP() << SPREAD_DEFAULT_TABLE << " missing: run through ctest (fixture capi.fixture.default_scene)";
  }
  pr::Predictor predictor(spread::tables::read_table_file(SPREAD_DEFAULT_TABLE));
  ASSERT_EQ(predictor.material_count(), 3u);
  const std::vector<double> widths{6, 8, 10, 12, 15, 18, 21, 24};
  for (std::size_t m = 0; m < predictor.material_count(); ++m) {
    const std::string name = predictor.material(m).name;
    pr::SettingChartOptions options;
    const pr::SettingChart chart = pr::setting_chart(predictor, name, widths, options);
    ASSERT_EQ(chart.rows.size(), widths.size());
    for (const pr::SettingChartRow& row : chart.rows) {
      double scan_best = std::numeric_limits<double>::infinity(), scan_rpm = 0.0;
      for (double rpm = chart.min_rpm; rpm <= chart.max_rpm + 1e-9; rpm += 25.0) {
        pr::PredictionRequest request;
        request.material = name;
        request.rpm = rpm;
        request.bout_width_m = row.width_m;
        pr::Prediction p;
        ASSERT_EQ(predictor.predict(request, p), pr::PredictStatus::kOk);
        if (p.cv_to_and_fro < scan_best) {
          scan_best = p.cv_to_and_fro;
          scan_rpm = rpm;
        }
      }
      EXPECT_LE(row.cv_to_and_fro, scan_best + 0.005)
          << name << " " << row.width_m << " m: chart " << row.rpm << " rpm, scan " << scan_rpm << " rpm";
      if (scan_best <= options.cv_target) {
        EXPECT_NE(row.reach, pr::ChartReach::kNotReached) << name << " " << row.width_m << " m";
      }
    }
  }
}

}  // namespace
