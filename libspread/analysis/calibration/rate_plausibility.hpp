#pragma once
// Warnings on a rate calibration whose arithmetic is right but whose inputs or result are not what a
// catch test gives (docs/field-calibration.md, step 1, "Warnings"): a gate setting far outside the
// caught openings (the metering line is extrapolated), a mass flow no spreader meters (grams typed as
// kilograms), two catches too close together to fix a line.
#include <optional>
#include <string>
#include <vector>

#include "libspread/analysis/calibration/rate_calibration.hpp"

namespace spread::calibration {

// The required opening may lie this factor beyond the caught openings (above the largest, below the
// smallest) before the metering line counts as extrapolated: see rate_plausibility.cpp.
inline constexpr double kGateExtrapolationFactor = 1.5;
// Largest mass flow of a centrifugal spreader's metering (both outlets), kg/s: see rate_plausibility.cpp.
inline constexpr double kLargestMassFlow_kg_s = 15.0;
// Two catches closer than this fraction of the larger opening do not fix a line: see rate_plausibility.cpp.
inline constexpr double kLeastCatchSeparation = 0.2;

std::vector<std::string> rate_warnings(const CatchTest& first, const std::optional<CatchTest>& second,
                                       const RateSetting& setting);

}  // namespace spread::calibration
