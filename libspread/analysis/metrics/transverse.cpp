// Tray layout and the transverse distribution (docs/design.md §3: the pattern summed along the driving
// direction into 0.5 m trays, ISO 5690 / EN 13739).
#include <cmath>
#include <stdexcept>
#include <string>

#include "libspread/analysis/metrics/input_checks.hpp"
#include "libspread/analysis/metrics/machine_frame.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/metrics/wide_kernel.hpp"

namespace spread::metrics {

TrayLayout tray_layout_covering(double half_extent_m, double tray_width_m) {
  if (!(std::isfinite(tray_width_m) && tray_width_m > 0.0)) {
    throw std::invalid_argument("tray_layout_covering: tray_width_m must be finite and > 0, got " +
                                std::to_string(tray_width_m));
  }
  if (!(std::isfinite(half_extent_m) && half_extent_m >= 0.0)) {
    throw std::invalid_argument("tray_layout_covering: half_extent_m must be finite and >= 0, got " +
                                std::to_string(half_extent_m));
  }
  // The relative slack keeps 12 m / 0.5 m from becoming 25 trays through rounding.
  const double trays_needed = std::ceil(2.0 * half_extent_m / tray_width_m * (1.0 - 1e-12));
  if (trays_needed > 1e7) {
    throw std::invalid_argument("tray_layout_covering: more than 1e7 trays for half_extent_m " +
                                std::to_string(half_extent_m));
  }
  TrayLayout layout;
  layout.tray_width_m = tray_width_m;
  layout.tray_count = static_cast<int>(trays_needed);
  return layout;
}

double accumulate_transverse(std::span<const double> x_m, std::span<const double> mass_kg,
                             const MachineLayout& machine, const TrayLayout& trays,
                             std::span<double> tray_mass_kg) {
  detail::require_same_size(x_m.size(), mass_kg.size(), "accumulate_transverse", "x_m", "mass_kg");
  detail::require_tray_span(tray_mass_kg.size(), trays, "accumulate_transverse", "tray_mass_kg");
  detail::require_valid_machine(machine, "accumulate_transverse");

  const double left_edge_m = trays.left_edge_m();
  const double trays_per_m = 1.0 / trays.tray_width_m;
  const double tray_count = static_cast<double>(trays.tray_count);
  double lost_kg = 0.0;
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    const detail::MachineLandings landings = detail::to_machine_frame(x_m[i], machine);
    for (int d = 0; d < landings.count; ++d) {
      const double tray_position = (landings.x_m[d] - left_edge_m) * trays_per_m;
      // Written so that NaN fails the test (and is counted lost) before the cast.
      if (tray_position >= 0.0 && tray_position < tray_count) {
        tray_mass_kg[static_cast<std::size_t>(tray_position)] += mass_kg[i];
      } else {
        lost_kg += mass_kg[i];
      }
    }
  }
  return lost_kg;
}

}  // namespace spread::metrics

