#include "libspread/analysis/calibration/fit_acceptance.hpp"

#include <array>
#include <cmath>
#include <cstdio>

namespace spread::calibration {
namespace {

struct Range {
  const char* name;        // as --fit names it
  const char* quantity;
  double low, high;        // check_parameters' range, in the fitted unit (δ in rad)
  double margin;           // the fit's central-difference step (pattern_fit.cpp)
  double to_display;       // factor into the unit printed
  const char* unit;
};
constexpr double kDegPerRad = 180.0 / kPi;
constexpr std::array<Range, kPatternParameterCount> kRanges{{
    {"friction", "friction on the vanes", 0.0, 2.0, 2e-3, 1.0, ""},
    {"drag", "drag diameter factor", 0.2, 5.0, 2e-3, 1.0, ""},
    {"offset", "launch-angle offset", -0.5 * kPi, 0.5 * kPi, 1e-3, kDegPerRad, " deg"},
    {"speed", "launch speed factor", 0.5, 2.0, 2e-3, 1.0, ""},
    {"elevation", "launch elevation offset", -kPi / 6.0, kPi / 6.0, 1e-3, kDegPerRad, " deg"},
}};

}  // namespace

FitAcceptance assess_fit(const PatternFitResult& fit, const PassScatter& scatter) {
  FitAcceptance a;
  if (!fit.converged) {
    a.refusals.push_back("the fit did not converge (" + std::to_string(fit.iterations) + " iterations, " +
                         fit.stop_reason +
                         "): check that --rpm is the tray test's disc speed and that the table's scene (inlet, "
                         "vanes) is the machine's; fit fewer parameters (e.g. --fit friction,drag; on a DEM "
                         "table --fit speed,offset); or start from a material nearer the truth");
  }
  const std::array<double, kPatternParameterCount> value = as_array(fit.fitted);
  for (std::size_t i = 0; i < kPatternParameterCount; ++i) {
    if (!fit.fitted_mask[i]) continue;
    const Range& r = kRanges[i];
    const bool at_low = value[i] - r.low < r.margin;
    const bool at_high = r.high - value[i] < r.margin;
    if (!at_low && !at_high) continue;
    char text[512];
    std::snprintf(text, sizeof text,
                  "%s ended on its %s bound (%.4g%s, range %.4g to %.4g%s): the model cannot reproduce the tray "
                  "test with a value inside its range — check --rpm, the tray positions (centre line, left "
                  "negative) and the table's scene; or fix it (--fit without %s) and fit the others",
                  r.quantity, at_low ? "lower" : "upper", value[i] * r.to_display, r.unit, r.low * r.to_display,
                  r.high * r.to_display, r.unit, r.name);
    a.refusals.emplace_back(text);
  }
  if (scatter.available && scatter.rms_mean_fraction > 0.0) {
    a.residual_to_scatter = fit.residual_rms_fraction / scatter.rms_mean_fraction;
    if (a.residual_to_scatter > kResidualToScatterLimit) {
      char text[512];
      std::snprintf(text, sizeof text,
                    "the residual (rms %.3g %% of the mass per tray) is %.1f times the tray test's own "
                    "pass-to-pass scatter (%.3g %% for the mean of %d passes; limit %.0f): the model does not "
                    "describe this tray test — check --rpm, the inlet and the tray positions before using "
                    "the calibrated material",
                    100.0 * fit.residual_rms_fraction, a.residual_to_scatter, 100.0 * scatter.rms_mean_fraction,
                    scatter.passes, kResidualToScatterLimit);
      a.warnings.emplace_back(text);
    }
  }
  return a;
}

}  // namespace spread::calibration
