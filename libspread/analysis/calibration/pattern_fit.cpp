#include "libspread/analysis/calibration/pattern_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "libspread/analysis/calibration/least_squares.hpp"

namespace spread::calibration {
namespace {

std::vector<double> normalised(std::vector<double> values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  if (sum > 0.0) {
    for (double& v : values) v /= sum;
  }
  return values;
}

}  // namespace

bool informative(double measured, double predicted, double largest_measured) {
  return measured > 0.0 || predicted > kVarianceFloor * largest_measured;
}

double VarianceModel::variance(double q) const {
  return floor_variance + counting * q + relative * q * q;
}

// v(q) = a + b q + c q² with a, b, c >= 0, by least squares of e_i² on (1, q_i, q_i²): the best of the
// non-negative solutions over the subsets of the three terms (an exact non-negative least squares for
// three unknowns). e_i² estimates v(q_i) with variance 2 v(q_i)² (χ²₁), so the regression is weighted
// by 1 / v(q_i)², iterated from an unweighted start: unweighted, the few full trays decide everything
// and the counting term, which rules the many sparse trays of the pattern's edges, comes out as noise.
// The floor is at least (kVarianceFloor × largest tray)²: a tray test's readings are not better than
// that, and a zero floor would give the empty trays infinite weight.
VarianceModel fit_variance_model(const std::vector<double>& q, const std::vector<double>& e, double largest) {
  const double minimum_floor = (kVarianceFloor * largest) * (kVarianceFloor * largest);
  // Empty trays with a prediction below the least floor carry no information about the noise.
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (informative(q[i] + e[i], q[i], largest)) used.push_back(i);
  }
  const auto rows = static_cast<Eigen::Index>(used.size());
  VarianceModel model;
  // Iterated to convergence this is the Gaussian maximum-likelihood estimate of (a, b, c): its score
  // equations are the weighted normal equations with weights 1 / v².
  for (int pass = 0; pass < 12; ++pass) {
    VarianceModel best;
    double best_cost = std::numeric_limits<double>::infinity();
    for (unsigned mask = 1; mask < 8; ++mask) {
      std::vector<int> terms;
      for (int t = 0; t < 3; ++t) {
        if (mask & (1u << t)) terms.push_back(t);
      }
      const auto m = static_cast<Eigen::Index>(terms.size());
      Eigen::MatrixXd a(rows, m);
      Eigen::VectorXd b(rows);
      for (Eigen::Index i = 0; i < rows; ++i) {
        const double qi = q[used[static_cast<std::size_t>(i)]], ei = e[used[static_cast<std::size_t>(i)]];
        const double row_weight = pass == 0 ? 1.0 : 1.0 / model.variance(qi);
        const double basis[3] = {1.0, qi, qi * qi};
        for (Eigen::Index t = 0; t < m; ++t) a(i, t) = row_weight * basis[terms[static_cast<std::size_t>(t)]];
        b[i] = row_weight * ei * ei;
      }
      const Eigen::VectorXd x = a.colPivHouseholderQr().solve(b);
      if (!x.allFinite() || (x.array() < 0.0).any()) continue;
      const double cost = (a * x - b).squaredNorm();
      if (cost < best_cost) {
        best_cost = cost;
        best = {};
        for (Eigen::Index t = 0; t < m; ++t) {
          const double c = x[t];
          switch (terms[static_cast<std::size_t>(t)]) {
            case 0: best.floor_variance = c; break;
            case 1: best.counting = c; break;
            default: best.relative = c; break;
          }
        }
      }
    }
    best.floor_variance = std::max(best.floor_variance, minimum_floor);
    model = best;
  }
  return model;
}

