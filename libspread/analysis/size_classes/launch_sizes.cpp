#include "libspread/analysis/size_classes/launch_sizes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace spread::size_classes {

double launch_passing_size_mm(std::span<const tables::LaunchSample> samples, double percent) {
  if (samples.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<std::pair<double, double>> by_size;  // (diameter mm, mass kg)
  by_size.reserve(samples.size());
  double total = 0.0;
  for (const tables::LaunchSample& s : samples) {
    by_size.emplace_back(1e3 * double{s.diameter_m}, double{s.mass_kg});
    total += double{s.mass_kg};
  }
  std::sort(by_size.begin(), by_size.end());
  // The empirical curve through (d_k, mass below d_k plus half of d_k's own): symmetric in the samples, so
  // a set of equal granules has its d50 at their diameter.
  const double target = percent / 100.0 * total;
  double below = 0.0, previous_d = by_size.front().first, previous_at = 0.5 * by_size.front().second;
  if (target <= previous_at) return previous_d;
  for (const auto& [d, m] : by_size) {
    const double at = below + 0.5 * m;
    if (at >= target && at > previous_at) return previous_d + (target - previous_at) / (at - previous_at) * (d - previous_d);
    below += m;
    previous_d = d;
    previous_at = at;
  }
  return by_size.back().first;
}

LaunchSizes launch_sizes(std::span<const tables::LaunchSample> samples) {
  LaunchSizes out;
  out.d50_mm = launch_passing_size_mm(samples, 50.0);
  out.size_guide_number = 100.0 * out.d50_mm;
  out.uniformity_index = 100.0 * launch_passing_size_mm(samples, 5.0) / launch_passing_size_mm(samples, 90.0);
  return out;
}

}  // namespace spread::size_classes
