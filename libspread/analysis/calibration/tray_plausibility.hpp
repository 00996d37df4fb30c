#pragma once
// What a tray test can physically be. The reader (tray_csv.hpp) takes any well-formed file; these are
// the limits beyond which its numbers cannot be a tray test of a disc spreader, only a unit mistake or
// a wrong file — refused with the likely mistake named instead of a CV of 102,523 % or "CV inf %".
#include <string>

#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::calibration {

// The heaviest application a disc spreader makes is a lime dressing of about 10 t/ha; 20 t/ha leaves a
// factor of two. A tray's mass in one pass is judged against it on the largest tray in use: ISO 5690 /
// EN 13739 practice is 0.5 m × 0.5 m (0.25 m²); 0.5 m² again leaves a factor of two. So a tray holds at
// most 20 000 kg/ha × 0.5 m² / 10 000 m²/ha = 1 kg in one pass. Grams written into a `_kg` column are a
// thousand times the truth (a 10 g tray reads 10 kg, 200 t/ha): far beyond, whatever the rate was.
inline constexpr double kHeaviestRate_kg_ha = 20'000.0;
inline constexpr double kLargestTrayArea_m2 = 0.5;
double heaviest_tray_mass_kg();  // kHeaviestRate_kg_ha × kLargestTrayArea_m2 / 10 000

// "" when `value` (one tray, one pass, as read from `column`, kg_per_unit 1 for kilograms or 1e-3 for
// grams) can be a tray's catch; otherwise why not, naming the rate it implies and, for a kilogram
// column, the likely grams.
std::string tray_mass_problem(double value, double kg_per_unit, const std::string& column);

// Disc spreaders work bouts of up to about 50 m and throw no farther than about 50 m to a side; 100 m
// from the centre line leaves a factor of two. A tray beyond is a position in centimetres or millimetres
// read as metres, or not a tray test. The analysis of a tray test costs time in the square of its tray
// count (a CV at every bout width, each over the whole row), so this limit also bounds the work:
// ±100 m of the narrowest trays below is 4,000 trays, under a second.
inline constexpr double kFarthestTray_m = 100.0;
// No collecting tray is narrower than 5 cm (0.5 m in ISO 5690 practice): a closer spacing is not a row
// of trays.
inline constexpr double kNarrowestTray_m = 0.05;

// "" when a bout of `bout_width_m` can be judged from this tray test; otherwise why not. A bout wider
// than the trays reach takes the unmeasured ground as empty, so its CV (933.8 % for 500 m on 6 m of
// trays) describes the missing trays, not the spreader.
std::string bout_width_problem(const metrics::TrayLayout& trays, double bout_width_m);

}  // namespace spread::calibration
