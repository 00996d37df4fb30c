#include "libspread/analysis/calibration/field_ranges.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>

namespace spread::calibration {
namespace {

std::string number(double value) {
  char text[48];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// A unit the value could have been typed in: value × to_range is in the range's unit.
struct Slip {
  const char* unit;   // the unit the value is likely in
  double to_range;    // its factor to the range's unit
};

// The slips a technician makes with each quantity: a tray measured in cm² or mm², a rate in g/ha or t/ha,
// a width in cm, a speed in m/h, a mass in g or t, a time in minutes.
std::string likely_unit(const FieldRange& range, double value) {
  static const struct {
    const char* unit;
    Slip slips[2];
  } kSlips[] = {{"m²", {{"cm²", 1e-4}, {"mm²", 1e-6}}},
                {"kg/ha", {{"g/ha", 1e-3}, {"t/ha", 1e3}}},
                {"m", {{"cm", 1e-2}, {"mm", 1e-3}}},
                {"km/h", {{"m/h", 1e-3}, {"m/s", 3.6}}},
                {"kg", {{"g", 1e-3}, {"t", 1e3}}},
                {"s", {{"min", 60.0}, {"ms", 1e-3}}}};
  for (const auto& entry : kSlips) {
    if (std::strcmp(entry.unit, range.unit) != 0) continue;
    for (const Slip& slip : entry.slips) {
      const double converted = value * slip.to_range;
      if (converted >= range.low && converted <= range.high) {
        return "; " + number(value) + " " + slip.unit + " is " + number(converted) + " " + range.unit + " — give it in " +
               range.unit;
      }
    }
  }
  return {};
}

}  // namespace

const FieldRange kTrayAreaRange{"a collecting tray's area", "m²", 0.01, 0.5};
const FieldRange kRateRange{"an application rate", "kg/ha", 1.0, 20'000.0};
const FieldRange kBoutWidthRange{"a bout width", "m", 1.0, 100.0};
const FieldRange kSpeedRange{"a forward speed", "km/h", 1.0, 50.0};
const FieldRange kCatchMassRange{"a catch test's mass", "kg", 0.1, 5000.0};
const FieldRange kCatchTimeRange{"a catch test's time", "s", 1.0, 3600.0};
const FieldRange kGateRange{"a gate opening", "(its scale)", 1e-3, 1e4};

std::string field_range_problem(const FieldRange& range, const std::string& option, double value) {
  if (value >= range.low && value <= range.high) return {};
  const std::string shown = std::isfinite(value) ? number(value) : std::string(std::isnan(value) ? "nan" : "inf");
  std::string problem = option + " " + shown + ": " + range.what + " is " + number(range.low) + "-" +
                        number(range.high) + " " + range.unit;
  if (std::isfinite(value) && value > 0.0) problem += likely_unit(range, value);
  return problem;
}

}  // namespace spread::calibration
