#pragma once
// The machine's ground pattern at one setting as the cells a stamp puts down: mass fraction of the
// discharged mass per cell of the field grid's size, machine frame (x to the right, y forward, the disc
// centres' midpoint at the origin; libspread/core/vec3.hpp). Only cells that receive mass are kept, in
// flat arrays: the stamping loop runs over them once per step of the machine.
//
// The pattern is the predictor's landings binned with the same Epanechnikov kernel its trays use
// (Prediction::kernel_half_width_m), as a product kernel in x and y: each landing's mass spread over
// [x − h, x + h] × [y − h, y + h] with weights K(u)K(v). Summed along y, a cell column holds exactly the
// kernel estimate of the transverse distribution in the trays (the marginal of a product kernel is the
// one-dimensional kernel), so a field spread in straight passes reproduces the tray test's overlap.
#include <cstddef>
#include <vector>

#include "libspread/analysis/predict/predictor.hpp"

namespace spread::field {

struct StampPattern {
  double cell_m = 0.5;
  // Cell centres (m, machine frame) and the fraction of the discharged mass each receives.
  std::vector<double> x_m, y_m, fraction;
  double landed_fraction = 0.0;  // Σ fraction: the rest did not land (Prediction's not-landed granules)
  // The flow this setting meters as a share of the field setting's (a border setting with its edge-side
  // disc at 60 % meters 0.8 of it).
  double metered_fraction = 1.0;
  std::size_t size() const { return fraction.size(); }
};

// From a prediction's landings (both discs, machine frame, mass fractions of the whole machine's
// discharge). Cell edges at multiples of cell_m. Throws std::invalid_argument when cell_m <= 0.
StampPattern stamp_pattern(const predict::Prediction& prediction, double cell_m);

// The same with only disc `disc`'s landings (predict::kLeftDisc or kRightDisc), still as fractions of
// the whole machine's discharge: one disc's half of the pattern (a section switched off).
StampPattern stamp_pattern_of_disc(const predict::Prediction& prediction, int disc, double cell_m);

// Two discs at their own settings and flows as one stamp: `field_side` and `edge_side` each hold one
// disc's cells as fractions of its prediction's whole discharge, `*_share` that disc's share of it (its
// landings' mass, landed or not); the edge-side disc meters edge_flow_fraction of its normal flow. The
// result's fractions are of its own metered mass, metered_fraction = field_share + edge_flow · edge_share.
StampPattern combine_discs(const StampPattern& field_side, double field_share, const StampPattern& edge_side,
                           double edge_share, double edge_flow_fraction);

// The share of the machine's discharge that disc `disc`'s landings carry (landed or not).
double disc_share(const predict::Prediction& prediction, int disc);

}  // namespace spread::field
