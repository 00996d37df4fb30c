#pragma once
// Where a left-disc sample lands in the machine frame (docs/design.md §3): the left disc centre sits at
// x = -spacing/2 and the right disc throws the mirror image (x → -x about the centre line x = 0).
#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::metrics::detail {

// Lateral landing positions (m) of one sample, one per disc; `count` is 1 or 2.
struct MachineLandings {
  double x_m[2];
  int count;
};

inline MachineLandings to_machine_frame(double sample_x_m, const MachineLayout& machine) {
  if (machine.disc_count == 1) return {{sample_x_m, 0.0}, 1};
  const double left_x_m = sample_x_m - 0.5 * machine.disc_spacing_m;
  return {{left_x_m, -left_x_m}, 2};
}

}  // namespace spread::metrics::detail
