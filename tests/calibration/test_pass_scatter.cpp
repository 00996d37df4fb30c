// The tray test's own pass-to-pass scatter, by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "libspread/analysis/calibration/pass_scatter.hpp"

namespace cal = spread::calibration;

TEST(PassScatter, TwoPassesByHand) {
  // Pass 1: 1, 2, 4, 2, 1 g (10 g); pass 2: 1, 3, 2, 3, 1 g (10 g). Fractions differ by 0, .1, .2, .1, 0:
  // per tray s² = d²/2 (two passes, mean halfway) → Σ s² = (0.01 + 0.04 + 0.01) / 2 = 0.03;
  // one pass rms sqrt(0.03 / 5), the mean of two ÷ √2, in grams × 10 g.
  const cal::TrayTest t = cal::parse_tray_csv(
      "position_m,p1_g,p2_g\n-1.0,1,1\n-0.5,2,3\n0.0,4,2\n0.5,2,3\n1.0,1,1\n", "t.csv");
  const cal::PassScatter s = cal::pass_scatter(t);
  ASSERT_TRUE(s.available);
  EXPECT_EQ(s.passes, 2);
  EXPECT_EQ(s.trays, 5);
  EXPECT_NEAR(s.rms_one_pass_fraction, std::sqrt(0.03 / 5.0), 1e-12);
  EXPECT_NEAR(s.rms_mean_fraction, std::sqrt(0.03 / 5.0) / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(s.rms_one_pass_g, 10.0 * std::sqrt(0.03 / 5.0), 1e-9);
}

TEST(PassScatter, OnePassHasNone) {
  const cal::TrayTest t = cal::parse_tray_csv("position_m,mass_g\n-1.0,1\n-0.5,2\n0.0,4\n0.5,2\n1.0,1\n", "t.csv");
  EXPECT_FALSE(cal::pass_scatter(t).available);
}
