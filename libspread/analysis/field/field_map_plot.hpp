#pragma once
// The as-applied map as a PNG: each cell coloured by its rate as a share of the target (0 to 150 %, the
// plots' colour map; ≥ 150 % the top colour), cells outside the boundary faded, the boundary in black, the
// passes as thin grey lines, and a legend with the 80 % and 120 % marks. At most kMapMaxPixels a side:
// larger grids are shown a block of cells per pixel (the block's mean rate).
#include <string>
#include <vector>

#include "libspread/analysis/field/boundary.hpp"
#include "libspread/analysis/field/pass.hpp"
#include "libspread/analysis/field/rate_grid.hpp"

namespace spread::field {

inline constexpr int kMapMaxPixels = 1000;
inline constexpr int kPanelMaxPixels = 450;  // a side-by-side panel

// Throws std::runtime_error naming the path when it cannot be written, and with plot::kWithoutPlots in a
// build without plots.
void write_field_map_png(const std::string& path, const RateGrid& grid, const Boundary& boundary,
                         const std::vector<Pass>& passes, double target_rate_kg_ha, const std::string& title);

// Several runs of one field side by side (two to a row) at one scale, each titled (its lines split at
// '\n'), with one legend: the
// strategies of a comparison. The grids and passes must outlive the call. The same refusals.
struct MapPanel {
  const RateGrid* grid = nullptr;
  const std::vector<Pass>* passes = nullptr;
  std::string title;
};
void write_field_maps_png(const std::string& path, const std::vector<MapPanel>& panels, const Boundary& boundary,
                          double target_rate_kg_ha, const std::string& title);

}  // namespace spread::field
