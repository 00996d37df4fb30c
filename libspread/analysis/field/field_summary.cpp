// The field's numbers from its as-applied grid (field_summary.hpp).
#include "libspread/analysis/field/field_summary.hpp"

#include <algorithm>
#include <cmath>

namespace spread::field {

std::vector<std::uint8_t> inside_mask(const RateGrid& grid, const Ring& ring) {
  std::vector<std::uint8_t> mask(grid.mass_kg.size(), 0);
  std::vector<double> xs;
  for (int iy = 0; iy < grid.ny; ++iy) {
    const double y = grid.y0_m + (iy + 0.5) * grid.cell_m;
    xs.clear();
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const Point a = ring[i], b = ring[j];
      if ((a.y_m > y) != (b.y_m > y)) xs.push_back(a.x_m + (y - a.y_m) * (b.x_m - a.x_m) / (b.y_m - a.y_m));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      // Cells whose centre x0 + (ix + ½) c lies in [xs[k], xs[k + 1]).
      const long first = std::max(0L, static_cast<long>(std::ceil((xs[k] - grid.x0_m) / grid.cell_m - 0.5)));
      const long end = std::min(static_cast<long>(grid.nx),
                                static_cast<long>(std::ceil((xs[k + 1] - grid.x0_m) / grid.cell_m - 0.5)));
      for (long ix = first; ix < end; ++ix) mask[static_cast<std::size_t>(iy) * grid.nx + ix] = 1;
    }
  }
  return mask;
}

FieldSummary summarise(const AsApplied& run, const Boundary& boundary, double target_rate_kg_ha) {
  const RateGrid& g = run.grid;
  const std::vector<std::uint8_t> mask = inside_mask(g, boundary.ring);
  FieldSummary s;
  s.target_rate_kg_ha = target_rate_kg_ha;
  s.metered_kg = run.metered_kg;
  s.not_landed_kg = run.not_landed_kg;
  const double to_kg_ha = 1e4 / g.cell_area_m2();
  double sum = 0.0, beyond = g.off_grid_kg;
  for (std::size_t i = 0; i < g.mass_kg.size(); ++i) {
    const double m = g.mass_kg[i];
    if (!mask[i]) {
      beyond += m;
      continue;
    }
    ++s.cells_inside;
    sum += m;
    const double rate = m * to_kg_ha;
    if (rate < kUnderFraction * target_rate_kg_ha) {
      s.under_area_m2 += g.cell_area_m2();
    } else if (rate > kOverFraction * target_rate_kg_ha) {
      s.over_area_m2 += g.cell_area_m2();
    } else {
      s.within_area_m2 += g.cell_area_m2();
    }
  }
  const double n = static_cast<double>(s.cells_inside);
  s.applied_kg = sum;
  s.beyond_kg = beyond;
  s.beyond_fraction = run.metered_kg > 0.0 ? beyond / run.metered_kg : 0.0;
  s.field_area_m2 = n * g.cell_area_m2();
  if (s.cells_inside > 1) {
    s.mean_rate_kg_ha = sum * to_kg_ha / n;
    // Second pass about the mean: no cancellation between two large sums.
    double squares = 0.0;
    for (std::size_t i = 0; i < g.mass_kg.size(); ++i) {
      if (!mask[i]) continue;
      const double deviation = g.mass_kg[i] * to_kg_ha - s.mean_rate_kg_ha;
      squares += deviation * deviation;
    }
    s.cv = s.mean_rate_kg_ha > 0.0 ? std::sqrt(squares / (n - 1.0)) / s.mean_rate_kg_ha : 0.0;
  }
  return s;
}

}  // namespace spread::field
