#pragma once
// Adaptive Dormand–Prince 5(4) (Dormand & Prince 1980; Hairer, Nørsett & Wanner, Solving ODEs I,
// Sect. II.4–II.6): 7 stages with FSAL (the last stage is the next step's first), 5th-order solution
// propagated, embedded 4th-order error estimate, standard step-size control
//   h_new = h · clamp(safety · err^(−1/5), min_factor, max_factor),  err = RMS(e_i / (atol + rtol·|y_i|)),
// no growth right after a rejection, and the 4th-order continuous extension (dense output) to locate the
// ground crossing inside the crossing step (ground_crossing.hpp).
#include <algorithm>
#include <cmath>

#include "libspread/core/dormand_prince.hpp"
#include "libspread/physics/flight/ground_crossing.hpp"
#include "libspread/physics/flight/state_vector.hpp"

namespace spread::flight::detail {

// Controller constants, tuned on typical granule flights (docs/physics-flight.md): the flights are
// smooth and non-stiff, so a large growth limit lets the first trial step (Settings::dt_s) grow to the
// natural step in one or two steps.
inline constexpr double kDpSafety = 0.9;
inline constexpr double kDpMinFactor = 0.2;
inline constexpr double kDpMaxFactor = 10.0;
// After the first accepted step the error estimate is the best guess of the natural step there is:
// let it grow up to this factor once, so a conservative first trial step (Settings::dt_s = 1 ms) costs
// one short step instead of three (measured: docs/physics-flight.md).
inline constexpr double kDpMaxFirstFactor = 1000.0;
inline constexpr double kDpMinStep_s = 1e-12;  // below this the controller has failed: stop, not landed

// Butcher tableau: libspread/core/dormand_prince.hpp (shared with the DEM verification references).
using namespace spread::dormand_prince;
// Dense output (Hairer's DOPRI5 continuous extension of order 4).
inline constexpr double kD1 = -12715105075.0 / 11282082432.0, kD3 = 87487479700.0 / 32700410799.0,
                        kD4 = -10690763975.0 / 1880347072.0, kD5 = 701980252875.0 / 199316789632.0,
                        kD6 = -1453857185.0 / 822651844.0, kD7 = 69997945.0 / 29380423.0;

// Dense output of one component over the step: u(θ) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5))).
struct DenseComponent {
  double r1, r2, r3, r4, r5;
  double value(double theta) const {
    return r1 + theta * (r2 + (1.0 - theta) * (r3 + theta * (r4 + (1.0 - theta) * r5)));
  }
  double derivative(double theta) const {  // du/dθ
    const double q = r3 + theta * (r4 + (1.0 - theta) * r5);
    const double dq = r4 + (1.0 - 2.0 * theta) * r5;
    const double r = r2 + (1.0 - theta) * q;
    const double dr = -q + (1.0 - theta) * dq;
    return r + theta * dr;
  }
};

template <EffectSet E>
struct DpStages {
  StateVector<E> k1, k2, k3, k4, k5, k6, k7;
};

template <EffectSet E>
inline DenseComponent dense_component(const DpStages<E>& k, const StateVector<E>& y0, const StateVector<E>& y1,
                                      double h, std::size_t i) {
  DenseComponent d;
  d.r1 = y0[i];
  d.r2 = y1[i] - y0[i];
  d.r3 = h * k.k1[i] - d.r2;
  d.r4 = d.r2 - h * k.k7[i] - d.r3;
  d.r5 = h * (kD1 * k.k1[i] + kD3 * k.k3[i] + kD4 * k.k4[i] + kD5 * k.k5[i] + kD6 * k.k6[i] + kD7 * k.k7[i]);
  return d;
}

// The step from y to y_new (length h, stages k) crossed the ground: the step fraction θ of the crossing on
// the dense output's z, and the state there (z set to the ground exactly) into y_land.
template <EffectSet E>
inline double locate_crossing(const DpStages<E>& k, const StateVector<E>& y, const StateVector<E>& y_new, double h,
                              double ground_z_m, StateVector<E>& y_land) {
  const DenseComponent z = dense_component<E>(k, y, y_new, h, 2);
  const auto eval = [&](double theta) { return CrossingSample{z.value(theta) - ground_z_m, z.derivative(theta)}; };
  const double theta = find_crossing_fraction(eval, y[2] - ground_z_m, y_new[2] - ground_z_m);
  for (std::size_t i = 0; i < kStateSize<E>; ++i) y_land[i] = dense_component<E>(k, y, y_new, h, i).value(theta);
  y_land[2] = ground_z_m;
  return theta;
}

// Step-size factor after an accepted step with error err (err <= 1), as the controller above.
inline double accepted_step_factor(double err, bool last_rejected, int steps) {
  const double factor = err > 0.0 ? kDpSafety * std::pow(err, -0.2) : kDpMaxFactor;
  const double max_factor = last_rejected ? 1.0 : (steps == 1 ? kDpMaxFirstFactor : kDpMaxFactor);
  return std::clamp(factor, kDpMinFactor, max_factor);
}
// ... and after a rejected one (err > 1 or NaN): shrink hard.
inline double rejected_step_factor(double err) {
  return std::isfinite(err) ? std::max(kDpMinFactor, kDpSafety * std::pow(err, -0.2)) : kDpMinFactor;
}

template <EffectSet E>
Landing fly_dormand_prince(const FlightParameters& p, const State& launch, double ground_z_m,
                           const Settings& settings, const StepObserver& observer) {
  constexpr std::size_t n = kStateSize<E>;
  Landing landing;
  StateVector<E> y = to_state_vector<E>(launch);
  StateVector<E> y_new;
  StateVector<E> stage;
  DpStages<E> k;
  flight_rhs<E>(p, y, k.k1);
  double t = 0.0;
  double h = settings.dt_s;
  bool last_rejected = false;
  const double rtol = settings.rel_tol;
  const double atol = settings.abs_tol;

  while (landing.steps < settings.max_steps && t < settings.max_time_s) {
    h = std::min(h, settings.max_time_s - t);
    if (h < kDpMinStep_s) break;
    for (std::size_t i = 0; i < n; ++i) stage[i] = y[i] + h * kA21 * k.k1[i];
    flight_rhs<E>(p, stage, k.k2);
    for (std::size_t i = 0; i < n; ++i) stage[i] = y[i] + h * (kA31 * k.k1[i] + kA32 * k.k2[i]);
    flight_rhs<E>(p, stage, k.k3);
    for (std::size_t i = 0; i < n; ++i) stage[i] = y[i] + h * (kA41 * k.k1[i] + kA42 * k.k2[i] + kA43 * k.k3[i]);
    flight_rhs<E>(p, stage, k.k4);
    for (std::size_t i = 0; i < n; ++i) {
      stage[i] = y[i] + h * (kA51 * k.k1[i] + kA52 * k.k2[i] + kA53 * k.k3[i] + kA54 * k.k4[i]);
    }
    flight_rhs<E>(p, stage, k.k5);
    for (std::size_t i = 0; i < n; ++i) {
      stage[i] = y[i] + h * (kA61 * k.k1[i] + kA62 * k.k2[i] + kA63 * k.k3[i] + kA64 * k.k4[i] + kA65 * k.k5[i]);
    }
    flight_rhs<E>(p, stage, k.k6);
    for (std::size_t i = 0; i < n; ++i) {
      y_new[i] = y[i] + h * (kB1 * k.k1[i] + kB3 * k.k3[i] + kB4 * k.k4[i] + kB5 * k.k5[i] + kB6 * k.k6[i]);
    }
    flight_rhs<E>(p, y_new, k.k7);

    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double e = h * (kE1 * k.k1[i] + kE3 * k.k3[i] + kE4 * k.k4[i] + kE5 * k.k5[i] + kE6 * k.k6[i] +
                            kE7 * k.k7[i]);
      const double scale = atol + rtol * std::max(std::abs(y[i]), std::abs(y_new[i]));
      const double r = e / scale;
      sum += r * r;
    }
    const double err = std::sqrt(sum / static_cast<double>(n));

    if (!(err <= 1.0)) {  // also catches NaN: shrink hard
      ++landing.rejected_steps;
      h *= rejected_step_factor(err);
      last_rejected = true;
      continue;
    }

    ++landing.steps;
    // From a launch on the ground (t = 0, going up: fly_unchecked lands the others at once) the hop may
    // end inside the first step.
    if ((y[2] > ground_z_m || t == 0.0) && y_new[2] <= ground_z_m) {
      StateVector<E> y_land;
      const double theta = locate_crossing<E>(k, y, y_new, h, ground_z_m, y_land);
      landing.state = to_state<E>(y_land, p);
      landing.flight_time_s = t + theta * h;
      landing.landed = true;
      if (observer.on_step != nullptr) notify(observer, landing.flight_time_s, landing.state);
      return landing;
    }
    t += h;
    y = y_new;
    k.k1 = k.k7;  // FSAL
    if (observer.on_step != nullptr) notify(observer, t, to_state<E>(y, p));

    h *= accepted_step_factor(err, last_rejected, landing.steps);
    last_rejected = false;
  }
  landing.state = to_state<E>(y, p);
  landing.flight_time_s = t;
  return landing;
}

}  // namespace spread::flight::detail
