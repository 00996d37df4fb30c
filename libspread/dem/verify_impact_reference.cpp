// Reference for `spread verify impact`: the duration of one head-on contact of the damped model the
// engine simulates, from the 1-D overlap ODE solved to tight tolerance — an integration independent of
// the engine (no particles, walls, pair lists or time step; its own adaptive Dormand–Prince 5(4)).
//
// Non-dimensional overlap x = δ/δ0, time τ = t/t0, head-on approach at speed v:
//   Hertz (Eqs. 16–18):  M* δ̈ = −max(0, k δ^{3/2} + c_n δ^{1/4} δ̇),  k = 4/3 sqrt(R*) E*,
//                        c_n = γ sqrt(8 E* M* sqrt(R*)) = γ sqrt(6 k M*).
//     δ0 = (M* v²/k)^{2/5}, t0 = δ0/v  →  x'' = −max(0, x^{3/2} + γ sqrt(6) x^{1/4} x').
//   Linear (seed 001):   M* δ̈ = −max(0, k δ + 2ζ sqrt(M* k) δ̇),  t0 = sqrt(M*/k), δ0 = v t0
//                        →  x'' = −max(0, x + 2ζ x').
// x(0) = 0, x'(0) = 1. The contact ends as the simulation measures it: at the first time the clipped
// force is zero again — the overlap gone (elastic), or the damping term cancelling the spring while the
// bodies recede (damped; from then on they fly apart: the spring-to-damping ratio only falls).
#include <algorithm>
#include <array>
#include <cmath>

#include "libspread/core/dormand_prince.hpp"
#include "libspread/dem/verify.hpp"

namespace spread::dem {

namespace {
using State = std::array<double, 2>;  // x, x'

struct Law {
  bool hertz = true;
  double c = 0.0;  // non-dimensional damping coefficient
  // Force before clipping; only meaningful for x > 0.
  double unclipped(double x, double v) const {
    return hertz ? x * std::sqrt(x) + c * std::sqrt(std::sqrt(x)) * v : x + c * v;
  }
  State rhs(const State& y) const {
    if (y[0] <= 0.0) return {y[1], 0.0};
    return {y[1], -std::max(0.0, unclipped(y[0], y[1]))};
  }
  // True once the contact is over (after the start): no overlap, or a zero clipped force while receding.
  bool ended(const State& y) const { return y[0] <= 0.0 || (y[1] < 0.0 && unclipped(y[0], y[1]) <= 0.0); }
};

// One Dormand–Prince 5(4) step; err = max over components of |error| / (1 + |y|) (values are O(1)).
State dp_step(const Law& law, const State& y, double h, double& err) {
  State e;
  const State y5 = dormand_prince::step([&](const State& x) { return law.rhs(x); }, y, h, e);
  err = 0.0;
  for (std::size_t i = 0; i < 2; ++i) err = std::max(err, std::abs(e[i]) / (1.0 + std::max(std::abs(y[i]), std::abs(y5[i]))));
  return y5;
}
}  // namespace

ContactReference contact_reference(ContactModel model, double damping_ratio, double tol) {
  Law law;
  law.hertz = model == ContactModel::kHertzThornton;
  law.c = law.hertz ? damping_ratio * std::sqrt(6.0) : 2.0 * damping_ratio;
  State y = {0.0, 1.0};
  double t = 0.0, h = 1e-4;
  bool started = false;  // x > 0 after the first accepted step
  ContactReference out;
  for (int guard = 0; guard < 10'000'000; ++guard) {
    double err = 0.0;
    const State y_new = dp_step(law, y, h, err);
    if (err > tol) {
      h *= std::max(0.1, 0.9 * std::pow(tol / err, 0.2));
      continue;
    }
    if (started && law.ended(y_new)) {
      // Locate the end: bisection on the step length from the last accepted state (the state inside
      // one accepted step is as accurate as the step itself).
      double lo = 0.0, hi = h;
      State y_hi = y_new;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * std::max(1.0, t); ++it) {
        const double mid = 0.5 * (lo + hi);
        double e2 = 0.0;
        const State ym = dp_step(law, y, mid, e2);
        if (law.ended(ym)) { hi = mid; y_hi = ym; } else { lo = mid; }
      }
      out.duration = t + hi;
      out.restitution = -y_hi[1];
      return out;
    }
    y = y_new;
    t += h;
    started = started || y[0] > 0.0;
    h *= std::min(5.0, 0.9 * std::pow(tol / std::max(err, 1e-300), 0.2));
  }
  return out;  // not reached for damping ratios the restitution fits produce
}

}  // namespace spread::dem
