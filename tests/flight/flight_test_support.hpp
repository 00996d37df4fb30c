#pragma once
// Shared launch set-ups of the flight tests.
#include "libspread/physics/flight/flight.hpp"

namespace spread::flight::test {

// A typical fertiliser granule thrown by a disc (3.2 mm, 1500 kg/m³, ~30 m/s, 0.8 m high).
inline Granule typical_granule() { return Granule{3.2e-3, 1500.0}; }

inline State typical_launch() {
  State s;
  s.position_m = Vec3(0.6, 0.1, 0.8);
  s.velocity_m_s = Vec3(25.0, 15.0, 3.0);
  s.spin_rad_s = Vec3(0.0, 0.0, 300.0);
  return s;
}

inline constexpr EffectSet kDiscEffects = kDrag | kMagnus | kSpinDecay;

inline Settings tight_dormand_prince() {
  Settings s;
  s.scheme = Scheme::kDormandPrince45;
  s.rel_tol = 1e-12;
  s.abs_tol = 1e-12;
  s.dt_s = 1e-4;
  return s;
}

inline Settings rk4(double dt_s) {
  Settings s;
  s.scheme = Scheme::kRk4;
  s.dt_s = dt_s;
  return s;
}

inline double horizontal_distance_m(const State& a, const State& b) {
  return (a.position_m - b.position_m).head<2>().norm();
}

}  // namespace spread::flight::test
