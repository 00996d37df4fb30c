// The setting chart: at each width it finds the setting (disc speed and drop point) with the lowest CV
// (no point of a scan in 25 rpm and 10 degree steps is better by more than half a CV point) and gives
// the candidate whose 95 % upper bound is lowest, every width that some setting reaches is reachable,
// the spans within the target are where the CV is, and bad input is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "libspread/analysis/predict/setting_chart.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace spread::predict {
namespace {

double cv_at(Predictor& predictor, double rpm, double width_m, double turn_rad = 0.0) {
  PredictionRequest request;
  request.material = "can";
  request.rpm = rpm;
  request.drop_point_turn_rad = turn_rad;
  request.bout_width_m = width_m;
  Prediction p;
  EXPECT_EQ(predictor.predict(request, p), PredictStatus::kOk);
  return p.cv_to_and_fro;
}

TEST(SettingChart, PicksTheLowestCvAndEveryReachableWidth) {
  Predictor predictor(testing::synthetic_contents());
  SettingChartOptions options;
  std::vector<double> widths;
  for (double w = 2.0; w <= 30.0; w += 4.0) widths.push_back(w);
  const SettingChart chart = setting_chart(predictor, "can", widths, options);
  EXPECT_EQ(chart.min_rpm, 500.0);
  EXPECT_EQ(chart.max_rpm, 800.0);
  ASSERT_EQ(chart.rows.size(), widths.size());
  // The grid holds every row and steps of at most kChartScanStep_rpm.
  for (std::size_t k = 1; k < chart.scan_rpm.size(); ++k) {
    EXPECT_LE(chart.scan_rpm[k] - chart.scan_rpm[k - 1], kChartScanStep_rpm + 1e-9);
  }
  int reached = 0, not_reached = 0;
  for (const SettingChartRow& row : chart.rows) {
    // A technician's scan in 25 rpm and 10 degree steps never finds a setting better by more than half a
    // CV point.
    double scan_best = std::numeric_limits<double>::infinity();
    for (double rpm = 500.0; rpm <= 800.0; rpm += 25.0) {
      for (double turn_deg = -90.0; turn_deg <= 90.0; turn_deg += 10.0) {
        scan_best = std::min(scan_best, cv_at(predictor, rpm, row.width_m, turn_deg * kPi / 180.0));
      }
    }
    ASSERT_TRUE(std::isfinite(row.rpm)) << row.width_m;
    EXPECT_LE(std::abs(row.drop_point_turn_rad), options.max_drop_point_turn_rad) << row.width_m;
    EXPECT_GE(row.cv_to_and_fro, 0.0);
    EXPECT_LE(row.lowest_cv, scan_best + 0.005) << row.width_m << " m at " << row.lowest_cv_rpm << " rpm";
    // The CVs reported are the predictor's at those settings.
    EXPECT_DOUBLE_EQ(row.cv_to_and_fro, cv_at(predictor, row.rpm, row.width_m, row.drop_point_turn_rad));
    EXPECT_DOUBLE_EQ(row.lowest_cv, cv_at(predictor, row.lowest_cv_rpm, row.width_m, row.lowest_cv_drop_point_turn_rad));
    // The chart's setting holds at least as surely as the lowest CV: its 95 % upper bound is not above
    // the lowest CV's, and it meets the target whenever the lowest CV does.
    EXPECT_LE(row.cv_to_and_fro + kConfidence95 * row.cv_to_and_fro_se,
              row.lowest_cv + kConfidence95 * row.lowest_cv_se + 1e-12) << row.width_m;
    if (row.lowest_cv <= options.cv_target) {
      EXPECT_LE(row.cv_to_and_fro, options.cv_target) << row.width_m;
    }
    // Reachable exactly when some setting meets the target.
    if (scan_best <= options.cv_target) {
      EXPECT_NE(row.reach, ChartReach::kNotReached) << row.width_m;
    }
    if (row.reach == ChartReach::kNotReached) {
      ++not_reached;
      EXPECT_GT(row.cv_to_and_fro, options.cv_target);
      EXPECT_TRUE(row.within_target_rpm.empty());
    } else {
      ++reached;
      EXPECT_LE(row.cv_to_and_fro, options.cv_target);
      EXPECT_EQ(row.reach == ChartReach::kReached,
                row.cv_to_and_fro + kConfidence95 * row.cv_to_and_fro_se <= options.cv_target);
      EXPECT_FALSE(row.within_target_rpm.empty()) << row.width_m;
    }
    // Inside each span the CV is within the target, just outside it is not (at grid points).
    for (const auto& [low, high] : row.within_target_rpm) {
      EXPECT_LE(low, high);
      const double mid = 0.5 * (low + high);
      EXPECT_LE(cv_at(predictor, mid, row.width_m, row.drop_point_turn_rad), options.cv_target + 0.01)
          << row.width_m << " m at " << mid;
    }
  }
  // The synthetic rows reach the narrow widths and not the widest.
  EXPECT_GT(reached, 0);
  EXPECT_GT(not_reached, 0);
}

TEST(SettingChart, BadInputIsRefused) {
  Predictor predictor(testing::synthetic_contents());
  const std::vector<double> widths{12.0}, zero{0.0};
  EXPECT_THROW(setting_chart(predictor, "sand", widths, {}), std::invalid_argument);
  EXPECT_THROW(setting_chart(predictor, "can", zero, {}), std::invalid_argument);
  SettingChartOptions wide;
  wide.max_drop_point_turn_rad = 4.0;
  EXPECT_THROW(setting_chart(predictor, "can", widths, wide), std::invalid_argument);
  SettingChartOptions no_step;
  no_step.drop_point_step_rad = 0.0;
  EXPECT_THROW(setting_chart(predictor, "can", widths, no_step), std::invalid_argument);
}

// With the drop point held at the table's, the chart is the speed-only chart: every row at turn 0.
TEST(SettingChart, NoDropPointRangeKeepsTheTablesDropPoint) {
  Predictor predictor(testing::synthetic_contents());
  SettingChartOptions options;
  options.max_drop_point_turn_rad = 0.0;
  const std::vector<double> widths{6.0, 14.0};
  const SettingChart chart = setting_chart(predictor, "can", widths, options);
  ASSERT_EQ(chart.grid_drop_point_turn_rad.size(), 1u);
  for (const SettingChartRow& row : chart.rows) EXPECT_EQ(row.drop_point_turn_rad, 0.0);
}

}  // namespace
}  // namespace spread::predict
