#pragma once
// A recorded track (a terminal's or a GNSS receiver's log) as a pass. CSV with a header naming the
// columns, in any order: time_s, then either x_m, y_m (metres in the field boundary's CRS) or lon_deg,
// lat_deg (WGS 84, projected to the boundary's CRS), then speed_m_s and heading_deg (clockwise from north,
// as receivers report it). Optional `spreading` (1/0): rows with 0 end a pass and start the next at the
// next 1 (the feed shut on a turn). Lines starting with # are comments.
//
// A track is refused, naming the line, where time does not increase or the machine moves farther
// between two fixes than its recorded speeds allow: more than 1.5 · max(v_i, v_i+1) · Δt + kJumpSlack_m
// (a lost fix, two logs joined, a receiver re-initialised). The positions' own direction gives the
// heading of each step; a recorded heading more than 90° from it (a reversing machine, or a log in
// another convention) is named too.
#include <string>
#include <vector>

#include "libspread/analysis/field/boundary.hpp"
#include "libspread/analysis/field/pass.hpp"

namespace spread::field {

inline constexpr double kJumpSlack_m = 2.0;  // GNSS noise of a single-frequency receiver, with margin

std::vector<Pass> read_track_csv(const std::string& path, const Boundary& boundary);
std::vector<Pass> parse_track_csv(const std::string& text, const std::string& where, const Boundary& boundary);

}  // namespace spread::field
