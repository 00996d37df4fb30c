// The setting chart: the rpm it finds gives the width asked, widths beyond the table's range are said to
// be so, and bad input is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "libspread/analysis/predict/setting_chart.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace spread::predict {
namespace {

TEST(SettingChart, FoundRpmGivesTheWidth) {
  Predictor predictor(testing::synthetic_contents());
  SettingChartOptions options;
  // A first chart only to learn the range of working widths the "can" rows give.
  const std::vector<double> probe{1.0};
  const SettingChart range = setting_chart(predictor, "can", probe, options);
  ASSERT_EQ(range.scan_rpm.size(), static_cast<std::size_t>(kScanPoints));
  EXPECT_EQ(range.min_rpm, 500.0);
  EXPECT_EQ(range.max_rpm, 800.0);
  const double narrowest = *std::min_element(range.scan_working_width_m.begin(), range.scan_working_width_m.end());
  const double widest = *std::max_element(range.scan_working_width_m.begin(), range.scan_working_width_m.end());
  ASSERT_GT(widest, narrowest + 1.0);

  const std::vector<double> widths{0.5 * (narrowest + widest), 0.5 * narrowest, widest + 50.0};
  const SettingChart chart = setting_chart(predictor, "can", widths, options);
  ASSERT_EQ(chart.rows.size(), 3u);
  const SettingChartRow& middle = chart.rows[0];
  // The synthetic rows' working width grows smoothly with rpm: the middle width is reached.
  ASSERT_EQ(middle.reach, ChartReach::kReached) << to_string(middle.reach);
  {
    EXPECT_GE(middle.rpm, 500.0);
    EXPECT_LE(middle.rpm, 800.0);
    // The predictor at that rpm: the working width within half a tray of the width asked.
    PredictionRequest request;
    request.material = "can";
    request.rpm = middle.rpm;
    Prediction p;
    ASSERT_EQ(predictor.predict(request, p), PredictStatus::kOk);
    EXPECT_NEAR(p.working_width_to_and_fro_m, widths[0], 0.5 * options.tray_width_m);
    EXPECT_TRUE(std::isfinite(middle.cv_to_and_fro));
    EXPECT_GT(middle.cv_to_and_fro_se, 0.0);
  }
  EXPECT_EQ(chart.rows[1].reach, ChartReach::kTooNarrow);
  EXPECT_TRUE(std::isnan(chart.rows[1].rpm));
  EXPECT_EQ(chart.rows[2].reach, ChartReach::kTooWide);
}

TEST(SettingChart, BadInputIsRefused) {
  Predictor predictor(testing::synthetic_contents());
  const std::vector<double> widths{12.0}, zero{0.0};
  EXPECT_THROW(setting_chart(predictor, "sand", widths, {}), std::invalid_argument);
  EXPECT_THROW(setting_chart(predictor, "can", zero, {}), std::invalid_argument);
}

}  // namespace
}  // namespace spread::predict
