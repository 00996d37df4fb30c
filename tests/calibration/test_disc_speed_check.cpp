// A pattern fit whose launch correction says the disc speed given was not the tray test's is flagged.
#include <gtest/gtest.h>

#include <string>

#include "libspread/analysis/calibration/disc_speed_check.hpp"

namespace cal = spread::calibration;

namespace {

// A DEM-row fit (speed and offset) with the given result.
cal::PatternFitResult speed_offset_fit(double speed_factor, double offset_deg) {
  cal::PatternFitResult f;
  f.fitted_mask[cal::kLaunchSpeed] = true;
  f.fitted_mask[cal::kAngleOffset] = true;
  f.fitted.launch_speed_factor = speed_factor;
  f.fitted.launch_angle_offset_rad = offset_deg * spread::kPi / 180.0;
  return f;
}

}  // namespace

TEST(DiscSpeedCheck, WalkthroughCorrectionIsQuiet) {
  // The walkthrough's test at its own 600 rpm: 0.9465 and 3.68° (docs/field-calibration.md).
  EXPECT_TRUE(cal::disc_speed_warnings(speed_offset_fit(0.9465, 3.68), 600.0).empty());
}

TEST(DiscSpeedCheck, WrongDiscSpeedIsNamed) {
  // The same 600 rpm test fitted at --rpm 750: 0.802 and 11.9°.
  const std::vector<std::string> w = cal::disc_speed_warnings(speed_offset_fit(0.802, 11.9), 750.0);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NE(w[0].find("the launch speed factor 0.802 is 20 % from 1 (warning beyond 15 %"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("one at about 602 rpm fitted at --rpm 750"), std::string::npos) << w[0];
  EXPECT_NE(w[1].find("the launch-angle offset 11.9 deg is beyond 10 deg"), std::string::npos) << w[1];
}

TEST(DiscSpeedCheck, ParametersNotFittedAreNotJudged) {
  cal::PatternFitResult f = speed_offset_fit(0.7, 20.0);
  f.fitted_mask = {};
  EXPECT_TRUE(cal::disc_speed_warnings(f, 750.0).empty());
}
