#pragma once
// The as-applied map of a field: every pass cut into steps of at most step_m, each step stamped with the
// ground pattern of its pass's setting at the mass the machine meters over it. A controller meters the
// target rate at the bout width whatever the speed (docs/design.md §3: Q = rate · W · v), so the mass
// over a step of length l is rate · W · l · flow_fraction — the step's length, not its time.
//
// Stages: fit the grid (the boundary and the passes, plus the pattern's reach), cut the passes into steps,
// stamp them in order. The same passes, patterns and settings give the same grid bit for bit.
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "libspread/analysis/field/boundary.hpp"
#include "libspread/analysis/field/pass.hpp"
#include "libspread/analysis/field/rate_grid.hpp"
#include "libspread/analysis/field/stamp_pattern.hpp"

namespace spread::field {

struct RunSettings {
  double target_rate_kg_ha = 200.0;
  double bout_width_m = 24.0;
  double step_m = 0.5;    // along each pass; the grid's cell size is the patterns'
  // Called every kProgressSteps steps and at the end with (steps done, steps in all): a progress line.
  std::function<void(std::size_t, std::size_t)> progress;
};
inline constexpr std::size_t kProgressSteps = 2000;

struct AsApplied {
  RateGrid grid;
  double metered_kg = 0.0;     // what the metering delivered to the discs over all passes
  double not_landed_kg = 0.0;  // of it, granules the patterns have not landing (the predictor's not landed)
  double spread_length_m = 0.0;
  std::size_t steps = 0;
};

// Throws spread::Error (kArgument, "field run") for a target rate or bout width <= 0, a step <= 0, no
// pattern, patterns of different cell sizes, a pass whose setting has no pattern.
AsApplied spread_passes(const Boundary& boundary, const std::vector<Pass>& passes,
                        std::span<const StampPattern> patterns, const RunSettings& settings);

// The grid a run stamps into: the boundary and every pass, plus `reach_m` (the farthest a stamp throws)
// and two cells all round.
RateGrid grid_for(const Boundary& boundary, const std::vector<Pass>& passes, double reach_m, double cell_m);
// The farthest cell centre of a stamp from the machine (m).
double pattern_reach_m(const StampPattern& pattern);

// The steps of a pass: its path cut into pieces of at most step_m, each stamped at its midpoint with the
// piece's direction. Appends to `steps` with each piece's length as mass_kg (scaled by the run).
void cut_into_steps(const Pass& pass, double step_m, std::vector<Step>& steps);

}  // namespace spread::field
