#include "libspread/analysis/calibration/cv_interval.hpp"

#include <cmath>
#include <stdexcept>

namespace spread::calibration {
namespace {

// Regularised lower incomplete gamma P(a, x) by its series e^{-x} x^a / Γ(a+1) Σ x^n / ((a+1)…(a+n)),
// which converges for every x (slowly only far beyond the quantiles needed here).
double lower_gamma_regularised(double a, double x) {
  if (!(x > 0.0)) return 0.0;
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 10000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (term < sum * 1e-16) break;
  }
  return std::min(1.0, std::exp(-x + a * std::log(x) - std::lgamma(a)) * sum);
}

}  // namespace

double chi_square_quantile(double p, int dof) {
  if (!(p > 0.0 && p < 1.0) || dof < 1) {
    throw std::invalid_argument("chi_square_quantile: p must be in (0, 1) and dof >= 1");
  }
  const double k = dof;
  double lo = 0.0, hi = k + 20.0 * std::sqrt(2.0 * k) + 50.0;
  while (hi - lo > 1e-10 * hi) {
    const double mid = 0.5 * (lo + hi);
    (lower_gamma_regularised(0.5 * k, 0.5 * mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

CvInterval cv_interval(double cv, int trays, double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0)) throw std::invalid_argument("cv_interval: confidence must be in (0, 1)");
  if (trays < 2) throw std::invalid_argument("cv_interval: need at least 2 trays");
  if (!(cv >= 0.0) || !std::isfinite(cv)) throw std::invalid_argument("cv_interval: the CV must be finite and >= 0");
  const int nu = trays - 1;
  const double alpha = 1.0 - confidence;
  const double u_upper = chi_square_quantile(1.0 - 0.5 * alpha, nu);
  const double u_lower = chi_square_quantile(0.5 * alpha, nu);
  auto bound = [&](double u) {
    const double radicand = (u / (nu + 1.0) - 1.0) * cv * cv + u / nu;
    return radicand > 0.0 ? cv / std::sqrt(radicand) : std::numeric_limits<double>::infinity();
  };
  CvInterval interval;
  interval.low = bound(u_upper);
  interval.high = bound(u_lower);
  interval.confidence = confidence;
  interval.trays = trays;
  return interval;
}

}  // namespace spread::calibration
