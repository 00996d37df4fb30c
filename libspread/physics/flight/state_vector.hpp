#pragma once
// Conversions between the public State (Eigen) and the integrators' flat state arrays.
#include "libspread/physics/flight/right_hand_side.hpp"

namespace spread::flight::detail {

template <EffectSet E>
inline StateVector<E> to_state_vector(const State& s) {
  StateVector<E> y{};
  for (int i = 0; i < 3; ++i) {
    y[static_cast<std::size_t>(i)] = s.position_m[i];
    y[static_cast<std::size_t>(i + 3)] = s.velocity_m_s[i];
    if constexpr (kIntegratesSpin<E>) y[static_cast<std::size_t>(i + 6)] = s.spin_rad_s[i];
  }
  return y;
}

template <EffectSet E>
inline State to_state(const StateVector<E>& y, const FlightParameters& p) {
  State s;
  for (int i = 0; i < 3; ++i) {
    s.position_m[i] = y[static_cast<std::size_t>(i)];
    s.velocity_m_s[i] = y[static_cast<std::size_t>(i + 3)];
    if constexpr (kIntegratesSpin<E>) {
      s.spin_rad_s[i] = y[static_cast<std::size_t>(i + 6)];
    } else {
      s.spin_rad_s[i] = p.constant_spin_rad_s[i];
    }
  }
  return s;
}

inline void notify(const StepObserver& observer, double time_s, const State& state) {
  observer.on_step(observer.context, time_s, state);
}

}  // namespace spread::flight::detail
