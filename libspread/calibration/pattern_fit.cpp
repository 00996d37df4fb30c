#include "libspread/calibration/pattern_fit.hpp"

#include <cmath>
#include <stdexcept>

#include "libspread/calibration/least_squares.hpp"

namespace spread::calibration {
namespace {

std::array<double, 3> as_array(const PatternParameters& p) {
  return {p.friction_wall, p.drag_diameter_factor, p.launch_angle_offset_rad};
}
PatternParameters from_array(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

std::vector<double> normalised(std::vector<double> values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  if (sum > 0.0) {
    for (double& v : values) v /= sum;
  }
  return values;
}

}  // namespace

PatternFitResult fit_pattern(const PatternSetup& setup, const TrayTest& test, const PatternFitOptions& options) {
  const PatternModel model(setup, test.layout, options.model);
  PatternFitResult result;
  result.initial = options.use_start ? options.start : parameters_of(setup.material);
  check_parameters(result.initial);
  result.measured_fraction = normalised(test.layout_mass_kg);
  const auto n = static_cast<Eigen::Index>(result.measured_fraction.size());
  result.fitted_mask = {options.fit_friction, options.fit_drag_diameter, options.fit_angle_offset};
  // Index of each fitted parameter in the full (μ, k, δ) triple.
  std::vector<std::size_t> free;
  for (std::size_t i = 0; i < 3; ++i) {
    if (result.fitted_mask[i]) free.push_back(i);
  }
  const auto p_count = static_cast<Eigen::Index>(free.size());
  if (p_count == 0) throw std::invalid_argument("pattern fit: no parameter to fit");
  if (n <= p_count) throw std::invalid_argument("pattern fit: needs more trays than fitted parameters");
  const std::array<double, 3> fixed = as_array(result.initial);
  auto full = [&](const Eigen::VectorXd& v) {
    std::array<double, 3> a = fixed;
    for (Eigen::Index i = 0; i < p_count; ++i) a[free[static_cast<std::size_t>(i)]] = v[i];
    return from_array(a);
  };

  // A layout that catches nothing of a trial pattern has no shape to compare: refused, like a
  // parameter outside its range, so the search backs off.
  auto predicted = [&](const PatternParameters& p, std::vector<double>& out) {
    try {
      out = model.tray_fractions(p);
    } catch (const std::invalid_argument&) {
      return false;
    }
    double sum = 0.0;
    for (double v : out) sum += v;
    if (!(sum > 1e-6)) return false;
    for (double& v : out) v /= sum;
    return true;
  };

  LeastSquaresProblem problem;
  problem.residual_count = static_cast<int>(n);
  // Steps well above the float32 rounding of the launch samples (~1e-7 relative) and well below the
  // parameters' natural scales (μ ~ 0.1, k ~ 0.1, δ ~ 0.05 rad).
  const std::array<double, 3> step{2e-3, 2e-3, 1e-3};
  problem.difference_step.resize(p_count);
  Eigen::VectorXd start(p_count);
  for (Eigen::Index i = 0; i < p_count; ++i) {
    problem.difference_step[i] = step[free[static_cast<std::size_t>(i)]];
    start[i] = fixed[free[static_cast<std::size_t>(i)]];
  }
  problem.evaluate = [&](const Eigen::VectorXd& v, Eigen::VectorXd& r) {
    std::vector<double> q;
    if (!predicted(full(v), q)) return false;
    for (Eigen::Index i = 0; i < n; ++i) {
      r[i] = result.measured_fraction[static_cast<std::size_t>(i)] - q[static_cast<std::size_t>(i)];
    }
    return true;
  };
  if (!predicted(result.initial, result.initial_fraction)) {
    throw std::invalid_argument("pattern fit: the model cannot run the starting parameters (friction " +
                                std::to_string(result.initial.friction_wall) + ")");
  }

  LeastSquaresOptions ls;
  ls.max_iterations = options.max_iterations;
  const LeastSquaresResult fit = levenberg_marquardt(problem, start, ls);

  result.fitted = full(fit.parameters);
  std::array<double, 3> error{0.0, 0.0, 0.0};
  for (Eigen::Index i = 0; i < p_count; ++i) {
    const std::size_t a = free[static_cast<std::size_t>(i)];
    error[a] = fit.standard_errors[i];
    for (Eigen::Index j = 0; j < p_count; ++j) {
      const double d = std::sqrt(fit.covariance(i, i) * fit.covariance(j, j));
      result.correlation[a][free[static_cast<std::size_t>(j)]] = fit.covariance(i, j) / d;
    }
  }
  result.standard_error = from_array(error);
  const double count = static_cast<double>(n);
  result.residual_rms_fraction = std::sqrt(fit.sum_of_squares / count);
  result.residual_rms_kg = result.residual_rms_fraction * test.total_mass_kg();
  result.initial_residual_rms_fraction = std::sqrt(fit.initial_sum_of_squares / count);
  result.residual_sd_fraction = std::sqrt(fit.residual_variance);
  result.iterations = fit.iterations;
  result.model_evaluations = fit.evaluations;
  result.converged = fit.converged;
  result.stop_reason = fit.stop_reason;
  predicted(result.fitted, result.fitted_fraction);
  return result;
}

}  // namespace spread::calibration
