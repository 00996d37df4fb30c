#pragma once
// Whether a pattern fit may become a calibrated material (docs/field-calibration.md, "When the fit is
// refused"). A material written into a table is used by `predict` as if it were measured, so a fit that
// did not reach a minimum, or reached it only by running into a parameter's range, is refused; a fit
// whose residual is far above the tray test's own pass-to-pass scatter is accepted with a warning (the
// model may still be the best available, but the technician must know it does not fit).
#include <string>
#include <vector>

#include "libspread/analysis/calibration/pass_scatter.hpp"
#include "libspread/analysis/calibration/pattern_fit.hpp"

namespace spread::calibration {

struct FitAcceptance {
  // Each a sentence naming the reason and what to try; the fit is usable when `refusals` is empty.
  std::vector<std::string> refusals;
  std::vector<std::string> warnings;
  // residual_rms_fraction / scatter.rms_mean_fraction; 0 when the scatter is not available.
  double residual_to_scatter = 0.0;
  bool accepted() const { return refusals.empty(); }
};

// A fitted parameter counts as on a bound when it is closer to the end of its range (check_parameters)
// than the fit's finite-difference step: there the Jacobian reaches outside the range, the standard
// error means nothing, and the best value may lie beyond what the model allows.
FitAcceptance assess_fit(const PatternFitResult& fit, const PassScatter& scatter);

}  // namespace spread::calibration
