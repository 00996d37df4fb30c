#include "libspread/analysis/calibration/least_squares.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

namespace spread::calibration {
namespace {

struct Evaluator {
  const LeastSquaresProblem& problem;
  int count = 0;
  bool operator()(const Eigen::VectorXd& p, Eigen::VectorXd& r) {
    ++count;
    r.resize(problem.residual_count);
    return problem.evaluate(p, r) && r.allFinite();
  }
};

// Central differences: error O(h²) instead of O(h), so the covariance is right to a few per cent even
// with the modest steps the model's smoothness allows. When one side is refused (the edge of the
// model's domain), falls back to the one-sided difference.
bool jacobian(Evaluator& eval, const Eigen::VectorXd& p, const Eigen::VectorXd& r0, Eigen::MatrixXd& j) {
  const auto n = static_cast<Eigen::Index>(r0.size());
  j.resize(n, p.size());
  Eigen::VectorXd plus, minus;
  for (Eigen::Index i = 0; i < p.size(); ++i) {
    const double h = eval.problem.difference_step[i];
    Eigen::VectorXd q = p;
    q[i] = p[i] + h;
    const bool have_plus = eval(q, plus);
    q[i] = p[i] - h;
    const bool have_minus = eval(q, minus);
    if (have_plus && have_minus) j.col(i) = (plus - minus) / (2.0 * h);
    else if (have_plus) j.col(i) = (plus - r0) / h;
    else if (have_minus) j.col(i) = (r0 - minus) / h;
    else return false;
  }
  return true;
}

}  // namespace

LeastSquaresResult levenberg_marquardt(const LeastSquaresProblem& problem, const Eigen::VectorXd& start,
                                       const LeastSquaresOptions& options) {
  const Eigen::Index p_count = start.size();
  if (p_count < 1 || problem.residual_count < p_count) {
    throw std::invalid_argument("least squares: need at least as many residuals (" +
                                std::to_string(problem.residual_count) + ") as parameters (" +
                                std::to_string(p_count) + ")");
  }
  if (problem.difference_step.size() != p_count || !(problem.difference_step.array() > 0.0).all()) {
    throw std::invalid_argument("least squares: one difference step > 0 per parameter");
  }
  Evaluator eval{problem};
  LeastSquaresResult result;
  Eigen::VectorXd p = start;
  Eigen::VectorXd r;
  if (!eval(p, r)) throw std::invalid_argument("least squares: the model refuses the starting parameters");
  double cost = r.squaredNorm();
  result.initial_sum_of_squares = cost;
  double damping = options.initial_damping;
  Eigen::MatrixXd j;
  result.stop_reason = "iteration limit";

  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    result.iterations = iteration;
    if (!jacobian(eval, p, r, j)) {
      result.stop_reason = "the model refuses every neighbour of the current parameters";
      break;
    }
    const Eigen::MatrixXd jtj = j.transpose() * j;
    const Eigen::VectorXd gradient = j.transpose() * r;
    bool accepted = false;
    bool small_step = false;
    // Raise the damping until a step lowers the cost (or the damping makes steps negligible).
    for (int attempt = 0; attempt < 12 && !accepted; ++attempt) {
      Eigen::MatrixXd a = jtj;
      for (Eigen::Index i = 0; i < p_count; ++i) a(i, i) += damping * std::max(jtj(i, i), 1e-12);
      const Eigen::VectorXd step = a.ldlt().solve(-gradient);
      small_step = (step.array().abs() < options.step_tolerance * problem.difference_step.array()).all();
      Eigen::VectorXd trial_r;
      const Eigen::VectorXd trial = p + step;
      if (step.allFinite() && eval(trial, trial_r) && trial_r.squaredNorm() < cost) {
        const double new_cost = trial_r.squaredNorm();
        const double relative_drop = (cost - new_cost) / std::max(cost, std::numeric_limits<double>::min());
        p = trial;
        r = trial_r;
        cost = new_cost;
        damping = std::max(damping / 3.0, 1e-12);
        accepted = true;
        if (small_step || relative_drop < options.cost_tolerance) {
          result.converged = true;
          result.stop_reason = small_step ? "step below tolerance" : "cost change below tolerance";
        }
      } else {
        damping *= 4.0;
        if (small_step) break;  // even tiny steps do not help: at the minimum to numerical precision
      }
    }
    if (!accepted) {
      result.converged = small_step;
      result.stop_reason = small_step ? "at the minimum (no smaller cost within the step tolerance)"
                                      : "no step lowers the cost";
      break;
    }
    if (result.converged) break;
  }

  result.parameters = p;
  result.residuals = r;
  result.sum_of_squares = cost;
  const auto dof = static_cast<double>(problem.residual_count - p_count);
  result.residual_variance = dof > 0.0 ? cost / dof : std::numeric_limits<double>::quiet_NaN();
  // Uncertainty from the Jacobian at the final parameters.
  if (jacobian(eval, p, r, j)) {
    result.jacobian = j;
    const Eigen::MatrixXd jtj = j.transpose() * j;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(jtj);
    if (lu.isInvertible()) {
      result.covariance = result.residual_variance * lu.inverse();
      result.standard_errors = result.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
    }
  }
  if (result.standard_errors.size() != p_count) {
    result.covariance = Eigen::MatrixXd::Constant(p_count, p_count, std::numeric_limits<double>::quiet_NaN());
    result.standard_errors = Eigen::VectorXd::Constant(p_count, std::numeric_limits<double>::quiet_NaN());
  }
  result.evaluations = eval.count;
  return result;
}

}  // namespace spread::calibration
