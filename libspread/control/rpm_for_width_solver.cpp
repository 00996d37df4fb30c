#include "libspread/control/rpm_for_width_solver.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace spread::firmware {

WidthCurve sample_width_curve(SpreadPredictor& predictor, std::string_view material, RpmRange range,
                              double rpm_step) {
  if (!(rpm_step > 0.0) || !std::isfinite(range.min_rpm) || !std::isfinite(range.max_rpm) ||
      !(range.max_rpm >= range.min_rpm)) {
    throw std::invalid_argument("sample_width_curve: need a finite rpm range and a step > 0 r/min");
  }
  WidthCurve curve;
  curve.material = std::string(material);
  const auto steps = static_cast<int>(std::ceil((range.max_rpm - range.min_rpm) / rpm_step - 1e-9));
  for (int i = 0; i <= steps; ++i) {
    const double rpm = std::min(range.min_rpm + rpm_step * i, range.max_rpm);
    SpreadPrediction p;
    // The bout width only changes the CV, not the effective width: any positive value does.
    const bool ok = predictor.predict(material, rpm, 1.0, p) == PredictionOutcome::kOk;
    curve.rpm.push_back(rpm);
    curve.width_m.push_back(ok ? p.first_band_width_m : std::numeric_limits<double>::quiet_NaN());
  }
  return curve;
}

RpmForWidthSolver::RpmForWidthSolver(RpmSolverSettings settings) : settings_(settings) {
  if (!(settings_.curve_rpm_step > 0.0)) {
    throw std::invalid_argument("RpmForWidthSolver: curve_rpm_step must be > 0 r/min");
  }
  if (settings_.max_bisections < 0) throw std::invalid_argument("RpmForWidthSolver: max_bisections must be >= 0");
  if (!(settings_.width_tolerance_m >= 0.0)) {
    throw std::invalid_argument("RpmForWidthSolver: width_tolerance_m must be >= 0 m");
  }
}

RpmSolution RpmForWidthSolver::solve(SpreadPredictor& predictor, const WidthCurve& curve,
                                     double width_setpoint_m) const {
  RpmSolution solution;
  const std::size_t n = curve.rpm.size();
  if (n == 0) {
    solution.prediction_failed = true;
    return solution;
  }
  // First sample reaching the set-point; NaN samples (failed predictions) never qualify.
  std::size_t first = n;
  std::size_t widest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = curve.width_m[i];
    if (!(w <= curve.width_m[widest]) && std::isfinite(w)) widest = i;
    if (first == n && w >= width_setpoint_m) first = i;
  }
  if (first == n) {
    // Too wide for this material and speed range: the widest speed, reached only within tolerance.
    solution.rpm = curve.rpm[widest];
    solution.effective_width_m = curve.width_m[widest];
    solution.reachable = width_setpoint_m - solution.effective_width_m <= settings_.width_tolerance_m;
    return solution;
  }
  if (first == 0 || !std::isfinite(curve.width_m[first - 1])) {
    // The slowest usable speed already throws at least as wide: reached only within tolerance.
    solution.rpm = curve.rpm[first];
    solution.effective_width_m = curve.width_m[first];
    solution.reachable = solution.effective_width_m - width_setpoint_m <= settings_.width_tolerance_m;
    return solution;
  }
  // Bracket (rpm[first-1], rpm[first]]: below the set-point at the left end, reaching it at the right.
  double lo = curve.rpm[first - 1];
  double hi = curve.rpm[first];
  double hi_width = curve.width_m[first];
  for (int b = 0; b < settings_.max_bisections; ++b) {
    const double mid = 0.5 * (lo + hi);
    SpreadPrediction p;
    ++solution.predictions;
    if (predictor.predict(curve.material, mid, width_setpoint_m, p) != PredictionOutcome::kOk ||
        !std::isfinite(p.first_band_width_m)) {
      solution.prediction_failed = true;
      break;  // keep the bracket found so far: its upper end is known to reach the set-point
    }
    if (p.first_band_width_m >= width_setpoint_m) {
      hi = mid;
      hi_width = p.first_band_width_m;
    } else {
      lo = mid;
    }
  }
  // The upper end is the slowest speed known to reach the set-point.
  solution.rpm = hi;
  solution.effective_width_m = hi_width;
  solution.reachable = true;
  return solution;
}

}  // namespace spread::firmware
