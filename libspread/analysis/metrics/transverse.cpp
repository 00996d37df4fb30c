// Tray layout and the transverse distribution (docs/design.md §3: the pattern summed along the driving
// direction into 0.5 m trays, ISO 5690 / EN 13739).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "libspread/analysis/metrics/input_checks.hpp"
#include "libspread/analysis/metrics/machine_frame.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/metrics/wide_kernel.hpp"
#include "libspread/core/cpu_features.hpp"

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

namespace {

// What binning one landing under a kernel of half-width h needs of the layout (computed once per call).
struct KernelFrame {
  double left_edge_m, right_edge_m, tray_width_m, kernel_half_width_m, inverse_half_width;
  long last;  // the last tray
};

// One landing (x, m) binned: its mass lost beyond the layout's outer edges returned, the rest added to the
// trays its kernel covers, tray k getting m (F(u_{k+1}) − F(u_k)), u at the tray's edges.
inline double bin_landing(double x, double m, const KernelFrame& f, double* tray_mass_kg) {
  const double left_edge_m = f.left_edge_m, right_edge_m = f.right_edge_m, w = f.tray_width_m;
  const double h = f.kernel_half_width_m, inv_h = f.inverse_half_width;
  const long last = f.last;
  if (!std::isfinite(x) || x + h <= left_edge_m || x - h >= right_edge_m) return m;
  // Mass beyond the layout's outer edges is lost, the rest goes to the trays the kernel covers (a kernel
  // inside the layout loses m (0 + 1 − 1) = 0: not computed).
  double lost_kg = 0.0;
  const double u_left = (left_edge_m - x) * inv_h, u_right = (right_edge_m - x) * inv_h;
  if (u_left > -1.0 || u_right < 1.0) lost_kg = m * (epanechnikov_cdf(u_left) + 1.0 - epanechnikov_cdf(u_right));
  // The floors without a libm call (kernel_edge_floor: positions clamped around the layout).
  const long first = std::max(0L, kernel_edge_floor((x - h - left_edge_m) / w, last + 1));
  const long end = std::min(last, kernel_edge_floor((x + h - left_edge_m) / w, last + 1));
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
  return lost_kg;
}

// kLanes doubles and as many 32-bit integers side by side (GCC/Clang vector extension).
template <std::size_t kLanes>
struct KernelLanes {
  typedef double Double __attribute__((vector_size(8 * kLanes)));
  typedef std::int32_t Int __attribute__((vector_size(4 * kLanes)));
};

// Kernels covering at most this many trays are binned kLanes landings at a time.
constexpr long kLaneTrays = 6;

// bin_landing() of kLanes landings at once, lane by lane the same operations (so the same bits), for a
// kernel that covers at most `span` <= kLaneTrays trays: each landing's first tray, the CDF at its left
// edge and the shares of `span` trays from there computed side by side, then added to the trays landing
// by landing in order (the trays past a kernel's end get exactly 0: F = 1 at both their edges), its lost
// mass added to lost_kg in order too. A landing off the layout, across its outer edges or whose trays
// would pass its end is binned by bin_landing().
template <std::size_t kLanes>
__attribute__((always_inline)) inline void bin_landing_lanes(const double* x_m, const double* mass_kg,
                                                             const KernelFrame& f, long span, double* tray_mass_kg,
                                                             double& lost_kg) {
  using Double = typename KernelLanes<kLanes>::Double;
  using Int = typename KernelLanes<kLanes>::Int;
  const double left_edge_m = f.left_edge_m, w = f.tray_width_m, h = f.kernel_half_width_m;
  const double inv_h = f.inverse_half_width;
  Double x, m;
  std::memcpy(&x, x_m, sizeof x);
  std::memcpy(&m, mass_kg, sizeof m);
  // kernel_edge_floor lane by lane: clamped to [−2, T + 2], truncated, one down where that rounded up (a
  // NaN, whose landing bin_landing() takes, clamped to −2 so that every conversion is in range).
  // (Helpers into out-parameters: a lambda returning a wide vector would change its ABI.)
  const double top = static_cast<double>(f.last + 1) + 2.0;
  const auto floor_lanes = [top](Double position, Int& out) __attribute__((always_inline)) {
    position = position >= -2.0 ? position : Double{} - 2.0;
    position = position <= top ? position : Double{} + top;
    const Int truncated = __builtin_convertvector(position, Int);
    out = truncated + __builtin_convertvector(__builtin_convertvector(truncated, Double) > position, Int);
  };
  Int first, end;
  floor_lanes((x - h - left_edge_m) / w, first);
  first = first < 0 ? Int{} : first;
  floor_lanes((x + h - left_edge_m) / w, end);
  const auto cdf = [](Double u, Double& out) __attribute__((always_inline)) {
    u = u < -1.0 ? Double{} - 1.0 : u;
    u = u > 1.0 ? Double{} + 1.0 : u;
    out = 0.5 + 0.25 * u * (3.0 - u * u);
  };
  Double below, above;
  cdf((left_edge_m + __builtin_convertvector(first, Double) * w - x) * inv_h, below);
  double share[kLaneTrays][kLanes];
  for (long j = 0; j < span; ++j) {
    const Int edge = first + static_cast<std::int32_t>(j + 1);
    cdf((left_edge_m + __builtin_convertvector(edge, Double) * w - x) * inv_h, above);
    const Double tray_share = m * (above - below);
    std::memcpy(share[j], &tray_share, sizeof tray_share);
    below = above;
  }
  for (std::size_t l = 0; l < kLanes; ++l) {
    const double xl = x[l];
    const long first_tray = first[l];
    // bin_landing()'s tests: a landing whose kernel loses no mass, with its trays inside the layout.
    const bool inside = std::isfinite(xl) && !((left_edge_m - xl) * inv_h > -1.0) &&
                        !((f.right_edge_m - xl) * inv_h < 1.0) && end[l] < first_tray + span &&
                        first_tray + span - 1 <= f.last;
    if (!inside) {
      lost_kg += bin_landing(xl, m[l], f, tray_mass_kg);
      continue;
    }
    double* trays = tray_mass_kg + first_tray;
    for (long j = 0; j < span; ++j) trays[j] += share[j][l];
  }
}

template <std::size_t kLanes>
__attribute__((always_inline)) inline double bin_landings(std::span<const double> x_m, std::span<const double> mass_kg,
                                                          const KernelFrame& f, double* tray_mass_kg) {
  const long span = static_cast<long>(2.0 * f.kernel_half_width_m / f.tray_width_m) + 2;
  double lost_kg = 0.0;
  std::size_t i = 0;
  if (span <= kLaneTrays) {
    for (; i + kLanes <= x_m.size(); i += kLanes) {
      bin_landing_lanes<kLanes>(&x_m[i], &mass_kg[i], f, span, tray_mass_kg, lost_kg);
    }
  }
  for (; i < x_m.size(); ++i) lost_kg += bin_landing(x_m[i], mass_kg[i], f, tray_mass_kg);
  return lost_kg;
}

double bin_landings_portable(std::span<const double> x_m, std::span<const double> mass_kg, const KernelFrame& f,
                             double* tray_mass_kg) {
  return bin_landings<4>(x_m, mass_kg, f, tray_mass_kg);
}
#if defined(__x86_64__) || defined(__i386__)
__attribute__((target("avx512f"))) double bin_landings_avx512(std::span<const double> x_m,
                                                             std::span<const double> mass_kg, const KernelFrame& f,
                                                             double* tray_mass_kg) {
  return bin_landings<8>(x_m, mass_kg, f, tray_mass_kg);
}
#endif

}  // namespace

