// A failed pattern fit is refused, naming why; a residual far above the pass-to-pass scatter warns.
#include <gtest/gtest.h>

#include <string>

#include "libspread/analysis/calibration/fit_acceptance.hpp"

namespace cal = spread::calibration;

namespace {

cal::PatternFitResult good_fit() {
  cal::PatternFitResult f;
  f.fitted = {0.32, 1.2, 0.0};
  f.fitted_mask = {true, true, false};
  f.converged = true;
  f.iterations = 8;
  f.stop_reason = "step below tolerance";
  f.residual_rms_fraction = 0.001;
  return f;
}

cal::PassScatter scatter(double rms_mean_fraction) {
  cal::PassScatter s;
  s.available = true;
  s.passes = 3;
  s.rms_mean_fraction = rms_mean_fraction;
  return s;
}

bool any_contains(const std::vector<std::string>& texts, const std::string& part) {
  for (const std::string& t : texts) {
    if (t.find(part) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST(FitAcceptance, GoodFitIsAccepted) {
  const cal::FitAcceptance a = cal::assess_fit(good_fit(), scatter(0.0008));
  EXPECT_TRUE(a.accepted());
  EXPECT_TRUE(a.warnings.empty());
  EXPECT_NEAR(a.residual_to_scatter, 1.25, 1e-12);
}

TEST(FitAcceptance, NotConvergedIsRefused) {
  cal::PatternFitResult f = good_fit();
  f.converged = false;
  f.iterations = 17;
  f.stop_reason = "iteration limit";
  const cal::FitAcceptance a = cal::assess_fit(f, scatter(0.001));
  ASSERT_FALSE(a.accepted());
  EXPECT_TRUE(any_contains(a.refusals, "did not converge (17 iterations, iteration limit)"));
  EXPECT_TRUE(any_contains(a.refusals, "--fit friction,drag"));
}

TEST(FitAcceptance, ParameterOnItsBoundIsRefused) {
  // Friction 2.5e-6 (closer to 0 than the fit's 2e-3 difference step): on its lower bound.
  cal::PatternFitResult f = good_fit();
  f.fitted.friction_wall = 2.5e-6;
  cal::FitAcceptance a = cal::assess_fit(f, scatter(0.001));
  ASSERT_FALSE(a.accepted());
  EXPECT_TRUE(any_contains(a.refusals, "friction on the vanes ended on its lower bound"));
  // A fixed parameter at its bound is the technician's choice, not the fit's.
  f.fitted_mask = {false, true, false};
  EXPECT_TRUE(cal::assess_fit(f, scatter(0.001)).accepted());
  f = good_fit();
  f.fitted.drag_diameter_factor = 4.9995;
  a = cal::assess_fit(f, scatter(0.001));
  EXPECT_TRUE(any_contains(a.refusals, "drag diameter factor ended on its upper bound"));
}

TEST(FitAcceptance, ResidualFarAboveTheScatterWarns) {
  cal::PatternFitResult f = good_fit();
  f.residual_rms_fraction = 0.0031;
  const cal::FitAcceptance a = cal::assess_fit(f, scatter(0.001));
  EXPECT_TRUE(a.accepted());  // a warning, not a refusal: the model may still be the best there is
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_NE(a.warnings[0].find("3.1 times the tray test's own pass-to-pass scatter"), std::string::npos)
      << a.warnings[0];
  // Without passes to compare, no ratio and no warning.
  EXPECT_TRUE(cal::assess_fit(f, cal::PassScatter{}).warnings.empty());
}
