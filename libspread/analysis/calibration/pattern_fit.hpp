#pragma once
// Pattern calibration (docs/field-calibration.md, step 3): the material parameters (pattern_model.hpp)
// that make the predicted transverse distribution match a tray test, by least squares
// (Levenberg–Marquardt, least_squares.hpp).
//
// Residuals: measured minus predicted mass fraction per tray of the tray test's layout, both normalised
// to sum to 1 over the layout — the tray test measures the shape of the pattern; its absolute mass is
// the rate calibration's business (step 1).
// Uncertainty (docs/field-calibration.md, "Uncertainty"): tray noise is not uniform (relative on full
// trays, counting on sparse ones, a floor on empty ones), so after an unweighted fit the residuals give a
// variance model v(q) (VarianceModel) and the fit is redone with weights 1 / v(q_i). Standard errors are
// s² (J̃ᵀJ̃)⁻¹ of the weighted fit with s² = χ² / (informative trays − fitted parameters), plus a
// sandwich estimate; the correlation matrix says which parameters the test cannot tell apart. Measured
// coverage of ±2 SE on synthetic tray tests: about 90 % (tests/calibration/test_pattern_fit.cpp).
#include <array>
#include <string>
#include <vector>

#include "libspread/analysis/calibration/pattern_model.hpp"
#include "libspread/analysis/calibration/tray_csv.hpp"

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
  bool fit_launch_speed = false;       // s and ε: the corrections of a DEM row (pattern_model.hpp)
  bool fit_elevation_offset = false;
  int max_iterations = 30;
  // Weighted least squares (see VarianceModel): after an unweighted fit, `reweight_rounds` fits with
  // weights 1 / v(q_i) from the variance model of the previous fit's residuals. false: unweighted only.
  bool weighted = true;
  int reweight_rounds = 1;
};

// Variance of a tray's measured fraction as a function of its predicted fraction q:
//   v(q) = floor_variance + counting · q + relative · q²
// — an additive floor (scale error, stray granules, empty trays read as 0), a counting term (a tray
// catching N granules varies like a Poisson count) and a relative term (the stream varies from pass to
// pass by some per cent). Estimated from the residuals of the fit itself (fit_variance_model), so it
// needs no noise figures from the technician.
struct VarianceModel {
  double floor_variance = 0.0;  // fraction²
  double counting = 0.0;        // fraction
  double relative = 0.0;        // dimensionless (relative sd²)
  double variance(double q) const;
};

// Least floor of the variance model, as a fraction of the largest measured tray (an sd).
inline constexpr double kVarianceFloor = 1e-3;

// A tray counts (degrees of freedom, variance model) when it caught something or its prediction is
// above the least floor: an empty tray predicted emptier than that is the same whatever the parameters.
bool informative(double measured_fraction, double predicted_fraction, double largest_measured_fraction);

// Non-negative least squares of e_i² on (1, q_i, q_i²); the floor at least (kVarianceFloor · largest)².
VarianceModel fit_variance_model(const std::vector<double>& predicted, const std::vector<double>& residual,
                                 double largest_measured);

struct PatternFitResult {
  PatternParameters initial;
  PatternParameters fitted;
  PatternParameters standard_error;          // same units as the parameters (δ, ε in rad); 0 when fixed
  PatternParameters robust_standard_error;   // sandwich estimate (no variance model assumed)
  bool weighted = false;
  VarianceModel variance_model;              // of the last reweighting round
  double reduced_chi_square = 0.0;           // Σ w r² / (informative trays − fitted parameters)
  int informative_trays = 0;                 // see informative()
  bool table_samples = false;                // corrected the table's (DEM) launch samples, not the analytic model
  std::array<bool, kPatternParameterCount> fitted_mask{};  // order μ, k, δ, s, ε (PatternParameterIndex)
  std::array<std::array<double, kPatternParameterCount>, kPatternParameterCount> correlation{};  // 0 when fixed
  double residual_rms_fraction = 0.0;        // sqrt(Σ r² / n) of the mass fractions
  double residual_rms_kg = 0.0;              // the same in mass per tray (× the measured total)
  double initial_residual_rms_fraction = 0.0;
  double residual_sd_fraction = 0.0;         // sqrt(Σ r² / (informative trays − fitted parameters)), unweighted
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
// it, when no parameter is to be fitted, when friction is to be fitted on table (DEM) samples, or when the tray test has no more trays than fitted parameters.
PatternFitResult fit_pattern(const PatternSetup& setup, const TrayTest& test, const PatternFitOptions& options = {});

}  // namespace spread::calibration
