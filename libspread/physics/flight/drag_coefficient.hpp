#pragma once
// Haider & Levenspiel (1989) sphere drag, seed Eq. 32:
//   C_D = 24/Re (1 + 0.1806 Re^0.6459) + 0.4251 / (1 + 6880.95/Re).
// The flight RHS never needs C_D alone: drag enters Eq. 27 as C_D |v| v, and with Re = ρ D |v| / μ that is
// (C_D Re) μ/(ρ D) v. C_D Re is finite at Re = 0 (Stokes: 24), so the force is finite and linear in v as
// v → 0 — no division by |v| and no NaN at rest.
#include <cmath>

#include "libspread/physics/flight/flight_lanes.hpp"

namespace spread::flight::detail {

// C_D · Re of Eq. 32 multiplied through by Re; one power. Re >= 0.
//   C_D Re = 24 (1 + 0.1806 Re^0.6459) + 0.4251 Re² / (Re + 6880.95)
// Re^0.6459 as exp(0.6459 ln Re): same value to a few ulp, ~25 % cheaper than std::pow here (glibc,
// measured), and exp(−∞) = 0 keeps Re = 0 exact.
inline double drag_coefficient_times_reynolds(double reynolds) {
  return 24.0 + 24.0 * 0.1806 * std::exp(0.6459 * std::log(reynolds)) +
         0.4251 * reynolds * reynolds / (reynolds + 6880.95);
}

// The same with Re^0.6459 by power_06459 (plain arithmetic, a few ulp as above): T = double or
// FlightLanes (several flights at once, flight_lanes.hpp; the same bits in every lane). Used by the
// flights that can run in lanes — in lanes and one by one alike, so both give the same landing — where
// glibc's exp and log, scalar calls, were most of the cost. As a scalar call glibc is the cheaper one,
// so flights with lift or spin decay (never in lanes) keep drag_coefficient_times_reynolds.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // FlightLanes by value: see flight_lanes.hpp
template <class T>
[[gnu::always_inline]] inline T drag_coefficient_times_reynolds_arithmetic(T reynolds) {
  return 24.0 + 24.0 * 0.1806 * power_06459(reynolds) + 0.4251 * reynolds * reynolds / (reynolds + 6880.95);
}
#pragma GCC diagnostic pop

// Slope of the drag acceleration along v_rel in units of drag_rate_per_s (FlightParameters): with
// |a| = drag_rate f(Re) |v| and Re ∝ |v|, d|a|/d|v| = drag_rate (f + Re f'(Re)). Increasing in Re.
inline double drag_slope_factor(double reynolds) {
  constexpr double c = 6880.95;
  const double q = reynolds + c;
  return 24.0 + 24.0 * 0.1806 * (1.0 + 0.6459) * std::pow(reynolds, 0.6459) + 0.4251 * reynolds * reynolds / q +
         0.4251 * reynolds * reynolds * (reynolds + 2.0 * c) / (q * q);
}

}  // namespace spread::flight::detail
