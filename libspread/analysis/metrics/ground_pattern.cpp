// Ground pattern of the whole machine (docs/design.md §3): mass per grid cell of both discs' landings.
// The left disc's samples are placed at x - spacing/2, the right disc's are their mirror image, so
// the grid is made symmetric about x = 0 (a twin-disc pattern is then symmetric cell for cell) and
// aligned to multiples of the cell size, with a one-cell margin round the landings.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "libspread/analysis/metrics/input_checks.hpp"
#include "libspread/analysis/metrics/machine_frame.hpp"
#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::metrics {

GroundPattern ground_pattern(std::span<const double> x_m, std::span<const double> y_m,
                             std::span<const double> mass_kg, const MachineLayout& machine, double cell_m) {
  detail::require_same_size(x_m.size(), y_m.size(), "ground_pattern", "x_m", "y_m");
  detail::require_same_size(x_m.size(), mass_kg.size(), "ground_pattern", "x_m", "mass_kg");
  detail::require_valid_machine(machine, "ground_pattern");
  if (!(std::isfinite(cell_m) && cell_m > 0.0)) {
    throw std::invalid_argument("ground_pattern: cell_m must be finite and > 0, got " + std::to_string(cell_m));
  }

  // Extent of the finite landings in the machine frame.
  double max_abs_x_m = 0.0;
  double min_y_m = std::numeric_limits<double>::infinity();
  double max_y_m = -std::numeric_limits<double>::infinity();
  bool any = false;
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    if (!(std::isfinite(x_m[i]) && std::isfinite(y_m[i]))) continue;
    const detail::MachineLandings landings = detail::to_machine_frame(x_m[i], machine);
    for (int d = 0; d < landings.count; ++d) max_abs_x_m = std::max(max_abs_x_m, std::abs(landings.x_m[d]));
    min_y_m = std::min(min_y_m, y_m[i]);
    max_y_m = std::max(max_y_m, y_m[i]);
    any = true;
  }
  GroundPattern pattern;
  pattern.cell_m = cell_m;
  if (!any) return pattern;

  const double half_cells_x = std::floor(max_abs_x_m / cell_m) + 2.0;  // cell holding the landing + margin
  const double first_cell_y = std::floor(min_y_m / cell_m) - 1.0;
  const double last_cell_y = std::floor(max_y_m / cell_m) + 1.0;
  const double cells = 2.0 * half_cells_x * (last_cell_y - first_cell_y + 1.0);
  if (cells > 16e6) {
    throw std::invalid_argument("ground_pattern: the landings span " + std::to_string(2.0 * max_abs_x_m) + " m × " +
                                std::to_string(max_y_m - min_y_m) + " m, more than 16 million cells of " +
                                std::to_string(cell_m) + " m");
  }
  pattern.nx = static_cast<int>(2.0 * half_cells_x);
  pattern.ny = static_cast<int>(last_cell_y - first_cell_y + 1.0);
  pattern.x0_m = -half_cells_x * cell_m;
  pattern.y0_m = first_cell_y * cell_m;
  pattern.mass_kg.assign(static_cast<std::size_t>(pattern.nx) * static_cast<std::size_t>(pattern.ny), 0.0);

  for (std::size_t i = 0; i < x_m.size(); ++i) {
    if (!(std::isfinite(x_m[i]) && std::isfinite(y_m[i]))) continue;
    const long iy = std::clamp(static_cast<long>(std::floor((y_m[i] - pattern.y0_m) / cell_m)), 0L,
                               static_cast<long>(pattern.ny - 1));
    const detail::MachineLandings landings = detail::to_machine_frame(x_m[i], machine);
    for (int d = 0; d < landings.count; ++d) {
      // Clamped: rounding at the extreme landing must not step outside the grid.
      const long ix = std::clamp(static_cast<long>(std::floor((landings.x_m[d] - pattern.x0_m) / cell_m)), 0L,
                                 static_cast<long>(pattern.nx - 1));
      pattern.mass_kg[static_cast<std::size_t>(iy * pattern.nx + ix)] += mass_kg[i];
    }
  }
  return pattern;
}

}  // namespace spread::metrics