PatternFitResult fit_pattern(const PatternSetup& setup, const TrayTest& test, const PatternFitOptions& options) {
  const PatternModel model(setup, test.layout, options.model);
  PatternFitResult result;
  result.initial = options.use_start ? options.start : parameters_of(setup.material);
  check_parameters(result.initial);
  result.measured_fraction = normalised(test.layout_mass_kg);
  const auto n = static_cast<Eigen::Index>(result.measured_fraction.size());
  // Missing trays (no reading) are left out: residual weight 0, and the prediction is normalised over
  // the trays that were read, as the measurement is.
  std::vector<bool> present(result.measured_fraction.size(), true);
  for (std::size_t i = 0; i < present.size() && i < test.layout_missing.size(); ++i) present[i] = !test.layout_missing[i];
  const auto present_count = static_cast<Eigen::Index>(std::count(present.begin(), present.end(), true));
  result.fitted_mask = {options.fit_friction, options.fit_drag_diameter, options.fit_angle_offset,
                        options.fit_launch_speed, options.fit_elevation_offset};
  result.table_samples = !setup.table_samples.empty();
  if (result.table_samples && options.fit_friction) {
    throw std::invalid_argument("pattern fit: friction cannot be fitted on the table's DEM launch samples (the DEM's "
                                "launches do not depend on a friction the fit could change); fit the launch "
                                "speed factor and offsets instead");
  }
  // Index of each fitted parameter in the full parameter set.
  std::vector<std::size_t> free;
  for (std::size_t i = 0; i < kPatternParameterCount; ++i) {
    if (result.fitted_mask[i]) free.push_back(i);
  }
  const auto p_count = static_cast<Eigen::Index>(free.size());
  if (p_count == 0) throw std::invalid_argument("pattern fit: no parameter to fit");
  if (present_count <= p_count) throw std::invalid_argument("pattern fit: needs more trays than fitted parameters");
  const std::array<double, kPatternParameterCount> fixed = as_array(result.initial);
  auto full = [&](const Eigen::VectorXd& v) {
    std::array<double, kPatternParameterCount> a = fixed;
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
    for (std::size_t i = 0; i < out.size(); ++i) sum += present[i] ? out[i] : 0.0;
    if (!(sum > 1e-6)) return false;
    for (double& v : out) v /= sum;
    return true;
  };

  LeastSquaresProblem problem;
  problem.residual_count = static_cast<int>(n);
  // Steps well above the float32 rounding of the launch samples (~1e-7 relative) and well below the
  // parameters' natural scales (μ ~ 0.1, k ~ 0.1, δ ~ 0.05 rad, s ~ 0.05, ε ~ 0.05 rad).
  const std::array<double, kPatternParameterCount> step{2e-3, 2e-3, 1e-3, 2e-3, 1e-3};
  problem.difference_step.resize(p_count);
  Eigen::VectorXd start(p_count);
  for (Eigen::Index i = 0; i < p_count; ++i) {
    problem.difference_step[i] = step[free[static_cast<std::size_t>(i)]];
    start[i] = fixed[free[static_cast<std::size_t>(i)]];
  }
  // Residual i is sqrt(w_i) (y_i − q_i): w_i = 1 in the first round, 1 / v_i (the variance model) after.
  Eigen::VectorXd sqrt_weight = Eigen::VectorXd::Ones(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!present[static_cast<std::size_t>(i)]) sqrt_weight[i] = 0.0;
  }
  problem.evaluate = [&](const Eigen::VectorXd& v, Eigen::VectorXd& r) {
    std::vector<double> q;
    if (!predicted(full(v), q)) return false;
    for (Eigen::Index i = 0; i < n; ++i) {
      r[i] = sqrt_weight[i] *
             (result.measured_fraction[static_cast<std::size_t>(i)] - q[static_cast<std::size_t>(i)]);
    }
    return true;
  };
  if (!predicted(result.initial, result.initial_fraction)) {
    throw std::invalid_argument("pattern fit: the model cannot run the starting parameters (friction " +
                                std::to_string(result.initial.friction_wall) + ")");
  }

  LeastSquaresOptions ls;
  ls.max_iterations = options.max_iterations;
  LeastSquaresResult fit = levenberg_marquardt(problem, start, ls);
  const double initial_sum_of_squares = fit.initial_sum_of_squares;
  int iterations = fit.iterations, evaluations = fit.evaluations;
  double largest = 0.0;
  for (double y : result.measured_fraction) largest = std::max(largest, y);
  const int rounds = options.weighted ? std::max(options.reweight_rounds, 1) : 0;
  for (int round = 0; round < rounds; ++round) {
    std::vector<double> q;
    if (!predicted(full(fit.parameters), q)) break;
    std::vector<double> q_read, e_read;
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (!present[i]) continue;
      q_read.push_back(q[i]);
      e_read.push_back(result.measured_fraction[i] - q[i]);
    }
    result.variance_model = fit_variance_model(q_read, e_read, largest);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto iu = static_cast<std::size_t>(i);
      sqrt_weight[i] = present[iu] ? 1.0 / std::sqrt(result.variance_model.variance(q[iu])) : 0.0;
    }
    fit = levenberg_marquardt(problem, fit.parameters, ls);
    iterations += fit.iterations;
    evaluations += fit.evaluations;
  }
  result.weighted = rounds > 0;

  result.fitted = full(fit.parameters);
  predicted(result.fitted, result.fitted_fraction);
  // Trays empty in the measurement with a prediction below the least floor say nothing (their residual
  // is ~0 whatever the parameters): they do not count as degrees of freedom — with them s² would be
  // too small (the kernel's tails reach 6 sd beyond the last landing).
  result.informative_trays = 0;
  double unweighted_sum_of_squares = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!present[static_cast<std::size_t>(i)]) continue;
    const double y = result.measured_fraction[static_cast<std::size_t>(i)];
    const double q = result.fitted_fraction.empty() ? 0.0 : result.fitted_fraction[static_cast<std::size_t>(i)];
    if (informative(y, q, largest)) ++result.informative_trays;
    unweighted_sum_of_squares += (y - q) * (y - q);
  }
  const double dof = static_cast<double>(std::max<Eigen::Index>(result.informative_trays - p_count, 1));
  result.reduced_chi_square = fit.sum_of_squares / dof;

  std::array<double, kPatternParameterCount> error{}, robust{};
  error.fill(std::numeric_limits<double>::quiet_NaN());
  robust = error;
  if (fit.jacobian.rows() == n) {
    const Eigen::MatrixXd& j = fit.jacobian;  // already weighted
    const Eigen::MatrixXd jtj = j.transpose() * j;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(jtj);
    if (lu.isInvertible()) {
      const Eigen::MatrixXd bread = lu.inverse();
      // Model-based: s² (J̃ᵀJ̃)⁻¹, s² = χ² / (informative trays − parameters) (J̃ = W½ J).
      const Eigen::MatrixXd covariance = result.reduced_chi_square * bread;
      // Sandwich (heteroscedasticity-consistent, HC1): (J̃ᵀJ̃)⁻¹ (Σ r̃_i² J̃_iᵀ J̃_i) (J̃ᵀJ̃)⁻¹ · m / (m − p).
      Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(p_count, p_count);
      for (Eigen::Index i = 0; i < n; ++i) {
        meat += fit.residuals[i] * fit.residuals[i] * j.row(i).transpose() * j.row(i);
      }
      const Eigen::MatrixXd sandwich =
          bread * meat * bread * (static_cast<double>(result.informative_trays) / dof);
      for (Eigen::Index i = 0; i < p_count; ++i) {
        const std::size_t a = free[static_cast<std::size_t>(i)];
        error[a] = std::sqrt(std::max(covariance(i, i), 0.0));
        robust[a] = std::sqrt(std::max(sandwich(i, i), 0.0));
        for (Eigen::Index k = 0; k < p_count; ++k) {
          const double d = std::sqrt(covariance(i, i) * covariance(k, k));
          result.correlation[a][free[static_cast<std::size_t>(k)]] = covariance(i, k) / d;
        }
      }
    }
  }
  for (std::size_t a = 0; a < kPatternParameterCount; ++a) {
    if (!result.fitted_mask[a]) error[a] = robust[a] = 0.0;
  }
  result.standard_error = from_array(error);
  result.robust_standard_error = from_array(robust);
  const double count = static_cast<double>(present_count);
  result.residual_rms_fraction = std::sqrt(unweighted_sum_of_squares / count);
  result.residual_rms_kg = result.residual_rms_fraction * test.total_mass_kg();
  result.initial_residual_rms_fraction = std::sqrt(initial_sum_of_squares / count);
  result.residual_sd_fraction = std::sqrt(unweighted_sum_of_squares / dof);
  result.iterations = iterations;
  result.model_evaluations = evaluations;
  result.converged = fit.converged;
  result.stop_reason = fit.stop_reason;
  return result;
}

}  // namespace spread::calibration
