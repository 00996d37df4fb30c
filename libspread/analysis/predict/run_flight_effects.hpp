#pragma once
// The flight effects a table run's launches are flown with, read the one way every reader of a table
// uses (the predictor, the calibration's pattern model): those the run recorded ("flight_effects" in its
// stats_json: DEM runs record what their own flights used); a run that records none — tables written
// before runs recorded them — flew every flight effect there was then, and keeps that meaning when a
// flight effect is added.
#include "libspread/io/tables/table_format.hpp"
#include "libspread/physics/flight/flight.hpp"

namespace spread::predict {

// The flight effects of a run that records none: all of them when runs began to record theirs.
inline constexpr flight::EffectSet kUnrecordedRunEffects = flight::kDrag | flight::kMagnus | flight::kSpinDecay |
                                                           flight::kWind;

// Throws std::invalid_argument naming the effect when the recorded list holds one flight does not know.
flight::EffectSet run_flight_effects(const tables::Run& run);

}  // namespace spread::predict
