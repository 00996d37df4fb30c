// The quick check: χ² quantiles, McKay's interval of a CV from few trays, and the check by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "libspread/analysis/calibration/cv_interval.hpp"
#include "libspread/analysis/calibration/quick_check.hpp"
#include "libspread/analysis/calibration/tray_csv.hpp"

namespace cal = spread::calibration;

TEST(CvInterval, ChiSquareQuantilesAsTabulated) {
  // Tables of the χ² distribution (e.g. NIST/SEMATECH e-Handbook 1.3.6.7.4), 4 significant digits.
  EXPECT_NEAR(cal::chi_square_quantile(0.025, 3), 0.2158, 5e-5);
  EXPECT_NEAR(cal::chi_square_quantile(0.975, 3), 9.348, 5e-4);
  EXPECT_NEAR(cal::chi_square_quantile(0.025, 7), 1.690, 5e-4);
  EXPECT_NEAR(cal::chi_square_quantile(0.975, 7), 16.013, 5e-4);
  EXPECT_NEAR(cal::chi_square_quantile(0.5, 1), 0.4549, 5e-5);
  EXPECT_THROW(cal::chi_square_quantile(0.0, 3), std::invalid_argument);
  EXPECT_THROW(cal::chi_square_quantile(0.5, 0), std::invalid_argument);
}

TEST(CvInterval, McKayByHand) {
  // K = 10 % from 4 trays (ν = 3): 0.1 / sqrt((9.348/4 − 1)·0.01 + 9.348/3) = 5.65 %, and with
  // u = 0.2158: 0.1 / sqrt((0.2158/4 − 1)·0.01 + 0.2158/3) = 40.0 %.
  const cal::CvInterval i = cal::cv_interval(0.10, 4);
  EXPECT_NEAR(i.low, 0.0565, 5e-4);
  EXPECT_NEAR(i.high, 0.400, 5e-4);
  // More trays, a narrower interval around the same CV.
  const cal::CvInterval eight = cal::cv_interval(0.10, 8);
  EXPECT_GT(eight.low, i.low);
  EXPECT_LT(eight.high, i.high);
  EXPECT_NEAR(eight.low, 0.066, 5e-4);  // the numbers docs/field-calibration.md quotes
  EXPECT_NEAR(eight.high, 0.207, 5e-4);
  // A CV of 100 % from 4 trays has no upper bound.
  EXPECT_TRUE(std::isinf(cal::cv_interval(1.0, 4).high));
  EXPECT_THROW(cal::cv_interval(0.1, 1), std::invalid_argument);
}

TEST(QuickCheck, FourTraysByHand) {
  // 10, 12, 8, 10 g: mean 10, s = sqrt(8/3) = 1.633 g, CV 16.3 %; 95 % interval 9.2–75.6 %: the 15 %
  // target lies inside — undecided. Positions 3 m apart from the tramline, off the centre-line grid.
  const cal::TrayTest t = cal::parse_tray_csv("position_m,mass_g\n0.5,10\n3.5,12\n6.5,8\n9.5,10\n", "four.csv",
                                              cal::quick_check_csv_options());
  const cal::QuickCheck q = cal::quick_check(t, 0.15);
  EXPECT_EQ(q.trays, 4);
  EXPECT_NEAR(q.mean_kg, 0.010, 1e-12);
  EXPECT_NEAR(q.cv, std::sqrt(8.0 / 3.0) / 10.0, 1e-12);
  EXPECT_NEAR(q.interval.low, 0.092, 5e-4);
  EXPECT_NEAR(q.interval.high, 0.756, 5e-4);
  EXPECT_EQ(q.verdict, cal::QuickCheckVerdict::kUndecided);
  // The full tray test's rules refuse the same file (4 trays, off the grid).
  EXPECT_THROW(cal::parse_tray_csv("position_m,mass_g\n0.5,10\n3.5,12\n6.5,8\n9.5,10\n", "four.csv"), cal::TrayCsvError);
}

TEST(QuickCheck, VerdictsAtTheEnds) {
  const cal::TrayCsvOptions options = cal::quick_check_csv_options();
  // Eight trays within ±4 %: even the interval's top is below 15 %.
  const cal::TrayTest even = cal::parse_tray_csv(
      "position_m,mass_g\n1,10\n3,10.4\n5,9.6\n7,10.2\n9,9.8\n11,10.3\n13,9.7\n15,10\n", "even.csv", options);
  EXPECT_EQ(cal::quick_check(even, 0.15).verdict, cal::QuickCheckVerdict::kMeetsTarget);
  // Four trays 2, 10, 18, 10 g (CV 65 %): even the interval's bottom is above 15 %.
  const cal::TrayTest uneven = cal::parse_tray_csv("position_m,mass_g\n1,2\n3,10\n5,18\n7,10\n", "uneven.csv", options);
  EXPECT_EQ(cal::quick_check(uneven, 0.15).verdict, cal::QuickCheckVerdict::kFailsTarget);
  // A missing tray is left out: of five, four remain (accepted); of four, three (refused).
  const cal::TrayTest missing =
      cal::parse_tray_csv("position_m,mass_g\n1,2\n3,NA\n5,18\n7,10\n9,10\n", "missing.csv", options);
  EXPECT_EQ(cal::quick_check(missing, 0.15).trays, 4);
  EXPECT_THROW(cal::parse_tray_csv("position_m,mass_g\n1,2\n3,NA\n5,18\n7,10\n", "three.csv", options),
               cal::TrayCsvError);
}
