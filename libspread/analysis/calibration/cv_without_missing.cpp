#include "libspread/analysis/calibration/cv_without_missing.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace spread::calibration {

double cv_without_missing(const std::vector<double>& tray_mass_kg, const std::vector<bool>& missing,
                          const metrics::TrayLayout& trays, int bout_tray_count, metrics::Overlap overlap) {
  const auto count = static_cast<std::size_t>(trays.tray_count);
  if (tray_mass_kg.size() != count || missing.size() != count) {
    throw std::invalid_argument("cv_without_missing: masses and missing flags must have one entry per tray");
  }
  if (bout_tray_count == 1) return 0.0;
  const metrics::BoutTrays bout = metrics::bout_trays(trays, bout_tray_count);
  const double width_m = bout_tray_count * trays.tray_width_m;
  const auto grid = static_cast<std::size_t>(bout.grid_trays);
  // The overlap is linear in the pattern: overlapping the 0/1 flags counts the missing trays in each
  // bout tray.
  std::vector<double> flags(count, 0.0);
  for (std::size_t i = 0; i < count; ++i) flags[i] = missing[i] ? 1.0 : 0.0;
  std::vector<double> bout_kg(grid), bout_missing(grid);
  metrics::overlapped_profile(tray_mass_kg, trays, width_m, overlap, bout_kg);
  metrics::overlapped_profile(flags, trays, width_m, overlap, bout_missing);

  auto weight = [&](std::size_t j) { return bout.cut_edges && (j == 0 || j + 1 == grid) ? 0.5 : 1.0; };
  double weights = 0.0, total_kg = 0.0;
  for (std::size_t j = 0; j < grid; ++j) {
    if (bout_missing[j] > 0.0) continue;
    weights += weight(j);
    total_kg += weight(j) * bout_kg[j];
  }
  if (weights < 2.0 - 1e-9) return std::numeric_limits<double>::quiet_NaN();
  const double mean_kg = total_kg / weights;
  if (!(mean_kg > 0.0)) return std::numeric_limits<double>::infinity();
  double squares_kg2 = 0.0;
  for (std::size_t j = 0; j < grid; ++j) {
    if (bout_missing[j] > 0.0) continue;
    squares_kg2 += weight(j) * (bout_kg[j] - mean_kg) * (bout_kg[j] - mean_kg);
  }
  return std::sqrt(squares_kg2 / (weights - 1.0)) / mean_kg;
}

}  // namespace spread::calibration
