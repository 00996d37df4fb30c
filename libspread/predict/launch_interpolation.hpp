#pragma once
// Launch samples at an rpm between two table rows (DESIGN.md §4: velocities are stored divided by the rim
// speed ωR and spins by ω, so the normalised samples of neighbouring rows are close and interpolate well;
// the caller scales them back by the requested ω).
//
// Two ways, chosen by the rows themselves:
// - Pairwise: when both rows hold the same number of samples, sample k of one row and sample k of the
//   other describe the same granule (the analytic builder draws the same feed radii and diameters for
//   every rpm), so every field is interpolated linearly: s_k = (1 − t)·a_k + t·b_k, weight = its mass.
// - Mixture: otherwise there is no correspondence, and the result is the union of both rows' samples,
//   each keeping its own state, with its mass scaled by the row's weight ((1 − t) for the lower row, t
//   for the upper one). The ground pattern is then the mass-weighted blend of the two rows' patterns.
// No allocation: outputs are caller-provided spans.
#include <cstddef>
#include <optional>
#include <span>

#include "libspread/tables/table_format.hpp"

namespace spread::predict {

// The two rows around an rpm: lower == upper for an exact row (no interpolation).
struct RowBracket {
  std::size_t lower = 0;
  std::size_t upper = 0;
  double upper_weight = 0.0;  // t in [0, 1): share of the upper row
};

// `row_rpm` ascending. std::nullopt when rpm is outside [row_rpm.front(), row_rpm.back()] or not finite.
std::optional<RowBracket> bracket_rpm(std::span<const double> row_rpm, double rpm);

// Samples needed in the output for rows of these sizes (pairwise: n, mixture: n_a + n_b).
std::size_t interpolated_sample_count(std::size_t lower_count, std::size_t upper_count, double upper_weight);

// Writes interpolated_sample_count(...) samples and their weights (kg, the mass each sample stands for)
// to the front of `out_samples` / `out_weight_kg`; returns that count. With upper_weight == 0 the lower
// row is copied unchanged. Precondition: the outputs are large enough (checked, std::length_error).
std::size_t interpolate_launch_samples(std::span<const tables::LaunchSample> lower,
                                       std::span<const tables::LaunchSample> upper, double upper_weight,
                                       std::span<tables::LaunchSample> out_samples,
                                       std::span<double> out_weight_kg);

}  // namespace spread::predict
