#pragma once
// What a technician types beside a tray or catch test — a tray's area, a rate, a bout width, a forward
// speed, a caught mass and its time — within what a disc spreader in a field can be. A number beyond is
// a unit slip (cm² typed for m², g/ha for kg/ha) or a typing slip (1e300, sixty digits), never a setting:
// it is refused before any arithmetic, naming the range and, where one fits, the unit it would be right in.
#include <string>

namespace spread::calibration {

// A quantity's name as the message gives it, its unit and its plausible range (inclusive).
struct FieldRange {
  const char* what;  // "tray area"
  const char* unit;  // "m²"
  double low, high;
};

// Collecting trays: from 0.1 m × 0.1 m up to tray_plausibility.hpp's largest (0.5 m², twice ISO 5690's
// 0.25 m²).
extern const FieldRange kTrayAreaRange;
// Application rates: slug pellets at a few kg/ha up to tray_plausibility.hpp's heaviest (20 t/ha).
extern const FieldRange kRateRange;
// Bout widths: 1 m (a garden spreader) to 100 m (twice the widest disc spreader's 50 m).
extern const FieldRange kBoutWidthRange;
// Forward speeds: 1 km/h to 50 km/h (spreading is done at 6-30 km/h).
extern const FieldRange kSpeedRange;
// A catch test's mass: 0.1 kg (a few seconds of a small gate) to 5 t (a hopper).
extern const FieldRange kCatchMassRange;
// A catch test's time: 1 s to an hour.
extern const FieldRange kCatchTimeRange;
// A gate opening on the spreader's own scale (mm, %, scale marks): above 0, below 10 000.
extern const FieldRange kGateRange;

// "" when `value` lies within `range`; otherwise the refusal, e.g. "--tray-area 2500 m²: a collecting
// tray is 0.01-0.5 m²; 2500 cm² is 0.25 m² — give it in m²". `option` names the input ("--tray-area").
// NaN and infinities are refused as not a number of that quantity.
std::string field_range_problem(const FieldRange& range, const std::string& option, double value);

}  // namespace spread::calibration
