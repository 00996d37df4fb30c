#include "libspread/analysis/calibration/rate_plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace spread::calibration {

// Why these limits:
// - kGateExtrapolationFactor 1.5: a metering gate's flow is linear in the opening only over part of
//   its travel (dead zone near closed, the hopper's outflow limit near full), and the line through one
//   catch assumes no dead zone at all. Within half the caught opening beyond the catches the error stays
//   of the order of the dead zone; far beyond (a setting of 3840 from a catch at 40) the number is
//   arithmetic, not a setting: catch again near the required opening.
// - kLargestMassFlow_kg_s 15: the largest twin-disc spreaders meter about 500 kg/min (8.3 kg/s) at
//   full gate; 15 kg/s leaves room for that and is still well below what a mass in grams entered as
//   kilograms gives (25 kg in 60 s entered as 25000: 417 kg/s, 52,083 kg/ha).
// - kLeastCatchSeparation 0.2: the two-point slope is (Q2 − Q1)/(g2 − g1). A catch weighed and timed to
//   1 % gives Q to about 1 %, so the slope's relative error is about √2 · 1 % · g / Δg: 7 % at
//   Δg = 0.2 g, 140 % for catches at 40 and 40.1.

std::vector<std::string> rate_warnings(const CatchTest& first, const std::optional<CatchTest>& second,
                                       const RateSetting& setting) {
  std::vector<std::string> warnings;
  char text[512];
  const double low = second ? std::min(first.gate_opening, second->gate_opening) : first.gate_opening;
  const double high = second ? std::max(first.gate_opening, second->gate_opening) : first.gate_opening;
  const double required = setting.required_gate_opening;
  if (required > kGateExtrapolationFactor * high || required < low / kGateExtrapolationFactor) {
    char caught[96];
    if (second) std::snprintf(caught, sizeof caught, "openings %.4g to %.4g", low, high);
    else std::snprintf(caught, sizeof caught, "opening %.4g", low);
    std::snprintf(text, sizeof text,
                  "the required gate opening %.4g is far outside the caught %s: the metering line is extrapolated "
                  "%.1f times beyond it — do a catch test near %.4g and calibrate again",
                  required, caught, required > high ? required / high : low / required, required);
    warnings.emplace_back(text);
  }
  const double flows[2] = {catch_mass_flow_kg_s(first), second ? catch_mass_flow_kg_s(*second) : 0.0};
  const double largest_flow = std::max(flows[0], flows[1]);
  if (largest_flow > kLargestMassFlow_kg_s || setting.current_mass_flow_kg_s > kLargestMassFlow_kg_s) {
    std::snprintf(text, sizeof text,
                  "a mass flow of %.4g kg/s (%.0f kg/ha at the current gate) is more than any spreader meters "
                  "(%.0f kg/s): is --mass in grams? it takes kilograms (%.4g kg, not %.4g)",
                  std::max(largest_flow, setting.current_mass_flow_kg_s), setting.current_rate_kg_ha,
                  kLargestMassFlow_kg_s, first.mass_kg / 1000.0, first.mass_kg);
    warnings.emplace_back(text);
  }
  if (second) {
    const double separation = std::abs(second->gate_opening - first.gate_opening);
    if (separation < kLeastCatchSeparation * high) {
      std::snprintf(text, sizeof text,
                    "the two catches are %.3g gate units apart (at %.4g and %.4g): too close to fix the metering "
                    "line (a 1 %% weighing error moves its slope by %.0f %%) — catch at openings at least %.0f %% "
                    "apart",
                    separation, first.gate_opening, second->gate_opening,
                    100.0 * std::sqrt(2.0) * 0.01 * high / separation, 100.0 * kLeastCatchSeparation);
      warnings.emplace_back(text);
    }
  }
  return warnings;
}

}  // namespace spread::calibration
