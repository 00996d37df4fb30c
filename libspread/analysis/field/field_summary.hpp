#pragma once
// The as-applied map's numbers. A cell belongs to the field when its centre lies inside the boundary.
//   - rate of a cell: its mass over its area (kg/ha);
//   - field CV: s / x̄ over the field's cells, s the sample standard deviation (docs/design.md §3, as the
//     tray test's CV, with the cells for trays);
//   - areas under 80 %, within 80–120 %, over 120 % of the target rate (the bands section-control
//     studies report over- and under-application in);
//   - mass beyond the boundary: every stamped kilogram in a cell outside it or off the grid, in kg and as
//     a share of the metered mass. Applied + beyond + not landed = metered.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "libspread/analysis/field/as_applied.hpp"
#include "libspread/analysis/field/boundary.hpp"

namespace spread::field {

inline constexpr double kUnderFraction = 0.80;
inline constexpr double kOverFraction = 1.20;

struct FieldSummary {
  double target_rate_kg_ha = 0.0;
  double mean_rate_kg_ha = 0.0;   // over the field's cells
  double cv = 0.0;                // fraction
  std::size_t cells_inside = 0;
  double field_area_m2 = 0.0;     // the cells' area (the boundary's own: Boundary::area_m2)
  double under_area_m2 = 0.0, within_area_m2 = 0.0, over_area_m2 = 0.0;
  double metered_kg = 0.0, applied_kg = 0.0, beyond_kg = 0.0, not_landed_kg = 0.0;
  double beyond_fraction = 0.0;   // of the metered mass
};

// 1 for the grid's cells whose centre lies inside the ring, row by row (the ring's crossings of each
// row's centre line, sorted, filled between pairs: the even–odd rule).
std::vector<std::uint8_t> inside_mask(const RateGrid& grid, const Ring& ring);

FieldSummary summarise(const AsApplied& run, const Boundary& boundary, double target_rate_kg_ha);

}  // namespace spread::field
