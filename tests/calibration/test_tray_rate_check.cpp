// The rate a tray test caught and EN 13739-2's 90–110 % check, by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "libspread/analysis/calibration/tray_rate_check.hpp"

namespace cal = spread::calibration;

TEST(TrayRateCheck, RateByHand) {
  // 100 g per pass over trays 0.5 m wide and 0.5 m deep (0.25 m²), driven at 12 m: a strip 12 m × 0.5 m
  // holds 100 g → 0.1 kg / 6 m² = 166.67 kg/ha. The same as (M / n) / A with n = 24 trays.
  const cal::TrayRateCheck check = cal::tray_rate_check(0.1, 12.0, 0.5, 0.25, std::numeric_limits<double>::quiet_NaN());
  EXPECT_NEAR(check.rate_kg_ha, 0.1 / 6.0 * 1e4, 1e-9);
  EXPECT_NEAR(check.rate_kg_ha, 0.1 / 24.0 / 0.25 * 1e4, 1e-9);
  EXPECT_FALSE(check.checked());
  EXPECT_FALSE(check.pass);
}

TEST(TrayRateCheck, NinetyToOneHundredTenPercentPass) {
  const double caught = 0.1 / 6.0 * 1e4;  // 166.67 kg/ha
  EXPECT_TRUE(cal::tray_rate_check(0.1, 12.0, 0.5, 0.25, caught / 0.9).pass);    // exactly 90 %
  EXPECT_FALSE(cal::tray_rate_check(0.1, 12.0, 0.5, 0.25, caught / 0.89).pass);  // 89 %
  EXPECT_TRUE(cal::tray_rate_check(0.1, 12.0, 0.5, 0.25, caught / 1.1).pass);    // 110 %
  EXPECT_FALSE(cal::tray_rate_check(0.1, 12.0, 0.5, 0.25, caught / 1.11).pass);  // 111 %
  const cal::TrayRateCheck check = cal::tray_rate_check(0.1, 12.0, 0.5, 0.25, 150.0);
  EXPECT_NEAR(check.caught_percent, 100.0 * caught / 150.0, 1e-9);
}

TEST(TrayRateCheck, BadInputIsRefused) {
  EXPECT_THROW(cal::tray_rate_check(0.1, 0.0, 0.5, 0.25, 100.0), std::invalid_argument);
  EXPECT_THROW(cal::tray_rate_check(0.1, 12.0, 0.5, -1.0, 100.0), std::invalid_argument);
  EXPECT_THROW(cal::tray_rate_check(0.1, 12.0, 0.5, 0.25, 0.0), std::invalid_argument);
  EXPECT_THROW(cal::tray_rate_check(-0.1, 12.0, 0.5, 0.25, 100.0), std::invalid_argument);
}
