#pragma once
// The as-applied grid as a file a GIS opens: CSV of the cell centres in the boundary's CRS and their
// rate, with the CRS stated in a comment line and in the column names' companion (QGIS "Delimited Text":
// X field x_m, Y field y_m, the layer's CRS the one stated). Only cells with mass or inside the field.
#include <cstdint>
#include <string>
#include <vector>

#include "libspread/analysis/field/rate_grid.hpp"

namespace spread::field {

// Throws spread::Error (kIo) when the file cannot be written.
void write_rate_grid_csv(const std::string& path, const RateGrid& grid, const std::vector<std::uint8_t>& inside,
                         const std::string& crs);

}  // namespace spread::field
