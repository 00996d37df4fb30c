#pragma once
// How much a tray test's passes differ from each other (docs/field-calibration.md, "Pass-to-pass
// scatter"): the measurement noise of the tray test, estimated from the test itself.
//
// Each pass p is normalised to fractions f_pi of its own mass (the passes may carry different amounts;
// the pattern fit compares shapes too). Per tray i read in every pass, the sample variance over the P
// passes s_i² = Σ_p (f_pi − f̄_i)² / (P − 1) estimates the variance of one pass's reading, and s_i² / P
// that of their mean — the value the fit compares with the model. Over the layout's n trays:
//     rms of the mean = sqrt( Σ_i s_i² / P / n ),
// which is what the fit's residual_rms_fraction (sqrt(Σ r_i² / n) over the same trays) comes to when the
// model is right and only the tray test's noise is left. E[s_i²] = σ_i² whatever the noise's form
// (relative, counting, floor), so no noise model is assumed. With P passes the estimate has about
// ν = (P − 1)·(trays holding mass) degrees of freedom, a relative sd of √(1/(2ν)) in the rms: ±11 % for
// 3 passes over the 20 trays of the example file (less sure when a few full trays dominate the sum).
#include "libspread/analysis/calibration/tray_csv.hpp"

namespace spread::calibration {

struct PassScatter {
  bool available = false;          // needs at least two passes and two trays read in all of them
  int passes = 0;
  int trays = 0;                   // trays read in every pass
  double rms_one_pass_fraction = 0.0;  // sqrt(Σ s_i² / n): one pass, fraction of a pass's mass per tray
  double rms_mean_fraction = 0.0;      // the same for the mean of the passes: ÷ sqrt(P)
  double rms_one_pass_g = 0.0;         // rms_one_pass_fraction × the mean mass of a pass, grams
};

PassScatter pass_scatter(const TrayTest& test);

// The fit residual against the scatter, above which the model does not describe the tray test: see
// pass_scatter.cpp for why this value.
inline constexpr double kResidualToScatterLimit = 3.0;

}  // namespace spread::calibration
