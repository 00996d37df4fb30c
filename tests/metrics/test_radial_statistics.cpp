// Seed Eqs. 51–52: R̄ and ξ.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "libspread/analysis/metrics/metrics.hpp"

namespace sm = spread::metrics;

namespace {
void add_ring(double cx, double cy, double r, double ring_mass, int n, std::vector<double>& x,
              std::vector<double>& y, std::vector<double>& m) {
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * 3.14159265358979323846 * i / n;
    x.push_back(cx + r * std::cos(a));
    y.push_back(cy + r * std::sin(a));
    m.push_back(ring_mass / n);
  }
}
}  // namespace

TEST(RadialStatistics, CircleHasZeroWidth) {
  std::vector<double> x, y, m;
  add_ring(1.5, -2.0, 7.0, 3.0, 37, x, y, m);
  const sm::RadialStats s = sm::radial_statistics(x, y, m, 1.5, -2.0);
  EXPECT_NEAR(s.mean_radius_m, 7.0, 1e-12);
  EXPECT_NEAR(s.radial_width_m, 0.0, 1e-12);
}

TEST(RadialStatistics, TwoRings) {
  // Equal masses at r = 2 and 4: R̄ = 3, ξ = 1. Masses 3:1: R̄ = (3·2 + 4)/4 = 2.5,
  // ξ = (3·0.5 + 1·1.5)/4 = 0.75.
  std::vector<double> x, y, m;
  add_ring(0, 0, 2.0, 1.0, 20, x, y, m);
  add_ring(0, 0, 4.0, 1.0, 33, x, y, m);
  sm::RadialStats s = sm::radial_statistics(x, y, m);
  EXPECT_NEAR(s.mean_radius_m, 3.0, 1e-12);
  EXPECT_NEAR(s.radial_width_m, 1.0, 1e-12);
  x.clear(), y.clear(), m.clear();
  add_ring(0, 0, 2.0, 3.0, 20, x, y, m);
  add_ring(0, 0, 4.0, 1.0, 33, x, y, m);
  s = sm::radial_statistics(x, y, m);
  EXPECT_NEAR(s.mean_radius_m, 2.5, 1e-12);
  EXPECT_NEAR(s.radial_width_m, 0.75, 1e-12);
}

TEST(RadialStatistics, EdgeCases) {
  const sm::RadialStats empty = sm::radial_statistics({}, {}, {});
  EXPECT_EQ(empty.mean_radius_m, 0.0);
  EXPECT_EQ(empty.radial_width_m, 0.0);
  const std::vector<double> x{1, 2}, y{0, 0}, zero{0, 0};
  const sm::RadialStats massless = sm::radial_statistics(x, y, zero);
  EXPECT_EQ(massless.mean_radius_m, 0.0);
  EXPECT_EQ(massless.radial_width_m, 0.0);
  const std::vector<double> short_y{0};
  EXPECT_THROW(sm::radial_statistics(x, short_y, zero), std::invalid_argument);
}
