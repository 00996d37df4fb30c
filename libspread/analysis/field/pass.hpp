#pragma once
// What the machine drives while spreading: passes, each a polyline driven in its order at one setting.
// A plan (plan.hpp) or a recorded track (track_csv.hpp) makes them; the run (as_applied.hpp) stamps
// them. Turns between passes are driven with the discs' feed shut: they are not passes.
#include <string>
#include <vector>

#include "libspread/analysis/field/field_geometry.hpp"

namespace spread::field {

enum class PassKind { kHeadland, kTramline, kTrack };
const char* to_string(PassKind kind);

struct Pass {
  PassKind kind = PassKind::kTramline;
  std::vector<Point> path;   // metres, in driving order (a closed headland round repeats its first point)
  int setting = 0;           // which of the run's stamp patterns the discs run at (0: the field's setting)
  double flow_fraction = 1.0;  // metered flow as a share of the field's (a border setting's reduced flow)
  bool outermost = false;    // the pass along the boundary (border or edge mode applies)
};

double path_length_m(const std::vector<Point>& path);

}  // namespace spread::field
