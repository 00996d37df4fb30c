// Seed 000 Eqs. 51–52 (after [45, 46]): average radius R̄ = Σ m̄_ij r_ij and radial width
// ξ = Σ m̄_ij |r_ij - R̄|, with m̄ the mass fraction of ground interval (i, j) and r its distance from the
// disc centre. Taking each landing as its own interval (the limit of small cells) avoids a grid choice:
// m̄_i = m_i / Σ m and r_i = |(x_i, y_i) - centre|. Eq. 52 prints r̄; it is Eq. 51's R̄.
#include <cmath>

#include "libspread/analysis/metrics/input_checks.hpp"
#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::metrics {
namespace {
// |(dx, dy)| as sqrt(dx² + dy²): landings are metres, far from where the squares over- or underflow, and
// std::hypot's care for those ranges made it most of this function's cost.
double distance_m(double dx_m, double dy_m) { return std::sqrt(dx_m * dx_m + dy_m * dy_m); }
}  // namespace

RadialStats radial_statistics(std::span<const double> x_m, std::span<const double> y_m,
                              std::span<const double> mass_kg, double centre_x_m, double centre_y_m) {
  detail::require_same_size(x_m.size(), y_m.size(), "radial_statistics", "x_m", "y_m");
  detail::require_same_size(x_m.size(), mass_kg.size(), "radial_statistics", "x_m", "mass_kg");
  double total_kg = 0.0;
  double moment_kg_m = 0.0;
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    if (std::isnan(x_m[i]) || std::isnan(y_m[i])) continue;  // not landed
    total_kg += mass_kg[i];
    moment_kg_m += mass_kg[i] * distance_m(x_m[i] - centre_x_m, y_m[i] - centre_y_m);
  }
  RadialStats stats;
  if (!(total_kg > 0.0)) return stats;  // no mass: {0, 0}
  stats.mean_radius_m = moment_kg_m / total_kg;
  double spread_kg_m = 0.0;
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    if (std::isnan(x_m[i]) || std::isnan(y_m[i])) continue;
    const double r_m = distance_m(x_m[i] - centre_x_m, y_m[i] - centre_y_m);
    spread_kg_m += mass_kg[i] * std::abs(r_m - stats.mean_radius_m);
  }
  stats.radial_width_m = spread_kg_m / total_kg;
  return stats;
}

}  // namespace spread::metrics
