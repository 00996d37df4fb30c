#pragma once
// Locating the ground crossing inside the step that crossed it. Both integrators reduce it to a scalar
// root on the step fraction θ ∈ (0, 1]: g(θ) = z(θ) − ground with g(0) > 0 ≥ g(1).
//   Dormand–Prince: z(θ) is the 4th-order continuous extension (a quartic in θ) — the landing lies on
//     the interpolant, whose error is of the order of the step's local error.
//   RK4: z(θ) is the end of an RK4 step of length θh from the start of the step — the landing lies
//     exactly on an RK4 trajectory whose last step was shortened.
// Safeguarded Newton: a Newton step when it stays inside the bracket, bisection otherwise; the bracket
// always shrinks, so it terminates; typically 2–4 evaluations.
#include <cmath>

namespace spread::flight::detail {

// Stop when |z − ground| is below this (m): far below any measurement, far above rounding at z ~ 1 m.
inline constexpr double kGroundTolerance_m = 1e-12;

struct CrossingSample {
  double height_above_ground_m;  // g(θ)
  double slope_m;                // dg/dθ (exact or a close estimate); any value if unknown
};

// eval(θ) → CrossingSample. g0 = g(0) > 0, g1 = g(1) <= 0.
template <class Eval>
inline double find_crossing_fraction(Eval&& eval, double g0, double g1) {
  double lo = 0.0;
  double hi = 1.0;
  if (g1 >= -kGroundTolerance_m) return 1.0;
  // Start from the secant through the end points.
  double theta = g0 / (g0 - g1);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const CrossingSample s = eval(theta);
    if (std::abs(s.height_above_ground_m) <= kGroundTolerance_m) return theta;
    if (s.height_above_ground_m > 0.0) {
      lo = theta;
    } else {
      hi = theta;
    }
    if (hi - lo <= 1e-15) return hi;
    const double newton = theta - s.height_above_ground_m / s.slope_m;
    theta = (s.slope_m < 0.0 && newton > lo && newton < hi) ? newton : 0.5 * (lo + hi);
  }
  return hi;
}

}  // namespace spread::flight::detail
