#include "libspread/analysis/plot/cv_table.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spread::plot {
namespace {

constexpr double kSameWidth_m = 1e-3;

// Index of the curve width nearest to `width_m`.
std::size_t nearest(std::span<const double> curve_widths_m, double width_m) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < curve_widths_m.size(); ++i) {
    if (std::abs(curve_widths_m[i] - width_m) < std::abs(curve_widths_m[best] - width_m)) best = i;
  }
  return best;
}

}  // namespace

std::vector<double> cv_table_widths_m(double throw_width_m, std::span<const double> curve_widths_m) {
  std::vector<double> widths;
  if (curve_widths_m.empty()) return widths;
  const double tray_m = curve_widths_m.size() > 1 ? curve_widths_m[1] - curve_widths_m[0] : curve_widths_m[0];
  std::vector<double> wanted;
  int standard_within = 0;
  for (double w : kStandardWidths_m) standard_within += w <= throw_width_m ? 1 : 0;
  if (standard_within >= 3) {
    wanted.assign(std::begin(kStandardWidths_m), std::end(kStandardWidths_m));
  } else {
    // The step rounded to whole trays keeps the widths evenly spaced on the tray grid.
    const double step_m = std::max(1.0, std::round(throw_width_m / 6.0 / tray_m)) * tray_m;
    for (int k = 1; k <= 5; ++k) wanted.push_back(k * step_m);
  }
  for (double w : wanted) {
    if (w > curve_widths_m.back() + 0.5 * tray_m) continue;
    const double picked = curve_widths_m[nearest(curve_widths_m, w)];
    if (widths.empty() || picked > widths.back() + kSameWidth_m) widths.push_back(picked);
  }
  return widths;
}

std::vector<double> with_bout_width_m(std::vector<double> widths_m, double bout_width_m,
                                      std::span<const double> curve_widths_m) {
  if (!(bout_width_m > 0.0) || curve_widths_m.empty()) return widths_m;
  const double on_curve = curve_widths_m[nearest(curve_widths_m, bout_width_m)];
  if (std::abs(on_curve - bout_width_m) > kSameWidth_m) return widths_m;
  for (double w : widths_m) {
    if (std::abs(w - on_curve) <= kSameWidth_m) return widths_m;
  }
  widths_m.insert(std::upper_bound(widths_m.begin(), widths_m.end(), on_curve), on_curve);
  return widths_m;
}

std::vector<CvTableRow> cv_table(std::span<const double> widths_m, std::span<const double> curve_widths_m,
                                 std::span<const double> cv_to_and_fro, std::span<const double> cv_racetrack) {
  if (cv_to_and_fro.size() != curve_widths_m.size() || cv_racetrack.size() != curve_widths_m.size()) {
    throw std::invalid_argument("cv_table: the CV curves do not have one value per curve width");
  }
  std::vector<CvTableRow> rows;
  if (curve_widths_m.empty()) return rows;
  for (double w : widths_m) {
    const std::size_t i = nearest(curve_widths_m, w);
    if (std::abs(curve_widths_m[i] - w) > kSameWidth_m) continue;
    rows.push_back({curve_widths_m[i], cv_to_and_fro[i], cv_racetrack[i]});
  }
  return rows;
}

}  // namespace spread::plot
