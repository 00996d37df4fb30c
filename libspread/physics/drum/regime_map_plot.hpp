#pragma once
// Regime map PNG (cairo, through libspread/analysis/plot's canvas and axes): one marker per run at
// (log10 Fr, dynamic angle of repose), coloured by the regime label, with the regime bands along the top.
#include <string>
#include <vector>

#include "libspread/physics/drum/measurements.hpp"

namespace spread::drum {

// Throws std::runtime_error naming the path when the PNG cannot be written.
void write_regime_map_png(const std::vector<RegimeEvidence>& runs, const std::string& path, const std::string& title);

}  // namespace spread::drum
