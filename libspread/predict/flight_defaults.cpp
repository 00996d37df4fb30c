#include "libspread/predict/flight_defaults.hpp"

namespace spread::predict {

flight::Settings default_flight_settings() {
  flight::Settings s;
  s.scheme = flight::Scheme::kDormandPrince45;
  s.dt_s = 0.02;        // first trial step; the controller adapts from here
  // The cheapest tolerance that keeps landings within the documented 1 cm of the tight reference:
  // 4.1 mm worst error, 12 % cheaper than 1e-4 (docs/accuracy-cost.md, flight study).
  s.rel_tol = 1e-3;
  s.abs_tol = 1e-3;     // m, m/s, rad/s
  s.max_time_s = 60.0;
  return s;
}

flight::Settings reference_flight_settings() {
  flight::Settings s;
  s.scheme = flight::Scheme::kDormandPrince45;
  s.dt_s = 1e-4;
  s.rel_tol = 1e-11;
  s.abs_tol = 1e-11;
  s.max_time_s = 60.0;
  s.max_steps = 10'000'000;
  return s;
}

flight::Settings fixed_step_rk4_settings(double dt_s) {
  flight::Settings s;
  s.scheme = flight::Scheme::kRk4;
  s.dt_s = dt_s;
  s.max_time_s = 60.0;
  s.max_steps = 10'000'000;
  return s;
}

}  // namespace spread::predict
