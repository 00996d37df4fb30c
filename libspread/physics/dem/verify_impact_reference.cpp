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
#include "libspread/physics/dem/verify.hpp"

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
  // True once the contact is over: receding, and no overlap or a zero clipped force. (Receding excludes the
  // start, x = 0 with x' = 1: x' falls only while in contact and turns negative past full compression.)
  bool ended(const State& y) const { return y[1] < 0.0 && (y[0] <= 0.0 || unclipped(y[0], y[1]) <= 0.0); }
};

}  // namespace

ContactReference contact_reference(const ContactLaw& contact_law, double damping_ratio, double tol) {
  Law law;
  law.hertz = contact_law.normal == NormalModel::kHertz;
  law.c = law.hertz ? damping_ratio * std::sqrt(6.0) : 2.0 * damping_ratio;
  // Values are O(1): the error is taken relative to 1 + |y|.
  const dormand_prince::EventHit<2> end = dormand_prince::integrate_until(
      [&](const State& y) { return law.rhs(y); }, State{0.0, 1.0}, 1e-4, tol, 1.0,
      [&](const State& y) { return law.ended(y); });
  ContactReference out;
  if (end.reached) {  // always, for damping ratios the restitution fits produce
    out.duration = end.t;
    out.restitution = -end.y[1];
  }
  return out;
}

}  // namespace spread::dem
