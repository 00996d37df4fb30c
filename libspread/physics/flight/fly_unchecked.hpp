#pragma once
// fly_to_ground without input validation, for callers that validated already (fly_batch).
#include "libspread/physics/flight/flight.hpp"

namespace spread::flight::detail {

// The effects that act on this launch: `effects` within kAllEffects, less Magnus and spin decay for a
// launch without spin.
EffectSet effects_that_act(EffectSet effects, const State& launch);

Landing fly_unchecked(const Granule& granule, const State& launch, double ground_z_m, const Air& air,
                      EffectSet effects, const Settings& settings, const StepObserver& observer);

}  // namespace spread::flight::detail
