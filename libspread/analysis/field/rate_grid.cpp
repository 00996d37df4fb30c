// The rate grid and the stamp: the hot loop of a field run, over the pattern's flat arrays.
#include "libspread/analysis/field/rate_grid.hpp"

#include <cmath>
#include <sstream>

#include "libspread/core/error.hpp"

namespace spread::field {

RateGrid grid_covering(double min_x_m, double min_y_m, double max_x_m, double max_y_m, double margin_m, double cell_m) {
  RateGrid g;
  g.cell_m = cell_m;
  const double first_x = std::floor((min_x_m - margin_m) / cell_m), last_x = std::ceil((max_x_m + margin_m) / cell_m);
  const double first_y = std::floor((min_y_m - margin_m) / cell_m), last_y = std::ceil((max_y_m + margin_m) / cell_m);
  const double cells = (last_x - first_x) * (last_y - first_y);
  if (!(cells > 0.0) || cells > kMaxGridCells) {
    std::ostringstream out;
    out << "field grid: " << (max_x_m - min_x_m + 2.0 * margin_m) << " m × " << (max_y_m - min_y_m + 2.0 * margin_m)
        << " m at " << cell_m << " m cells is " << cells << " cells, beyond " << kMaxGridCells;
    throw Error(ErrorKind::kArgument, "field grid", out.str());
  }
  g.x0_m = first_x * cell_m;
  g.y0_m = first_y * cell_m;
  g.nx = static_cast<int>(last_x - first_x);
  g.ny = static_cast<int>(last_y - first_y);
  g.mass_kg.assign(static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny), 0.0);
  return g;
}

void stamp(RateGrid& grid, const StampPattern& pattern, const Step& step) {
  // Machine frame → field: x along the right-hand vector (forward turned clockwise), y along forward.
  const double fx = step.forward_x, fy = step.forward_y;
  const double rx = fy, ry = -fx;
  const double inv_cell = 1.0 / grid.cell_m;
  // Grid coordinates of a point, shifted by half a cell so that floor() gives the lower-left of the
  // four cells whose centres surround it.
  const double ox = (step.x_m - grid.x0_m) * inv_cell - 0.5, oy = (step.y_m - grid.y0_m) * inv_cell - 0.5;
  const double* px = pattern.x_m.data();
  const double* py = pattern.y_m.data();
  const double* pf = pattern.fraction.data();
  double* mass = grid.mass_kg.data();
  const long nx = grid.nx, ny = grid.ny;
  double off_grid = 0.0;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    const double gx = ox + (px[i] * rx + py[i] * fx) * inv_cell;
    const double gy = oy + (px[i] * ry + py[i] * fy) * inv_cell;
    const double m = pf[i] * step.mass_kg;
    const double fgx = std::floor(gx), fgy = std::floor(gy);
    const long ix = static_cast<long>(fgx), iy = static_cast<long>(fgy);
    const double tx = gx - fgx, ty = gy - fgy;
    if (ix >= 0 && iy >= 0 && ix + 1 < nx && iy + 1 < ny) {
      double* row = mass + iy * nx + ix;
      row[0] += m * (1.0 - tx) * (1.0 - ty);
      row[1] += m * tx * (1.0 - ty);
      row[nx] += m * (1.0 - tx) * ty;
      row[nx + 1] += m * tx * ty;
      continue;
    }
    // At the grid's rim: cell by cell, the shares beyond it off the grid.
    const double w[4] = {(1.0 - tx) * (1.0 - ty), tx * (1.0 - ty), (1.0 - tx) * ty, tx * ty};
    const long cx[4] = {ix, ix + 1, ix, ix + 1}, cy[4] = {iy, iy, iy + 1, iy + 1};
    for (int k = 0; k < 4; ++k) {
      if (cx[k] >= 0 && cy[k] >= 0 && cx[k] < nx && cy[k] < ny) {
        mass[cy[k] * nx + cx[k]] += m * w[k];
      } else {
        off_grid += m * w[k];
      }
    }
  }
  grid.off_grid_kg += off_grid;
}

}  // namespace spread::field
