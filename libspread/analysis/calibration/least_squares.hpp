#pragma once
// Levenberg–Marquardt for small nonlinear least-squares problems, min_p Σ r_i(p)², with a central
// finite-difference Jacobian (the residuals come from a simulation: no analytic derivatives), and the
// usual uncertainty at the minimum: covariance s² (JᵀJ)⁻¹ with s² = Σ r² / (n − p).
//
// Marquardt's damping is scaled by diag(JᵀJ), so parameters of different units (a friction coefficient,
// an angle in radians) are treated alike. A residual function may refuse a parameter vector (outside
// the model's domain, e.g. a friction too high for the granules to move): that trial step counts as a
// failed step and the damping grows.
#include <functional>
#include <string>

#include <Eigen/Core>

namespace spread::calibration {

struct LeastSquaresProblem {
  int residual_count = 0;
  // Fills `residuals` (already sized residual_count) at `parameters`; returns false when the parameters
  // are outside the model's domain.
  std::function<bool(const Eigen::VectorXd& parameters, Eigen::VectorXd& residuals)> evaluate;
  // Finite-difference step per parameter (in the parameter's unit). Larger than the model's numerical
  // noise, smaller than the scale on which it bends.
  Eigen::VectorXd difference_step;
};

struct LeastSquaresOptions {
  int max_iterations = 40;
  double initial_damping = 1e-3;
  // Stop when a step changes every parameter by less than this fraction of its difference step, or the
  // sum of squares by less than this relative amount.
  double step_tolerance = 1e-3;
  double cost_tolerance = 1e-10;
};

struct LeastSquaresResult {
  Eigen::VectorXd parameters;
  Eigen::VectorXd standard_errors;   // sqrt(diag(covariance)); NaN when JᵀJ is singular
  Eigen::MatrixXd covariance;        // s² (JᵀJ)⁻¹ at the minimum
  Eigen::VectorXd residuals;         // at the minimum
  Eigen::MatrixXd jacobian;          // ∂r/∂p at the minimum (empty when the model refused every neighbour)
  double sum_of_squares = 0.0;
  double initial_sum_of_squares = 0.0;
  double residual_variance = 0.0;    // s² = Σ r² / (n − p)
  int iterations = 0;
  int evaluations = 0;
  bool converged = false;
  std::string stop_reason;
};

// Throws std::invalid_argument when the start is refused by the model, or the problem is
// ill-posed (fewer residuals than parameters, step sizes not > 0).
LeastSquaresResult levenberg_marquardt(const LeastSquaresProblem& problem, const Eigen::VectorXd& start,
                                       const LeastSquaresOptions& options = {});

}  // namespace spread::calibration