namespace spread::metrics {

double accumulate_transverse_kernel(std::span<const double> x_m, std::span<const double> mass_kg,
                                    const TrayLayout& trays, double kernel_half_width_m,
                                    std::span<double> tray_mass_kg, std::span<double> scratch) {
  if (std::isfinite(kernel_half_width_m) && wide_kernel(kernel_half_width_m, trays) &&
      scratch.size() >= wide_kernel_scratch_size(trays)) {
    detail::require_same_size(x_m.size(), mass_kg.size(), "accumulate_transverse_kernel", "x_m", "mass_kg");
    detail::require_tray_span(tray_mass_kg.size(), trays, "accumulate_transverse_kernel", "tray_mass_kg");
    return accumulate_wide_kernel(x_m, mass_kg, trays, kernel_half_width_m, tray_mass_kg, scratch);
  }
  return accumulate_transverse_kernel(x_m, mass_kg, trays, kernel_half_width_m, tray_mass_kg);
}

double accumulate_transverse_kernel(std::span<const double> x_m, std::span<const double> mass_kg,
                                    const TrayLayout& trays, double kernel_half_width_m,
                                    std::span<double> tray_mass_kg) {
  detail::require_same_size(x_m.size(), mass_kg.size(), "accumulate_transverse_kernel", "x_m", "mass_kg");
  detail::require_tray_span(tray_mass_kg.size(), trays, "accumulate_transverse_kernel", "tray_mass_kg");
  if (!(std::isfinite(kernel_half_width_m) && kernel_half_width_m >= 0.0)) {
    throw std::invalid_argument("accumulate_transverse_kernel: kernel_half_width_m must be finite and >= 0, got " +
                                std::to_string(kernel_half_width_m));
  }
  if (kernel_half_width_m == 0.0) return accumulate_transverse(x_m, mass_kg, MachineLayout{1, 0.0}, trays, tray_mass_kg);
  const double left_edge_m = trays.left_edge_m();
  const double right_edge_m = -left_edge_m;
  const double w = trays.tray_width_m;
  const double inv_h = 1.0 / kernel_half_width_m;
  const long last = static_cast<long>(trays.tray_count) - 1;
  double lost_kg = 0.0;
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    const double x = x_m[i];
    const double m = mass_kg[i];
    if (!std::isfinite(x) || x + kernel_half_width_m <= left_edge_m || x - kernel_half_width_m >= right_edge_m) {
      lost_kg += m;
      continue;
    }
    // Mass beyond the layout's outer edges is lost, the rest goes to the trays the kernel covers (a kernel
    // inside the layout loses m (0 + 1 − 1) = 0: not computed).
    const double u_left = (left_edge_m - x) * inv_h, u_right = (right_edge_m - x) * inv_h;
    if (u_left > -1.0 || u_right < 1.0) lost_kg += m * (epanechnikov_cdf(u_left) + 1.0 - epanechnikov_cdf(u_right));
    // The floors without a libm call (kernel_edge_floor: positions clamped around the layout).
    const long first = std::max(0L, kernel_edge_floor((x - kernel_half_width_m - left_edge_m) / w, last + 1));
    const long end = std::min(last, kernel_edge_floor((x + kernel_half_width_m - left_edge_m) / w, last + 1));
    double below = epanechnikov_cdf((left_edge_m + static_cast<double>(first) * w - x) * inv_h);
    // Two trays at a time in SSE registers: the CDF at their right edges, each tray's share the difference
    // from its left edge's. The CDF is taken on u clamped to [−1, 1] (which gives exactly 0 and 1 there),
    // so every tray gets the same bits as one at a time.
    typedef double Double2 __attribute__((vector_size(16)));
    long k = first;
    for (; k + 1 <= end; k += 2) {
      const Double2 edge = {static_cast<double>(k + 1), static_cast<double>(k + 2)};
      Double2 u = (left_edge_m + edge * w - x) * inv_h;
      u = u < -1.0 ? Double2{-1.0, -1.0} : u;  // lane-wise selects, no branch at the kernel's ends
      u = u > 1.0 ? Double2{1.0, 1.0} : u;
      const Double2 above = 0.5 + 0.25 * u * (3.0 - u * u);
      const Double2 left = {below, above[0]};
      const Double2 share = m * (above - left);
      // Tray by tray: the next landing often adds to a tray pair shifted by one, and a 16-byte load
      // overlapping half of an earlier 16-byte store waits for the store to drain.
      tray_mass_kg[static_cast<std::size_t>(k)] += share[0];
      tray_mass_kg[static_cast<std::size_t>(k) + 1] += share[1];
      below = above[1];
    }
    for (; k <= end; ++k) {
      const double above = epanechnikov_cdf((left_edge_m + static_cast<double>(k + 1) * w - x) * inv_h);
      tray_mass_kg[static_cast<std::size_t>(k)] += m * (above - below);
      below = above;
    }
  }
  return lost_kg;
}

}  // namespace spread::metrics
