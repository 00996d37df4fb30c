#pragma once
// Launch samples at an rpm between two table rows (docs/design.md §4: velocities are stored divided by the rim
// speed ωR and spins by ω, so the normalised samples of neighbouring rows are close and interpolate well;
// the caller scales them back by the requested ω).
//
// Two ways, chosen by the caller (Predictor) from the rows:
// - Pairwise: when both rows come from the analytic builder with the same count, sample k of one row and
//   sample k of the other describe the same granule (the builder draws the same feed radii and diameters
//   for every rpm), so every field is interpolated linearly: s_k = (1 − t)·a_k + t·b_k, weight = its mass.
// - By quantile cells: otherwise (DEM rows: different granules, different counts) sample k of one row
//   and sample k of the other are unrelated, and averaging two unrelated granules is biased: it shrinks
//   the spread of every quantity the pairing does not match, and through the nonlinear flight it moves
//   the tails — even between two rows that sample the same distribution (two DEM seeds at one rpm),
//   where the right answer is that distribution. So no granule is averaged with another. Each row is cut into quantile cells of its landing distribution
//   (launch_quantile_cells.hpp); cell c covers the same quantiles in both rows. Every granule of both
//   rows is kept and moved by its cell's mean displacement: s' = s − m_c(own row) + (1 − t)·m_c(lower) +
//   t·m_c(upper) for position, velocity and spin (m_c: the cell's mass-weighted mean state), with weight
//   (1 − t)·mass for the lower row's granules and t·mass for the upper row's. So the cells' means — and
//   with them the pattern's quantiles, tails included — move linearly from one row to the other, while
//   each row's spread inside a cell is kept; two rows that are samples of the same distribution give
//   their plain mixture; t = 0 and t = 1 give each row exactly. Output: n_a + n_b samples.
//   (The first method, the plain mixture, did not move the tails: each row's tail stayed where it was.)
// No allocation: outputs are caller-provided spans.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "libspread/analysis/predict/launch_quantile_cells.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::predict {

// The two rows around an rpm: lower == upper for an exact row (no interpolation).
struct RowBracket {
  std::size_t lower = 0;
  std::size_t upper = 0;
  double upper_weight = 0.0;  // t in [0, 1): share of the upper row
};

// `row_rpm` ascending. std::nullopt when rpm is outside [row_rpm.front(), row_rpm.back()] or not finite.
std::optional<RowBracket> bracket_rpm(std::span<const double> row_rpm, double rpm);

// Pairwise. Writes lower.size() samples and their weights (kg, the mass each sample stands for) to the
// front of `out_samples` / `out_weight_kg`; returns that count. With upper_weight == 0 the lower row is
// copied unchanged (and upper may have any size). Throws std::invalid_argument when the rows differ in
// size and upper_weight != 0, std::length_error when the outputs are too small.
std::size_t interpolate_launch_samples(std::span<const tables::LaunchSample> lower,
                                       std::span<const tables::LaunchSample> upper, double upper_weight,
                                       std::span<tables::LaunchSample> out_samples,
                                       std::span<double> out_weight_kg);

// A row with its quantile cells (launch_quantile_cells.hpp). Both rows of a call use the same cell
// counts (cell_mean.size() equal).
struct CelledRow {
  std::span<const tables::LaunchSample> samples;
  std::span<const CellIndex> cell_of_sample;
  std::span<const tables::LaunchSample> cell_mean;
};

// By quantile cells. Writes lower + upper samples and their weights (kg) to the front of the outputs;
// returns that count. upper_weight in [0, 1]. A cell empty in either row moves nothing. Throws
// std::invalid_argument for rows whose cells do not match (sizes, cell index out of range, different
// cell counts), std::length_error when the outputs are too small.
std::size_t interpolate_by_quantile_cells(const CelledRow& lower, const CelledRow& upper, double upper_weight,
                                          std::span<tables::LaunchSample> out_samples,
                                          std::span<double> out_weight_kg);

// What interpolate_by_quantile_cells writes at [first, first + out_samples.size()) (first + size <= lower
// + upper samples), into the front of the outputs, without checking the rows (check_celled_rows, once):
// a caller that lands the samples a chunk at a time needs no buffer for all of them. `cell_target`, when
// not empty, holds quantile_cell_targets() of these rows at this weight (computed once, not per sample).
void interpolate_by_quantile_cells(const CelledRow& lower, const CelledRow& upper, double upper_weight,
                                   std::size_t first, std::span<tables::LaunchSample> out_samples,
                                   std::span<double> out_weight_kg,
                                   std::span<const tables::LaunchSample> cell_target = {});
// Where each cell's granules move to at weight upper_weight: the cell means interpolated, (1 − t)·m_c(lower)
// + t·m_c(upper), into cell_target[c] (cell_target.size() == the cells), its mass_kg 1 where the cell moves
// its granules and 0 where it is empty in either row (its granules stay).
void quantile_cell_targets(const CelledRow& lower, const CelledRow& upper, double upper_weight,
                           std::span<tables::LaunchSample> cell_target);
// std::invalid_argument as interpolate_by_quantile_cells when the rows' cells do not match.
void check_celled_rows(const CelledRow& lower, const CelledRow& upper);

}  // namespace spread::predict
