#pragma once
// The application rate a tray test caught, and EN 13739-2's check of it against the rate set from the
// catch test (docs/field-calibration.md, "Report").
//
// Overlapped at bout width W, every bout holds one pass's mass M (racetrack: one pass per period of W;
// to-and-fro: two mirrored passes per period of 2W), so the mean over the bout's n = W / w trays is M / n
// per tray. A tray of catching area A (m²) then stands for
//     rate [kg/ha] = (M / n) / A · 10 000 = M · w / (W · A) · 10 000,
// and with A = w · d (d the tray's depth along the driving direction) this is M / (W · d), the mass of
// one pass spread over a strip W wide. EN 13739-2 accepts a tray test whose caught rate lies within
// 90–110 % of the rate the catch test set.
#include <cmath>
#include <limits>

namespace spread::calibration {

inline constexpr double kRateCheckLowestPercent = 90.0;
inline constexpr double kRateCheckHighestPercent = 110.0;

struct TrayRateCheck {
  double rate_kg_ha = 0.0;                                          // caught in the trays at the bout width
  double set_rate_kg_ha = std::numeric_limits<double>::quiet_NaN();  // NaN: not given, no check
  double caught_percent = std::numeric_limits<double>::quiet_NaN();  // rate / set rate, %
  bool checked() const { return !std::isnan(set_rate_kg_ha); }
  bool pass = false;                                                // within [90, 110] % (checked only)
};

// `mass_per_pass_kg` (M, the mean of the passes over all trays read), `bout_width_m` (W > 0, whole trays),
// `tray_width_m` (w > 0), `tray_area_m2` (A > 0), `set_rate_kg_ha` (> 0, or NaN for no check).
// Throws std::invalid_argument naming the quantity that is not finite or out of range.
TrayRateCheck tray_rate_check(double mass_per_pass_kg, double bout_width_m, double tray_width_m,
                              double tray_area_m2, double set_rate_kg_ha);

}  // namespace spread::calibration
