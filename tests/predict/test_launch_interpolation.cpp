// Row bracketing and pairwise launch-sample interpolation (the rank path: test_launch_rank_order.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "libspread/analysis/predict/launch_interpolation.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace spread::predict {
namespace {

TEST(BracketRpm, ExactRowNeedsNoInterpolation) {
  const std::vector<double> rows{500, 600, 700};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto b = bracket_rpm(rows, rows[i]);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->lower, i);
    EXPECT_EQ(b->upper, i);
    EXPECT_EQ(b->upper_weight, 0.0);
  }
}

TEST(BracketRpm, BetweenRowsGivesLinearWeight) {
  const std::vector<double> rows{500, 600, 700};
  const auto b = bracket_rpm(rows, 675.0);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->lower, 1u);
  EXPECT_EQ(b->upper, 2u);
  EXPECT_DOUBLE_EQ(b->upper_weight, 0.75);
}

TEST(BracketRpm, OutsideOrNotFiniteIsRefused) {
  const std::vector<double> rows{500, 600};
  EXPECT_FALSE(bracket_rpm(rows, 499.999));
  EXPECT_FALSE(bracket_rpm(rows, 600.001));
  EXPECT_FALSE(bracket_rpm(rows, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(bracket_rpm(std::vector<double>{}, 500.0));
  const std::vector<double> single{550};
  EXPECT_TRUE(bracket_rpm(single, 550.0));
  EXPECT_FALSE(bracket_rpm(single, 551.0));
}

TEST(InterpolateLaunchSamples, PairwiseIsFieldByFieldLinear) {
  const auto a = testing::synthetic_samples(500.0, 16, 1800.0);
  auto b = testing::synthetic_samples(700.0, 16, 1800.0);
  for (auto& s : b) s.mass_kg *= 2.0f;  // make mass interpolation visible
  std::vector<tables::LaunchSample> out(16);
  std::vector<double> w(16);
  ASSERT_EQ(interpolate_launch_samples(a, b, 0.25, out, w), 16u);
  for (std::size_t k = 0; k < 16; ++k) {
    EXPECT_NEAR(out[k].vx_norm, 0.75 * a[k].vx_norm + 0.25 * b[k].vx_norm, 1e-6);
    EXPECT_NEAR(out[k].vy_norm, 0.75 * a[k].vy_norm + 0.25 * b[k].vy_norm, 1e-6);
    EXPECT_NEAR(out[k].mass_kg, 1.25 * a[k].mass_kg, 1e-6 * a[k].mass_kg);
    EXPECT_DOUBLE_EQ(w[k], double{out[k].mass_kg});
  }
}

TEST(InterpolateLaunchSamples, ZeroWeightCopiesTheLowerRow) {
  const auto a = testing::synthetic_samples(500.0, 8, 1800.0);
  const auto b = testing::synthetic_samples(700.0, 5, 1800.0);
  std::vector<tables::LaunchSample> out(13);
  std::vector<double> w(13);
  ASSERT_EQ(interpolate_launch_samples(a, b, 0.0, out, w), 8u);
  for (std::size_t k = 0; k < 8; ++k) {
    EXPECT_EQ(out[k].vx_norm, a[k].vx_norm);
    EXPECT_EQ(w[k], double{a[k].mass_kg});
  }
}

TEST(InterpolateLaunchSamples, UnequalRowsOrTooSmallOutputAreErrors) {
  const auto a = testing::synthetic_samples(500.0, 8, 1800.0);
  const auto b = testing::synthetic_samples(700.0, 5, 1800.0);
  std::vector<tables::LaunchSample> out(13);
  std::vector<double> w(13);
  EXPECT_THROW(interpolate_launch_samples(a, b, 0.5, out, w), std::invalid_argument);  // rank path's job
  std::vector<tables::LaunchSample> small(7);
  EXPECT_THROW(interpolate_launch_samples(a, a, 0.5, small, w), std::length_error);
}

}  // namespace
}  // namespace spread::predict
