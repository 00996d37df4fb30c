// Throw width: the lateral extent holding a fraction of the mass, mass uniform within trays.
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "libspread/analysis/metrics/metrics.hpp"

namespace sm = spread::metrics;

TEST(ThrowWidth, UniformStrip) {
  // 10 m of uniform mass (trays 10..29 of 40): 99 % of it lies in the middle 9.9 m.
  sm::TrayLayout trays;
  trays.tray_count = 40;
  std::vector<double> p(40, 0.0);
  for (int i = 10; i < 30; ++i) p[static_cast<std::size_t>(i)] = 0.3;
  EXPECT_NEAR(sm::throw_width(p, trays), 9.9, 1e-12);
  EXPECT_NEAR(sm::throw_width(p, trays, 1.0), 10.0, 1e-12);
  EXPECT_NEAR(sm::throw_width(p, trays, 0.5), 5.0, 1e-12);
}

TEST(ThrowWidth, AsymmetricByHand) {
  // Trays [-1,-0.5]: 1 kg, [-0.5,0]: 0, [0,0.5]: 3 kg, [0.5,1]: 0; total 4 kg, f = 0.5 → tails of 1 kg.
  // Left quantile: the whole first tray (x = -0.5). Right: 1 kg into the 3 kg tray from its right edge,
  // x = 0.5 - 0.5/3. Width = 1 - 1/6.
  sm::TrayLayout trays;
  trays.tray_count = 4;
  const std::vector<double> p{1.0, 0.0, 3.0, 0.0};
  EXPECT_NEAR(sm::throw_width(p, trays, 0.5), 1.0 - 1.0 / 6.0, 1e-12);
  EXPECT_NEAR(sm::throw_width(p, trays, 1.0), 1.5, 1e-12);
}

TEST(ThrowWidth, EdgeCases) {
  sm::TrayLayout trays;
  trays.tray_count = 6;
  EXPECT_EQ(sm::throw_width(std::vector<double>(6, 0.0), trays), 0.0);
  sm::TrayLayout empty;
  EXPECT_EQ(sm::throw_width({}, empty), 0.0);
  std::vector<double> one_tray(6, 0.0);
  one_tray[2] = 1.0;
  EXPECT_NEAR(sm::throw_width(one_tray, trays), 0.99 * 0.5, 1e-12);
  EXPECT_THROW(sm::throw_width(one_tray, trays, 0.0), std::invalid_argument);
  EXPECT_THROW(sm::throw_width(one_tray, trays, 1.5), std::invalid_argument);
  EXPECT_THROW(sm::throw_width(std::vector<double>(5, 1.0), trays), std::invalid_argument);
}