namespace detail {
double accumulate_transverse_kernel_in_lanes(std::span<const double> x_m, std::span<const double> mass_kg,
                                             const TrayLayout& trays, double kernel_half_width_m,
                                             std::span<double> tray_mass_kg, std::size_t lanes) {
  detail::require_same_size(x_m.size(), mass_kg.size(), "accumulate_transverse_kernel", "x_m", "mass_kg");
  detail::require_tray_span(tray_mass_kg.size(), trays, "accumulate_transverse_kernel", "tray_mass_kg");
  if (!(std::isfinite(kernel_half_width_m) && kernel_half_width_m >= 0.0)) {
    throw std::invalid_argument("accumulate_transverse_kernel: kernel_half_width_m must be finite and >= 0, got " +
                                std::to_string(kernel_half_width_m));
  }
  if (kernel_half_width_m == 0.0) return accumulate_transverse(x_m, mass_kg, MachineLayout{1, 0.0}, trays, tray_mass_kg);
  const KernelFrame f{trays.left_edge_m(), -trays.left_edge_m(), trays.tray_width_m, kernel_half_width_m,
                      1.0 / kernel_half_width_m, static_cast<long>(trays.tray_count) - 1};
  if (lanes == 1) {
    double lost_kg = 0.0;
    for (std::size_t i = 0; i < x_m.size(); ++i) lost_kg += bin_landing(x_m[i], mass_kg[i], f, tray_mass_kg.data());
    return lost_kg;
  }
#if defined(__x86_64__) || defined(__i386__)
  if (lanes >= 8 && cpu_has_avx512f()) return bin_landings_avx512(x_m, mass_kg, f, tray_mass_kg.data());
#endif
  return bin_landings_portable(x_m, mass_kg, f, tray_mass_kg.data());
}
}  // namespace detail

double accumulate_transverse_kernel(std::span<const double> x_m, std::span<const double> mass_kg,
                                    const TrayLayout& trays, double kernel_half_width_m,
                                    std::span<double> tray_mass_kg) {
  return detail::accumulate_transverse_kernel_in_lanes(x_m, mass_kg, trays, kernel_half_width_m, tray_mass_kg, 8);
}

}  // namespace spread::metrics
