// CSV of the as-applied grid (rate_grid_csv.hpp).
#include "libspread/analysis/field/rate_grid_csv.hpp"

#include <cstdio>
#include <memory>

#include "libspread/core/error.hpp"

namespace spread::field {

void write_rate_grid_csv(const std::string& path, const RateGrid& grid, const std::vector<std::uint8_t>& inside,
                         const std::string& crs) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> out(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!out) throw Error(ErrorKind::kIo, path, path + ": cannot write the rate grid");
  std::fprintf(out.get(), "# as-applied rate, %g m cells; x_m, y_m: cell centre in %s; inside: centre inside the boundary\n",
               grid.cell_m, crs.c_str());
  std::fprintf(out.get(), "x_m,y_m,rate_kg_ha,inside\n");
  const double to_kg_ha = 1e4 / grid.cell_area_m2();
  for (int iy = 0; iy < grid.ny; ++iy) {
    for (int ix = 0; ix < grid.nx; ++ix) {
      const std::size_t i = static_cast<std::size_t>(iy) * grid.nx + ix;
      if (!inside[i] && grid.mass_kg[i] <= 0.0) continue;
      const Point c = grid.centre(ix, iy);
      std::fprintf(out.get(), "%.2f,%.2f,%.3f,%d\n", c.x_m, c.y_m, grid.mass_kg[i] * to_kg_ha, inside[i] ? 1 : 0);
    }
  }
  if (std::ferror(out.get())) throw Error(ErrorKind::kIo, path, path + ": write failed");
}

}  // namespace spread::field
