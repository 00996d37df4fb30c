#pragma once
// Quantile cells of one launch-table row, for interpolating between rows whose samples do not correspond
// one to one (DEM rows: different granules, different counts; launch_interpolation.hpp).
//
// The samples are sorted by `primary_key` and cut into `primary` groups of equal mass (a sample belongs to
// the group in which the midpoint of its share of the row's mass falls); each group is sorted by
// `secondary_key` and cut likewise into `secondary` cells (a Knothe–Rosenblatt partition). Cell c of two
// rows then covers the same quantile range of the two keys, whatever the rows' counts: cell c of the
// lower row and cell c of the upper row are "the same part of the distribution". Interpolation moves
// each cell's mean between the rows and keeps every granule's deviation from its cell mean.
//
// Ties are broken by the sample index, so the cells are deterministic. Does not allocate.
#include <cstddef>
#include <cstdint>
#include <span>

#include "libspread/io/tables/table_format.hpp"

namespace spread::predict {

// A sample's cell: at most 16 × 4 = 64 cells (quantile_cells_for), so one byte holds it.
using CellIndex = std::uint8_t;

struct QuantileCellCounts {
  int primary = 1;    // groups along the primary key
  int secondary = 1;  // cells per group along the secondary key
  int cells() const { return primary * secondary; }
};

// Cells for a material whose smallest row holds this many samples: 16 × 4 for rows of ≥ 2048 samples,
// fewer for smaller rows so that a cell keeps ≥ 32 samples (the noise of its mean is then below
// 1/√32 ≈ 18 % of the spread inside the cell), at least 1 × 1. More cells follow the rows' shapes more
// finely but move granules by noisier means; 8 × 4 to 32 × 2 measured alike on DEM rows of ~2200
// samples (docs/building-tables.md, "Interpolation between DEM rows").
QuantileCellCounts quantile_cells_for(std::size_t smallest_row_count);

// Writes cell_of_sample[i] in [0, counts.cells()) for the row's n samples (n = mass_kg.size() = the key
// sizes = cell_of_sample.size() = order_scratch.size()). Throws std::invalid_argument for an empty row,
// mismatched sizes, counts < 1, a non-finite key, or a mass that is not finite and > 0 (naming which and
// the sample index).
void assign_quantile_cells(std::span<const double> primary_key, std::span<const double> secondary_key,
                           std::span<const double> mass_kg, QuantileCellCounts counts,
                           std::span<std::uint32_t> order_scratch, std::span<CellIndex> cell_of_sample);

// Mass-weighted mean launch state of every cell, written as a LaunchSample: position, velocity and spin
// fields are the means, mass_kg is the cell's total mass (0: empty cell, other fields 0), the other
// fields 0. cell_mean.size() == number of cells; cell_of_sample as assign_quantile_cells wrote it.
void quantile_cell_means(std::span<const tables::LaunchSample> samples, std::span<const CellIndex> cell_of_sample,
                         std::span<tables::LaunchSample> cell_mean);

}  // namespace spread::predict
