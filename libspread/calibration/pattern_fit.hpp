#pragma once
// Pattern calibration (docs/field-calibration.md, step 3): the material parameters (pattern_model.hpp)
// that make the predicted transverse distribution match a tray test, by least squares
// (Levenberg–Marquardt, least_squares.hpp).
//
// Residuals: measured minus predicted mass fraction per tray of the tray test's layout, both normalised
// to sum to 1 over the layout — the tray test measures the shape of the pattern; its absolute mass is
// the rate calibration's business (step 1). Uncertainty: standard errors from s² (JᵀJ)⁻¹, which assume
// independent tray errors of equal variance; the correlation matrix says which parameters the test
// cannot tell apart.
#include <array>
#include <string>
#include <vector>

#include "libspread/calibration/pattern_model.hpp"
#include "libspread/calibration/tray_csv.hpp"

namespace spread::calibration {

struct PatternFitOptions {
  PatternModelOptions model;
  // Start of the search; default: the stored material (μ as stored, k = 1, δ = 0).
  bool use_start = false;
  PatternParameters start;
  // Which parameters are fitted; the others stay at their start value. One transverse profile cannot
  // always tell a friction change from a launch-angle offset (both turn the throw; see the correlation
  // in the result): fixing one of them gives the other a usable uncertainty.
  bool fit_friction = true;
  bool fit_drag_diameter = true;
  bool fit_angle_offset = true;
  int max_iterations = 30;
};

struct PatternFitResult {
  PatternParameters initial;
  PatternParameters fitted;
  PatternParameters standard_error;          // same units as the parameters (δ in rad); 0 when fixed
  std::array<bool, 3> fitted_mask{};         // order μ, k, δ
  std::array<std::array<double, 3>, 3> correlation{};  // order μ, k, δ; 0 for fixed parameters
  double residual_rms_fraction = 0.0;        // sqrt(Σ r² / n) of the mass fractions
  double residual_rms_kg = 0.0;              // the same in mass per tray (× the measured total)
  double initial_residual_rms_fraction = 0.0;
  double residual_sd_fraction = 0.0;         // s = sqrt(Σ r² / (n − fitted parameters))
  int iterations = 0;
  int model_evaluations = 0;
  bool converged = false;
  std::string stop_reason;
  // On the tray test's layout (fractions of the mass in the layout): for plots and reports.
  std::vector<double> measured_fraction;
  std::vector<double> initial_fraction;
  std::vector<double> fitted_fraction;
};

// Throws std::invalid_argument when the start is outside the parameter ranges or the model cannot run
// it, when no parameter is to be fitted, or when the tray test has no more trays than fitted parameters.
PatternFitResult fit_pattern(const PatternSetup& setup, const TrayTest& test, const PatternFitOptions& options = {});

}  // namespace spread::calibration
