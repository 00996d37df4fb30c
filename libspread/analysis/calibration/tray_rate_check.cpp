#include "libspread/analysis/calibration/tray_rate_check.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::calibration {
namespace {

void require_above_zero(double value, const char* name) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw std::invalid_argument(std::string(name) + " must be a number > 0, got " + std::to_string(value));
  }
}

}  // namespace

TrayRateCheck tray_rate_check(double mass_per_pass_kg, double bout_width_m, double tray_width_m,
                              double tray_area_m2, double set_rate_kg_ha) {
  if (!std::isfinite(mass_per_pass_kg) || mass_per_pass_kg < 0.0) {
    throw std::invalid_argument("the caught mass must be >= 0 kg, got " + std::to_string(mass_per_pass_kg));
  }
  require_above_zero(bout_width_m, "the bout width (m)");
  require_above_zero(tray_width_m, "the tray width (m)");
  require_above_zero(tray_area_m2, "--tray-area (m²)");
  if (!std::isnan(set_rate_kg_ha)) require_above_zero(set_rate_kg_ha, "--rate-kg-ha");
  constexpr double kM2PerHa = 10000.0;
  TrayRateCheck check;
  check.rate_kg_ha = mass_per_pass_kg * tray_width_m / (bout_width_m * tray_area_m2) * kM2PerHa;
  check.set_rate_kg_ha = set_rate_kg_ha;
  if (check.checked()) {
    check.caught_percent = 100.0 * check.rate_kg_ha / set_rate_kg_ha;
    check.pass = check.caught_percent >= kRateCheckLowestPercent && check.caught_percent <= kRateCheckHighestPercent;
  }
  return check;
}

}  // namespace spread::calibration
