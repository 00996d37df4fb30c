#pragma once
// The evaluator of each flight effect: Term<bit> for every flight row of the effect registry
// (libspread/core/effect_registry.hpp). flight_term_table.hpp fails the build for a flight row without its
// Term, derives the terms' parameters once per flight and adds their accelerations to the right-hand side
// (right_hand_side.hpp) of exactly the instantiations whose effects include the bit (docs/design.md §7: an
// effect that is off is not evaluated).
#include "libspread/physics/flight/flight.hpp"

namespace spread::flight::detail {

// One specialisation per flight row, below.
template <EffectSet Bit>
struct Term;

// Drag (seed Eq. 27), Magnus lift (Eq. 28), spin decay (Eqs. 34–36) and wind act through the relative air
// velocity u = v − wind and the spin, and share one |u|, one Re and one |ω| per evaluation: flight_rhs
// evaluates them together in its air block, from FlightParameters.
struct AirBlockTerm {
  static constexpr bool kInAirBlock = true;
};
template <>
struct Term<kDrag> : AirBlockTerm {};
template <>
struct Term<kMagnus> : AirBlockTerm {};
template <>
struct Term<kSpinDecay> : AirBlockTerm {};
template <>
struct Term<kWind> : AirBlockTerm {};

// Any other flight effect is a term of its own: an acceleration added to gravity's and the air block's.
//
//   template <>
//   struct Term<kNew> {
//     struct Parameters { ... };  // derived once per flight, so that the hot loop only multiplies
//     static Parameters derive(const Granule&, const State& launch, const Air&, const Settings&);
//     // Adds the term's acceleration (m/s²) at the state y = [x, y, z, vx, vy, vz, ...].
//     static void accelerate(const Parameters&, const double* y, double& ax, double& ay, double& az);
//     // The stiffest linearised rate |∂a/∂v| of the term (1/s) over a flight from `launch`, for RK4's
//     // stable step (rk4_stable_step_bound_s); 0 for a force that does not depend on the state.
//     static double rate_per_s(const Parameters&, const State& launch);
//   };
//
// A term missing any of these is no Term (the build fails, flight_term_table.hpp).

}  // namespace spread::flight::detail
