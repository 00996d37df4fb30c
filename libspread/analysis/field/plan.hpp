#pragma once
// A spreading plan from a boundary: headland passes round the field, then tramlines across what the
// headland leaves, parallel to a chosen edge at the bout width W (the tramlines a drill leaves for the
// sprayer and the spreader).
//   - Headland pass k (1 = outermost) follows the boundary offset inward by (k − ½) W, driven
//     counter-clockwise so that the boundary is on the driver's right (the side border and edge settings are found for,
//     predict::EdgeRequest::side).
//   - Tramline j lies (H + j + ½) W from the reference edge's line, H the headland passes, inside the
//     boundary offset inward by H W; a line that the field's shape cuts in several pieces gives a pass
//     per piece. Neighbouring tramlines are driven in opposite directions (to-and-fro).
// Offsets are mitred: each edge's line moved inward, the new vertices where neighbouring moved lines
// meet, which is exact for the straight edges of a field and folds over itself where a part of the field
// is narrower than the offset — refused, naming the pass.
#include <vector>

#include "libspread/analysis/field/boundary.hpp"
#include "libspread/analysis/field/pass.hpp"

namespace spread::field {

struct PlanSettings {
  double bout_width_m = 24.0;
  int headland_passes = 1;     // 0: tramlines reach the boundary
  int reference_edge = -1;     // edge i runs from vertex i to i + 1 of the boundary's ring; −1: the longest
};

// Throws spread::Error (kArgument, "plan") for a bout width outside (0, 100] m, negative headland passes,
// a reference edge not in the ring, or a headland offset that folds over itself.
std::vector<Pass> plan_field(const Boundary& boundary, const PlanSettings& settings);

// The ring moved inward by offset_m (counter-clockwise ring in, counter-clockwise ring out), mitred.
Ring offset_inward(const Ring& ring, double offset_m);

}  // namespace spread::field
