// The repeatability interval of a tray test's CV (tray_cv_interval.hpp): exact where it must be, and the
// propagated uncertainty against the scatter of the CV over many simulated tray tests.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "libspread/analysis/calibration/tray_cv_interval.hpp"

namespace cal = spread::calibration;
using spread::metrics::Overlap;

namespace {

// 25 trays of 0.5 m (-6..6 m) holding a two-lobed pattern, grams.
std::vector<double> two_lobes_g() {
  std::vector<double> g;
  for (int k = -12; k <= 12; ++k) {
    const double x = 0.5 * k;
    g.push_back(20.0 * std::exp(-0.5 * std::pow((x - 2.5) / 1.3, 2)) + 20.0 * std::exp(-0.5 * std::pow((x + 2.5) / 1.3, 2)));
  }
  return g;
}

std::string csv(const std::vector<std::vector<double>>& passes_g) {
  std::string text = "position_m";
  for (std::size_t p = 0; p < passes_g.size(); ++p) text += ",p" + std::to_string(p + 1) + "_g";
  text += "\n";
  for (std::size_t i = 0; i < passes_g[0].size(); ++i) {
    char cell[48];
    std::snprintf(cell, sizeof cell, "%.2f", 0.5 * (static_cast<double>(i) - 12.0));
    text += cell;
    for (const auto& pass : passes_g) {
      std::snprintf(cell, sizeof cell, ",%.17g", pass[i]);  // exact: a doubled pass stays one shape
      text += cell;
    }
    text += "\n";
  }
  return text;
}

}  // namespace

TEST(TrayCvInterval, PassesOfOneShapeLeaveNoUncertainty) {
  // The second pass carried twice the fertiliser in the same pattern: the CV cannot be in doubt.
  std::vector<double> a = two_lobes_g(), b = a;
  for (double& m : b) m *= 2.0;
  const cal::TrayTest t = cal::parse_tray_csv(csv({a, b}), "t.csv");
  const cal::TrayCvInterval i = cal::tray_cv_interval(t, 8, Overlap::kToAndFro);
  ASSERT_TRUE(i.available);
  EXPECT_GT(i.cv, 0.0);
  EXPECT_NEAR(i.standard_uncertainty, 0.0, 1e-9);
  EXPECT_NEAR(i.low, i.cv, 1e-9);
  EXPECT_NEAR(i.high, i.cv, 1e-9);
}

TEST(TrayCvInterval, OnePassHasNone) {
  const cal::TrayTest t = cal::parse_tray_csv(csv({two_lobes_g()}), "t.csv");
  EXPECT_FALSE(cal::tray_cv_interval(t, 8, Overlap::kToAndFro).available);
}

// 600 simulated tests of three passes, each tray read with a normal error of 6 % of its mass: the
// propagated u(CV) matches the CV's scatter over the tests, and about 95 % of the intervals hold the
// CV's mean over them (~0.1 s).
TEST(TrayCvInterval, PropagatedUncertaintyMatchesTheScatterOfTheCv) {
  const std::vector<double> truth = two_lobes_g();
  std::mt19937_64 random(20261127);
  std::normal_distribution<double> normal(0.0, 1.0);
  constexpr int kTests = 600;
  std::vector<cal::TrayCvInterval> runs;
  for (int n = 0; n < kTests; ++n) {
    std::vector<std::vector<double>> passes(3, truth);
    for (auto& pass : passes) {
      for (double& m : pass) m = std::max(0.0, m * (1.0 + 0.06 * normal(random)));
    }
    runs.push_back(cal::tray_cv_interval(cal::parse_tray_csv(csv(passes), "t.csv"), 8, Overlap::kToAndFro));
    ASSERT_TRUE(runs.back().available);
  }
  double mean = 0.0, mean_u = 0.0;
  for (const auto& r : runs) {
    mean += r.cv / kTests;
    mean_u += r.standard_uncertainty / kTests;
  }
  double variance = 0.0;
  for (const auto& r : runs) variance += (r.cv - mean) * (r.cv - mean) / (kTests - 1);
  const double sd = std::sqrt(variance);
  // Of the order of a CV point: the test is not about a vanishing quantity.
  EXPECT_GT(sd, 0.003);
  EXPECT_NEAR(mean_u / sd, 1.0, 0.15) << "u " << mean_u << " against the scatter " << sd;
  int covered = 0;
  for (const auto& r : runs) covered += r.low <= mean && mean <= r.high ? 1 : 0;
  EXPECT_GT(covered, 0.90 * kTests);
  EXPECT_LT(covered, 0.99 * kTests);
}
