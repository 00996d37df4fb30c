#pragma once
// Tray layouts and deterministic pseudo-random patterns the overlap tests share.
#include <cstdint>
#include <random>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/core/unit_uniform.hpp"

namespace spread::metrics::testing {

inline TrayLayout layout(int count, double width_m = 0.5) {
  TrayLayout trays;
  trays.tray_width_m = width_m;
  trays.tray_count = count;
  return trays;
}

// Deterministic pseudo-random pattern in [0.1, 1.1) kg per tray (own mapping from the raw 64-bit draws,
// independent of the standard library's distributions).
inline std::vector<double> random_pattern(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> p(static_cast<std::size_t>(count));
  for (double& v : p) v = 0.1 + spread::unit_uniform(rng());
  return p;
}

}  // namespace spread::metrics::testing
