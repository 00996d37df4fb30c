#pragma once
// What a successful spread_predict() must deliver, and which statuses an entry point may return.
#include <cmath>
#include <cstddef>
#include <string>

#include "fuzz/fuzz_input.hpp"
#include "spread/spread.h"

namespace spread::fuzz {

// SPREAD_ERROR_INTERNAL is "a bug: please report" by the header's own words; anything outside the enum
// (SPREAD_ERROR_OUTSIDE_DOMAIN is the last code) is a broken status mapping.
inline void check_status(const char* harness, spread_status status, const char* call) {
  if (status == SPREAD_ERROR_INTERNAL || static_cast<int>(status) < 0 || static_cast<int>(status) > SPREAD_ERROR_OUTSIDE_DOMAIN) {
    fail(harness, std::string(call) + " returned " + spread_status_str(status));
  }
}

inline void check_prediction(const char* harness, const spread_prediction& p, const double* trays,
                             std::size_t tray_capacity) {
  const auto finite_at_least = [&](double value, double low, const char* what) {
    if (!std::isfinite(value) || value < low) fail(harness, std::string(what) + " = " + std::to_string(value));
  };
  finite_at_least(p.throw_width_m, 0.0, "throw_width_m");
  finite_at_least(p.working_width_to_and_fro_m, 0.0, "working_width_to_and_fro_m");
  finite_at_least(p.working_width_racetrack_m, 0.0, "working_width_racetrack_m");
  finite_at_least(p.bout_width_m, 0.0, "bout_width_m");
  if (p.bout_width_m > 0.0) {
    finite_at_least(p.cv_percent, 0.0, "cv_percent");
    finite_at_least(p.cv_racetrack_percent, 0.0, "cv_racetrack_percent");
  }
  finite_at_least(p.disc_height_m, 0.0, "disc_height_m");
  if (!(p.lost_mass_fraction >= 0.0 && p.lost_mass_fraction <= 1.0)) {
    fail(harness, "lost_mass_fraction = " + std::to_string(p.lost_mass_fraction));
  }
  if (p.tray_count < 0 || static_cast<std::size_t>(p.tray_count) > tray_capacity) {
    fail(harness, "tray_count " + std::to_string(p.tray_count) + " above the bound " + std::to_string(tray_capacity));
  }
  if (trays == nullptr) return;
  double sum = 0.0;
  for (int k = 0; k < p.tray_count; ++k) {
    finite_at_least(trays[k], 0.0, "transverse_mass_fraction[k]");
    sum += trays[k];
  }
  // The trays hold what was not lost (header: the sum over trays is 1 - lost_mass_fraction).
  if (std::abs(sum - (1.0 - p.lost_mass_fraction)) > 1e-6) {
    fail(harness, "tray sum " + std::to_string(sum) + " != 1 - lost " + std::to_string(1.0 - p.lost_mass_fraction));
  }
}

}  // namespace spread::fuzz
