#pragma once
// Input checks of fly_to_ground / fly_batch. Each throws std::invalid_argument naming the bad field.
#include "libspread/physics/flight/flight.hpp"

namespace spread::flight::detail {

// Inputs shared by every flight of a batch.
void validate_shared_inputs(double ground_z_m, const Air& air, EffectSet effects, const Settings& settings);
// Inputs of one flight; `index` >= 0 names the batch element in the message.
void validate_flight_inputs(const Granule& granule, const State& launch, double ground_z_m, long index);
// Scheme::kRk4 only: settings.dt_s within rk4_stable_step_bound_s() (call after the two above).
void validate_rk4_step(const Granule& granule, const State& launch, double ground_z_m, const Air& air,
                       EffectSet effects, const Settings& settings, long index);

}  // namespace spread::flight::detail
