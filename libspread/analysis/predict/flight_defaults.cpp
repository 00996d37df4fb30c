#include "libspread/analysis/predict/flight_defaults.hpp"

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
  // A step cap bounds the worst case of a prediction and of spread_trajectory by design (docs/c-api.md
  // "Worst-case time"): the explicit integrator's step is bounded by stability at about the drag
  // relaxation time τ = ρ d² / (18 μ) (Stokes), 3 ns for 1 µm dust, so such a flight would otherwise
  // run into the flight module's general cap of a million steps long before 60 s of flight. Granules of
  // a spreader (>= 0.5 mm) land in 5-73 steps; a flight stopped by the cap is counted as not landed.
  s.max_steps = kMaxFlightSteps;
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
