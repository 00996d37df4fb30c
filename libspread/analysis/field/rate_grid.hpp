#pragma once
// The as-applied grid: mass (kg) per square cell over the field and the ground the machine's throw
// reaches beyond it. Cell (ix, iy) covers [x0 + ix c, x0 + (ix + 1) c) × [y0 + iy c, y0 + (iy + 1) c),
// row-major (index iy · nx + ix), edges at multiples of c in the boundary's CRS.
#include <cstddef>
#include <vector>

#include "libspread/analysis/field/field_geometry.hpp"
#include "libspread/analysis/field/stamp_pattern.hpp"

namespace spread::field {

struct RateGrid {
  double x0_m = 0.0, y0_m = 0.0;
  double cell_m = 0.5;
  int nx = 0, ny = 0;
  std::vector<double> mass_kg;
  double off_grid_kg = 0.0;  // stamped mass that fell outside the grid (beyond the boundary by construction)
  double cell_area_m2() const { return cell_m * cell_m; }
  Point centre(int ix, int iy) const { return {x0_m + (ix + 0.5) * cell_m, y0_m + (iy + 0.5) * cell_m}; }
};

// A grid of cell_m cells covering [min, max] in x and y plus margin_m all round, edges at multiples of
// cell_m. Throws spread::Error (kArgument) when it would exceed kMaxGridCells.
inline constexpr double kMaxGridCells = 5e7;  // 400 MB of doubles: 1,250 ha with its margin at 0.5 m cells
RateGrid grid_covering(double min_x_m, double min_y_m, double max_x_m, double max_y_m, double margin_m, double cell_m);

// One step of the machine: the discs' midpoint at (x_m, y_m) heading along the unit vector
// (forward_x, forward_y), discharging mass_kg at the pattern's setting. Each pattern cell's mass goes to
// the grid point where its centre lands, split bilinearly among the four grid cells round it (mass is
// conserved: the four weights sum to 1; a share beyond the grid is counted in off_grid_kg).
struct Step {
  double x_m = 0.0, y_m = 0.0;
  double forward_x = 0.0, forward_y = 1.0;
  double mass_kg = 0.0;
};
void stamp(RateGrid& grid, const StampPattern& pattern, const Step& step);

}  // namespace spread::field
