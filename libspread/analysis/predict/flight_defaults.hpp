#pragma once
// Integrator settings of a prediction. The default is adaptive Dormand–Prince 5(4) with tolerances chosen
// so that every landing is within 1 cm of a tight-tolerance reference (rel/abs 1e-10) for the bundled
// tables (tests/predict checks it; bench/bench_predict reports the measured maximum); looser than
// flight::Settings' general-purpose defaults because a prediction flies hundreds of granules in its
// time budget and a tray is 50 cm wide.
#include "libspread/physics/flight/flight.hpp"

namespace spread::predict {

// Accepted integrator steps after which a default flight gives up: about 1.4 ms for one flight
// (bench_capi BM_TrajectoryWorstCase).
inline constexpr int kMaxFlightSteps = 3072;
flight::Settings default_flight_settings();
// Tight reference for accuracy checks (slow).
flight::Settings reference_flight_settings();
// Plain fixed-step RK4 (Eqs. 44–48) at Δt, for comparisons.
flight::Settings fixed_step_rk4_settings(double dt_s);

}  // namespace spread::predict
