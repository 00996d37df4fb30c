// Levenberg–Marquardt against closed forms: a straight line is ordinary least squares, whose estimates
// and standard errors are known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "libspread/analysis/calibration/least_squares.hpp"
#include "libspread/analysis/calibration/normal_noise.hpp"

namespace cal = spread::calibration;

TEST(LeastSquares, StraightLineMatchesOrdinaryLeastSquares) {
  cal::NormalNoise noise(42);
  const int n = 20;
  Eigen::MatrixXd x(n, 2);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    x(i, 0) = 1.0;
    x(i, 1) = 0.5 * i;
    y[i] = 1.5 + 0.8 * x(i, 1) + 0.1 * noise.next();
  }
  // Closed form: β = (XᵀX)⁻¹ Xᵀy, cov = s² (XᵀX)⁻¹, s² = |y − Xβ|² / (n − 2).
  const Eigen::MatrixXd xtx_inv = (x.transpose() * x).inverse();
  const Eigen::VectorXd beta = xtx_inv * x.transpose() * y;
  const double s2 = (y - x * beta).squaredNorm() / (n - 2);

  cal::LeastSquaresProblem problem;
  problem.residual_count = n;
  problem.difference_step = Eigen::Vector2d(1e-4, 1e-4);
  problem.evaluate = [&](const Eigen::VectorXd& p, Eigen::VectorXd& r) {
    r = y - x * p;
    return true;
  };
  const cal::LeastSquaresResult fit = cal::levenberg_marquardt(problem, Eigen::Vector2d(0.0, 0.0));
  EXPECT_TRUE(fit.converged) << fit.stop_reason;
  EXPECT_NEAR(fit.parameters[0], beta[0], 1e-8);
  EXPECT_NEAR(fit.parameters[1], beta[1], 1e-8);
  EXPECT_NEAR(fit.standard_errors[0], std::sqrt(s2 * xtx_inv(0, 0)), 1e-8);
  EXPECT_NEAR(fit.standard_errors[1], std::sqrt(s2 * xtx_inv(1, 1)), 1e-8);
  EXPECT_NEAR(fit.residual_variance, s2, 1e-12);
}

TEST(LeastSquares, ExponentialDecayFromFarStart) {
  // y = 3 exp(−0.7 t) without noise, from a start 3× off: the damped steps get there.
  std::vector<double> t, y;
  for (int i = 0; i < 15; ++i) {
    t.push_back(0.3 * i);
    y.push_back(3.0 * std::exp(-0.7 * t.back()));
  }
  cal::LeastSquaresProblem problem;
  problem.residual_count = 15;
  problem.difference_step = Eigen::Vector2d(1e-6, 1e-6);
  problem.evaluate = [&](const Eigen::VectorXd& p, Eigen::VectorXd& r) {
    if (p[1] < 0.0) return false;  // the domain: decay only
    for (int i = 0; i < 15; ++i) r[i] = y[static_cast<std::size_t>(i)] - p[0] * std::exp(-p[1] * t[static_cast<std::size_t>(i)]);
    return true;
  };
  const cal::LeastSquaresResult fit = cal::levenberg_marquardt(problem, Eigen::Vector2d(1.0, 2.1));
  EXPECT_NEAR(fit.parameters[0], 3.0, 1e-6);
  EXPECT_NEAR(fit.parameters[1], 0.7, 1e-6);
  EXPECT_LT(fit.sum_of_squares, 1e-12);
}

TEST(LeastSquares, RefusedStartIsAnError) {
  cal::LeastSquaresProblem problem;
  problem.residual_count = 3;
  problem.difference_step = Eigen::VectorXd::Constant(1, 1e-3);
  problem.evaluate = [](const Eigen::VectorXd&, Eigen::VectorXd&) { return false; };
  EXPECT_THROW(cal::levenberg_marquardt(problem, Eigen::VectorXd::Zero(1)), std::invalid_argument);
}
