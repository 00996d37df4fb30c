// Throw width (docs/design.md §3): the lateral extent holding a fraction f of the mass (99 % by default),
// between the (1-f)/2 and (1+f)/2 quantiles of the cumulative tray mass, the mass spread uniformly
// within each tray (so the cumulative mass is piecewise linear in x).
#include <cmath>
#include <stdexcept>
#include <string>

#include "libspread/analysis/metrics/input_checks.hpp"
#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::metrics {
namespace {

// Distance (m) from the outer edge of the first tray in `order` to the point where the mass passed
// reaches tail_kg. Zero-mass trays never hold the quantile, so with tail_kg = 0 the answer is the
// outer edge of the first non-empty tray. `step` is +1 (from the left) or -1 (from the right).
double tail_depth_m(std::span<const double> tray_mass_kg, double tray_width_m, double tail_kg, int step) {
  const long count = static_cast<long>(tray_mass_kg.size());
  double passed_kg = 0.0;
  for (long n = 0; n < count; ++n) {
    const long k = step > 0 ? n : count - 1 - n;
    const double m_kg = tray_mass_kg[static_cast<std::size_t>(k)];
    if (m_kg > 0.0 && passed_kg + m_kg >= tail_kg) {
      const double fraction_in_tray = (tail_kg - passed_kg) / m_kg;
      return (static_cast<double>(n) + (fraction_in_tray > 0.0 ? fraction_in_tray : 0.0)) * tray_width_m;
    }
    if (m_kg > 0.0) passed_kg += m_kg;
  }
  return static_cast<double>(count) * tray_width_m;
}

}  // namespace

ThrowExtent throw_extent(std::span<const double> tray_mass_kg, const TrayLayout& trays, double mass_fraction) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "throw_width", "tray_mass_kg");
  if (!(mass_fraction > 0.0 && mass_fraction <= 1.0)) {
    throw std::invalid_argument("throw_width: mass_fraction must be in (0, 1], got " +
                                std::to_string(mass_fraction));
  }
  double total_kg = 0.0;
  for (double m_kg : tray_mass_kg) {
    if (m_kg > 0.0) total_kg += m_kg;  // negative tray masses are not mass; ignore them
  }
  if (!(total_kg > 0.0)) return {};
  const double tail_kg = 0.5 * (1.0 - mass_fraction) * total_kg;
  const double left_m = trays.left_edge_m() + tail_depth_m(tray_mass_kg, trays.tray_width_m, tail_kg, +1);
  const double right_m = -trays.left_edge_m() - tail_depth_m(tray_mass_kg, trays.tray_width_m, tail_kg, -1);
  if (!(right_m > left_m)) return {};
  return {left_m, right_m};
}

double throw_width(std::span<const double> tray_mass_kg, const TrayLayout& trays, double mass_fraction) {
  const ThrowExtent e = throw_extent(tray_mass_kg, trays, mass_fraction);
  return e.right_m - e.left_m;
}

}  // namespace spread::metrics
