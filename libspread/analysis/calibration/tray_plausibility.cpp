#include "libspread/analysis/calibration/tray_plausibility.hpp"

#include <cmath>
#include <cstdio>

#include "libspread/analysis/calibration/text_excerpt.hpp"

namespace spread::calibration {
namespace {

constexpr double kSquareMetresPerHectare = 10'000.0;

std::string text_of(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

}  // namespace

double heaviest_tray_mass_kg() { return kHeaviestRate_kg_ha * kLargestTrayArea_m2 / kSquareMetresPerHectare; }

std::string tray_mass_problem(double value, double kg_per_unit, const std::string& column) {
  const double mass_kg = value * kg_per_unit;
  if (std::isfinite(mass_kg) && mass_kg <= heaviest_tray_mass_kg()) return {};
  const std::string name = excerpt(column);
  if (!std::isfinite(mass_kg)) return name + text_of(": %.4g is not a tray's mass", value);
  const char* unit = kg_per_unit == 1.0 ? "kg" : "g";
  const double rate_t_ha = mass_kg / kLargestTrayArea_m2 * kSquareMetresPerHectare / 1000.0;
  std::string problem = name + ": " + text_of("%.4g ", value) + unit +
                        text_of(" in one tray is %.4g t/ha even on a %g m² tray", rate_t_ha, kLargestTrayArea_m2) +
                        text_of(", more than any spreader applies (%g t/ha)", kHeaviestRate_kg_ha / 1000.0);
  if (kg_per_unit == 1.0 && mass_kg / 1000.0 <= heaviest_tray_mass_kg()) {
    problem += text_of(": grams in a kilogram column? %.4g g is a tray's catch — name the column *_g", value);
  }
  return problem;
}

std::string bout_width_problem(const metrics::TrayLayout& trays, double bout_width_m) {
  const double reach_m = trays.tray_count * trays.tray_width_m;
  // Whole trays: a bout within half a tray of the row is the row (metrics::bout_tray_count rounds).
  if (!(bout_width_m > reach_m + 0.5 * trays.tray_width_m)) return {};
  return text_of("%g m is wider than the trays reach (%.2f m across the centre line): the CV would take the "
                 "ground beyond the last trays as empty and describe the missing trays, not the spread — lay "
                 "trays across the whole bout, or give a bout width up to %.2f m",
                 bout_width_m, reach_m, reach_m);
}

}  // namespace spread::calibration
