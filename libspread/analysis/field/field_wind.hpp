#pragma once
// A wind over a field in the machine's frame. A wind over the field (east and north components, m/s) is a
// different wind in the machine frame on every heading: the ECU's wind reading and the discs' ground
// patterns take it at the nearest of kHeadingBins headings, so that the plans and the patterns a run
// needs are a few per wind, not one per step. Machine frame: x to the right, (f_y, −f_x) for the
// heading's unit vector f; y forward, f.
#include "libspread/analysis/field/field_geometry.hpp"

namespace spread::field {

inline constexpr int kHeadingBins = 16;  // 22.5° apart: a wind's cross and along components within 20 % of its speed

// The wind (east, north; m/s) in the machine frame of a machine heading along the unit vector `forward`
// (east, north), the heading taken to the nearest of kHeadingBins: (x to the right, y forward).
Point wind_in_machine_frame(Point forward, double wind_east_m_s, double wind_north_m_s);

}  // namespace spread::field
