#pragma once
// Locating the ground crossing inside the step that crossed it. Both integrators reduce it to a scalar
// root on the step fraction θ ∈ (0, 1]: g(θ) = z(θ) − ground with g(0) > 0 ≥ g(1) (or g(0) = 0 at a launch
// from the ground going up, below).
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

// eval(θ) → CrossingSample. g0 = g(0) > 0, g1 = g(1) <= 0 — or g0 = 0 for the first step of a launch on
// the ground going up whose hop ends inside the step: then g > 0 just after θ = 0 (g'(0) = h v_z > 0), and
// the crossing is the later root, bracketed from the first θ = 2^−k found above the ground.
template <class Eval>
inline double find_crossing_fraction(Eval&& eval, double g0, double g1) {
  double lo = 0.0;
  double hi = 1.0;
  if (g1 >= -kGroundTolerance_m) return 1.0;
  double g_lo = g0;
  if (!(g0 > 0.0)) {
    lo = 0.5;
    g_lo = eval(lo).height_above_ground_m;
    for (int halving = 0; halving < 60 && !(g_lo > kGroundTolerance_m); ++halving) {
      lo *= 0.5;
      g_lo = eval(lo).height_above_ground_m;
    }
    if (!(g_lo > kGroundTolerance_m)) return lo;  // a hop too small to resolve: it lands where it started
  }
  // Start from the secant through the ends of the bracket.
  double theta = lo + (hi - lo) * g_lo / (g_lo - g1);
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
