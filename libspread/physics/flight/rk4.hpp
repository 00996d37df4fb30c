#pragma once
// Classical fixed-step Runge–Kutta 4, seed Eqs. 44–48, applied to the whole flight state (position,
// velocity and — with spin decay — spin), ending in a shortened last step that lands exactly on the
// ground (ground_crossing.hpp).
#include <algorithm>

#include "libspread/physics/flight/ground_crossing.hpp"
#include "libspread/physics/flight/state_vector.hpp"

namespace spread::flight::detail {

// One RK4 step of length h from y (whose derivative k1 = f(y) is given): Eqs. 44–48.
template <EffectSet E>
inline void rk4_step(const FlightParameters& p, const StateVector<E>& y, const StateVector<E>& k1, double h,
                     StateVector<E>& y_out) {
  constexpr std::size_t n = kStateSize<E>;
  StateVector<E> k2;
  StateVector<E> k3;
  StateVector<E> k4;
  StateVector<E> stage;
  const double half = 0.5 * h;
  for (std::size_t i = 0; i < n; ++i) stage[i] = y[i] + half * k1[i];
  flight_rhs<E>(p, stage, k2);
  for (std::size_t i = 0; i < n; ++i) stage[i] = y[i] + half * k2[i];
  flight_rhs<E>(p, stage, k3);
  for (std::size_t i = 0; i < n; ++i) stage[i] = y[i] + h * k3[i];
  flight_rhs<E>(p, stage, k4);
  const double sixth = h / 6.0;
  for (std::size_t i = 0; i < n; ++i) y_out[i] = y[i] + sixth * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
}

template <EffectSet E>
Landing fly_rk4(const FlightParameters& p, const State& launch, double ground_z_m, const Settings& settings,
                const StepObserver& observer) {
  Landing landing;
  StateVector<E> y = to_state_vector<E>(launch);
  StateVector<E> k1;
  StateVector<E> y_next;
  double t = 0.0;
  const double dt = settings.dt_s;
  while (landing.steps < settings.max_steps && t < settings.max_time_s) {
    // The last step before max_time is shortened so the flight stops exactly at max_time.
    const double h = std::min(dt, settings.max_time_s - t);
    flight_rhs<E>(p, y, k1);
    rk4_step<E>(p, y, k1, h, y_next);
    ++landing.steps;
    if ((y[2] > ground_z_m || t == 0.0) && y_next[2] <= ground_z_m) {  // t = 0: as fly_dormand_prince
      // Shortened final step: find θ with z(RK4 step of θh) = ground. dz/dθ ≈ h v_z at the end point.
      StateVector<E> y_partial = y_next;
      const auto eval = [&](double theta) {
        rk4_step<E>(p, y, k1, theta * h, y_partial);
        return CrossingSample{y_partial[2] - ground_z_m, h * y_partial[5]};
      };
      const double theta = find_crossing_fraction(eval, y[2] - ground_z_m, y_next[2] - ground_z_m);
      if (theta == 1.0) {
        y_partial = y_next;
      } else {
        rk4_step<E>(p, y, k1, theta * h, y_partial);
      }
      y_partial[2] = ground_z_m;
      landing.state = to_state<E>(y_partial, p);
      landing.flight_time_s = t + theta * h;
      landing.landed = true;
      if (observer.on_step != nullptr) notify(observer, landing.flight_time_s, landing.state);
      return landing;
    }
    y = y_next;
    t += h;
    if (observer.on_step != nullptr) notify(observer, t, to_state<E>(y, p));
  }
  landing.state = to_state<E>(y, p);
  landing.flight_time_s = t;
  return landing;
}

}  // namespace spread::flight::detail
