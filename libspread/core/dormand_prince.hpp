#pragma once
// Dormand–Prince 5(4) (Dormand & Prince 1980; Hairer, Nørsett & Wanner, Solving ODEs I, Table II.5.2):
// the Butcher tableau, shared by the flight integrator (libspread/physics/flight/dormand_prince.hpp) and the
// tight-tolerance references of the DEM verification cases, and one generic step for the small
// autonomous systems those references solve (c_i are not needed: every system here is autonomous), with
// the adaptive driver that runs them to an event.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

namespace spread::dormand_prince {

inline constexpr double kA21 = 1.0 / 5.0;
inline constexpr double kA31 = 3.0 / 40.0, kA32 = 9.0 / 40.0;
inline constexpr double kA41 = 44.0 / 45.0, kA42 = -56.0 / 15.0, kA43 = 32.0 / 9.0;
inline constexpr double kA51 = 19372.0 / 6561.0, kA52 = -25360.0 / 2187.0, kA53 = 64448.0 / 6561.0,
                        kA54 = -212.0 / 729.0;
inline constexpr double kA61 = 9017.0 / 3168.0, kA62 = -355.0 / 33.0, kA63 = 46732.0 / 5247.0,
                        kA64 = 49.0 / 176.0, kA65 = -5103.0 / 18656.0;
// 5th-order weights (= row 7 of A: first same as last).
inline constexpr double kB1 = 35.0 / 384.0, kB3 = 500.0 / 1113.0, kB4 = 125.0 / 192.0,
                        kB5 = -2187.0 / 6784.0, kB6 = 11.0 / 84.0;
// Error weights b − b̂ (5th minus embedded 4th order).
inline constexpr double kE1 = 71.0 / 57600.0, kE3 = -71.0 / 16695.0, kE4 = 71.0 / 1920.0,
                        kE5 = -17253.0 / 339200.0, kE6 = 22.0 / 525.0, kE7 = -1.0 / 40.0;

// One step h of y' = f(y) from y: returns the 5th-order solution and writes each component's embedded
// error estimate (5th minus 4th order) into `error`; the caller weighs it into its own norm.
template <std::size_t N, class Rhs>
std::array<double, N> step(const Rhs& f, const std::array<double, N>& y, double h, std::array<double, N>& error) {
  using State = std::array<double, N>;
  const auto stage = [&](auto... terms) {  // y + h Σ a_j k_j over (a_j, k_j) pairs
    State r;
    for (std::size_t i = 0; i < N; ++i) r[i] = y[i] + h * (0.0 + ... + (terms.first * (*terms.second)[i]));
    return r;
  };
  const auto term = [](double a, const State& k) { return std::pair<double, const State*>(a, &k); };
  const State k1 = f(y);
  const State k2 = f(stage(term(kA21, k1)));
  const State k3 = f(stage(term(kA31, k1), term(kA32, k2)));
  const State k4 = f(stage(term(kA41, k1), term(kA42, k2), term(kA43, k3)));
  const State k5 = f(stage(term(kA51, k1), term(kA52, k2), term(kA53, k3), term(kA54, k4)));
  const State k6 = f(stage(term(kA61, k1), term(kA62, k2), term(kA63, k3), term(kA64, k4), term(kA65, k5)));
  const State y5 = stage(term(kB1, k1), term(kB3, k3), term(kB4, k4), term(kB5, k5), term(kB6, k6));
  const State k7 = f(y5);
  for (std::size_t i = 0; i < N; ++i)
    error[i] = h * (kE1 * k1[i] + kE3 * k3[i] + kE4 * k4[i] + kE5 * k5[i] + kE6 * k6[i] + kE7 * k7[i]);
  return y5;
}

// Where integrate_until stopped: the event's time and state, or reached = false if the step budget ran out.
template <std::size_t N>
struct EventHit {
  double t = 0.0;
  std::array<double, N> y{};
  bool reached = false;
};

// Integrates y' = f(y) from y0 at t = 0 until event(y) first holds, to the tolerance `tol` on
// err = max_i |e_i| / (scale_floor + max(|y_i|, |y5_i|)) (scale_floor sets where the error turns from
// relative to absolute), with the standard controller h ← h · clamp(0.9 (tol/err)^{1/5}, 0.1, 5)
// (Hairer, Nørsett & Wanner, Sect. II.4). The event is located by bisection on the length of the step
// that crosses it, from the last accepted state: the states inside one accepted step are as accurate as
// the step. For the tight-tolerance verification references, not for hot loops.
template <std::size_t N, class Rhs, class Event>
EventHit<N> integrate_until(const Rhs& f, const std::array<double, N>& y0, double first_step, double tol,
                            double scale_floor, const Event& event, int max_steps = 10'000'000) {
  using State = std::array<double, N>;
  const auto attempt = [&](const State& from, double h, double& err) {
    State e;
    const State y5 = step(f, from, h, e);
    err = 0.0;
    for (std::size_t i = 0; i < N; ++i)
      err = std::max(err, std::abs(e[i]) / (scale_floor + std::max(std::abs(from[i]), std::abs(y5[i]))));
    return y5;
  };
  EventHit<N> out;
  out.y = y0;
  double h = first_step;
  for (int guard = 0; guard < max_steps; ++guard) {
    double err = 0.0;
    const State y_new = attempt(out.y, h, err);
    if (err > tol) {
      h *= std::max(0.1, 0.9 * std::pow(tol / err, 0.2));
      continue;
    }
    if (event(y_new)) {
      double lo = 0.0, hi = h;
      State y_hi = y_new;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * std::max(1.0, out.t); ++it) {
        const double mid = 0.5 * (lo + hi);
        double unused = 0.0;
        const State ym = attempt(out.y, mid, unused);
        if (event(ym)) { hi = mid; y_hi = ym; } else { lo = mid; }
      }
      out.t += hi;
      out.y = y_hi;
      out.reached = true;
      return out;
    }
    out.y = y_new;
    out.t += h;
    h *= std::min(5.0, 0.9 * std::pow(tol / std::max(err, 1e-300), 0.2));
  }
  return out;
}

}  // namespace spread::dormand_prince
