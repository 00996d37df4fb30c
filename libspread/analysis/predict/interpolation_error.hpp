#pragma once
// The interpolation's own error in an answer between two DEM rows (docs/metrics.md "Between rows").
//
// Between rows interpolated by quantile cells (launch_interpolation.hpp) the pattern is the mixture of
// both rows' granules, each moved to the interpolated cells, weighted 1 − t and t. The delta-method
// standard errors (sample_influence.hpp) count the granules of both rows as independent samples of one
// distribution, so the ± of such an answer is the narrowest of all; yet the two rows need not agree about
// the pattern at that speed (the launch states are not linear in rpm: the cells move only on average).
//
// The estimate: the same answer read off each row's part of the mixture alone — its granules, moved to
// the same interpolated cells, carrying the disc's whole mass — gives F_lower and F_upper; their spread
// about the mixture's figure F,
//   e² = (1 − t)·(F_lower − F)² + t·(F_upper − F)²,
// is a further standard error, added to the sampling one in quadrature. It vanishes on a row (t = 0 or
// 1) and grows where the rows disagree about the pattern at that speed; it partly counts the rows'
// sampling noise a second time (conservative). Landings only, no flight: the parts are binned again with
// the answer's trays, kernel and target (two binnings and two width searches more).
//
// What it does not see: the moved cells are smoother than a DEM row built at that speed (the rows' bumps
// move with their cells' means, not as a new row's would fall), so the interpolated CV at a bout comes
// out low — on the main job's table, 15 of 18 comparisons with DEM rows at 525, 664 and 700 rpm, by 1.8
// points on average for Urea and DAP at 11 m — and both parts share that. Two estimates that would see
// it were measured and not kept (docs/building-tables.md "Between rows: the interpolation's own error").

#include <cstddef>
#include <span>

#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::predict {

// One disc's landings from each of its two rows (landing indices into the answer's landings); upper
// count 0: the disc is on a row, or its rows interpolate sample by sample (analytic rows: one granule
// per sample, no texture of its own).
struct DiscRowParts {
  std::size_t lower_first = 0, lower_count = 0;
  std::size_t upper_first = 0, upper_count = 0;
  bool interpolated() const { return upper_count > 0 && lower_count > 0; }
};

// The answer's figures the estimate applies to (each NaN where the answer has none).
struct InterpolatedFigures {
  double throw_width_m = 0.0;
  double working_width_m[2] = {0.0, 0.0};  // to-and-fro, racetrack: the headline band's upper end
  double cv[2] = {0.0, 0.0};               // at bout_trays, to-and-fro and racetrack (fractions)
};

struct InterpolationErrorInput {
  std::span<const double> x_m;     // every landing of the answer, machine frame
  std::span<const double> weight;  // each landing's share of the machine's mass (the answer's)
  DiscRowParts discs[2];
  int disc_count = 1;
  bool mirrored = false;           // the right disc is the left one's mirror image: bin the left, fold
  metrics::TrayLayout trays;
  double kernel_half_width_m = 0.0;
  double upper_weight = 0.0;       // t: the upper row's share (the discs' mean when they differ)
  double cv_target = 0.15;         // fraction
  int bout_trays = 0;              // where the answer's CVs are read; 0: none
  // The return pass of a to-and-fro field where it was flown (Prediction::return_tray_mass_fraction), held
  // at the answer's: the rows' own patterns are re-binned for the outgoing pass only. Empty: the outgoing
  // pattern (still air), or to-and-fro read as racetrack (to_and_fro_as_racetrack).
  std::span<const double> return_trays;
  bool to_and_fro_as_racetrack = false;
  // The answer's headline bands [lower_m, upper_m] (to-and-fro, racetrack); lower > upper: none.
  double headline_lower_m[2] = {1.0, 1.0}, headline_upper_m[2] = {0.0, 0.0};
};

// Workspace: two tray buffers of trays.tray_count, `scratch` as metrics::working_widths needs (and
// accumulate_transverse_kernel), `widths` a WorkingWidths to overwrite (it is large).
struct InterpolationErrorScratch {
  std::span<double> part_trays, disc_trays, scratch;
  metrics::WorkingWidths* widths = nullptr;
};

// True when any disc interpolates by cells (the estimate applies).
bool interpolates_by_cells(const InterpolationErrorInput& input);

// e for each of the answer's figures `answer` (same units): NaN where the answer's figure is NaN, +inf
// where a part's figure is not finite. Does not allocate.
InterpolatedFigures interpolation_error(const InterpolationErrorInput& input, const InterpolatedFigures& answer,
                                        const InterpolationErrorScratch& scratch);

}  // namespace spread::predict
