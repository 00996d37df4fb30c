#include "libspread/physics/dem/restitution.hpp"

#include <algorithm>
#include <cmath>

namespace spread::dem {

double hertz_damping_ratio(double restitution) {
  if (restitution >= 1.0) return 0.0;
  // h1..h10 of the Thornton–Cummins–Cleary fit (as in Kratos' DEMApplication), Horner form.
  static constexpr double h[10] = {-6.918798, -16.41105, 146.8049, -796.4559, 2928.711,
                                   -7206.864, 11494.29,  -11342.18, 6276.757, -1489.915};
  const double e = restitution;
  double poly = h[9];
  for (int k = 8; k >= 0; --k) poly = h[k] + e * poly;
  const double alpha = e * poly;
  const double onepe = 1.0 + e;
  return std::sqrt(1.0 / (1.0 - onepe * onepe * std::exp(alpha)) - 1.0);
}

namespace {
// Non-dimensional head-on impact: overlap x, x'' = -max(0, x^p + c x^q x'), x(0)=0, x'(0)=1.
// Hertz: p=3/2, q=1/4, with stiffness 1 the linearised critical damping is c = ratio*2*sqrt(1.5)
// because dF/dx = 1.5 x^{1/2}: 2 sqrt(1.5 x^{1/2}) = 2 sqrt(1.5) x^{1/4}. Linear: p=1, q=0, c=2 ratio.
// Returns the separation speed (restitution). RK4 with a step far below the contact time (~3).
double impact(double ratio, bool hertz) {
  const double c = hertz ? ratio * 2.0 * std::sqrt(1.5) : 2.0 * ratio;
  auto accel = [&](double x, double v) {
    if (x <= 0.0) return 0.0;
    const double el = hertz ? x * std::sqrt(x) : x;
    const double damp = hertz ? c * std::sqrt(std::sqrt(x)) * v : c * v;
    return -std::max(0.0, el + damp);
  };
  double x = 0.0, v = 1.0;
  const double h = 2e-4;
  for (int step = 0; step < 2'000'000; ++step) {
    const double k1x = v, k1v = accel(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = accel(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = accel(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = accel(x + h * k3x, v + h * k3v);
    x += h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    // Separated: overlap gone, or the clipped force is zero while receding (free flight from here).
    if (x <= 0.0 || (v < 0.0 && accel(x, v) == 0.0)) return -v;
  }
  return 0.0;
}
}  // namespace

double simulated_restitution_hertz(double ratio) { return impact(ratio, true); }
double simulated_restitution_linear(double ratio) { return impact(ratio, false); }

double linear_damping_ratio(double restitution) {
  if (restitution >= 1.0) return 0.0;
  // Restitution falls monotonically with ζ; bisection to 1e-10 on [0, 20].
  double lo = 0.0, hi = 20.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (simulated_restitution_linear(mid) > restitution) lo = mid; else hi = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace spread::dem
