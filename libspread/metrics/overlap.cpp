// Overlap at a bout width W (DESIGN.md §3): the distribution in the bout [-W/2, W/2] is the sum of the
// machine's pattern placed at every multiple of W, Σ_k pass_k(x - kW). Racetrack: every pass is the
// same pattern. To-and-fro: the machine turns at the headland, so odd passes are mirrored (x → -x).
// CV = s / x̄ with the sample standard deviation over the bout's trays.
//
// Tray grids. The pattern has T trays with edges at -T·w/2 + i·w; the bout has n = round(W/w) trays
// with edges at -n·w/2 + j·w. Pattern tray i of pass k therefore starts at bout-tray coordinate
// i + k·n + (n - T)/2. When n - T is even this is a whole tray index; when it is odd, every pattern tray
// straddles two bout trays and (mass uniform within trays) gives half its mass to each. Each pattern
// tray of each pass lands in at most two bout trays, so one bout costs O(T + n). The bout is scattered
// pass by pass into a fixed buffer on the stack (bouts up to kStackBoutTrays = 2048 trays, 1 km at 0.5 m);
// wider bouts are gathered tray by tray instead (slower: integer divisions per tray), so nothing here
// touches the heap.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "libspread/metrics/input_checks.hpp"
#include "libspread/metrics/metrics.hpp"

namespace spread::metrics {
namespace {

// floor(a / b) for b > 0 (C++ division truncates towards zero).
long floor_div(long a, long b) {
  const long q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

// Reads the overlapped distribution of one bout, tray by tray, without storing it.
class BoutView {
 public:
  BoutView(std::span<const double> pattern_kg, int bout_trays, Overlap overlap)
      : pattern_kg_(pattern_kg),
        pattern_trays_(static_cast<long>(pattern_kg.size())),
        bout_trays_(bout_trays),
        mirror_odd_passes_(overlap == Overlap::kToAndFro) {
    const long excess = bout_trays_ - pattern_trays_;   // n - T
    half_offset_ = (excess % 2) != 0;
    // Whole part of (n - T)/2, rounded down: pattern tray i of pass k starts at i + k·n + offset_
    // (+ 1/2 when half_offset_).
    offset_ = half_offset_ ? (excess - 1) / 2 : excess / 2;
  }

  int tray_count() const { return static_cast<int>(bout_trays_); }

  // Mass (kg) in bout tray j, summed over all passes that reach it.
  double tray_mass_kg(long j) const {
    if (!half_offset_) return passes_sum(j - offset_);
    // Upper half of the pattern tray starting at j - 1 and lower half of the one starting at j.
    return 0.5 * (passes_sum(j - offset_) + passes_sum(j - 1 - offset_));
  }

 private:
  // Σ_k pass_k tray (i0 - k·n): the pattern trays of every pass whose start coincides with position i0.
  double passes_sum(long i0) const {
    const long n = bout_trays_;
    // Valid pattern index 0 <= i0 - k·n < T  ⇔  (i0 - T)/n < k <= i0/n.
    const long k_first = floor_div(i0 - pattern_trays_, n) + 1;
    const long k_last = floor_div(i0, n);
    double sum_kg = 0.0;
    for (long k = k_first; k <= k_last; ++k) {
      const long i = i0 - k * n;
      const bool mirrored = mirror_odd_passes_ && (k % 2 != 0);
      const long source = mirrored ? pattern_trays_ - 1 - i : i;
      sum_kg += pattern_kg_[static_cast<std::size_t>(source)];
    }
    return sum_kg;
  }

  std::span<const double> pattern_kg_;
  long pattern_trays_;
  long bout_trays_;
  bool mirror_odd_passes_;
  bool half_offset_ = false;
  long offset_ = 0;
};

constexpr int kStackBoutTrays = 2048;  // 16 KiB of stack

// Adds weight × (pattern tray i) to bout tray i + base for every i landing in the bout; the mirrored
// pattern reads tray t-1-i. Two branch-free loops so the compiler can vectorise them.
void add_pass(std::span<const double> pattern_kg, bool mirrored, long base, double weight,
              std::span<double> bout_kg) {
  const long t = static_cast<long>(pattern_kg.size());
  const long n = static_cast<long>(bout_kg.size());
  const long i_begin = std::max(0L, -base), i_end = std::min(t, n - base);
  if (i_begin >= i_end) return;
  double* out = bout_kg.data() + base;
  const double* in = pattern_kg.data();
  if (mirrored) {
    for (long i = i_begin; i < i_end; ++i) out[i] += weight * in[t - 1 - i];
  } else {
    for (long i = i_begin; i < i_end; ++i) out[i] += weight * in[i];
  }
}

// Σ_k pass_k into bout_kg (size n, zeroed here): pass k's pattern tray i starts at bout coordinate
// i + base, base = k·n + offset; with a half-tray offset it starts at i + base + 1/2 and gives half its
// mass to bout trays i + base and i + base + 1.
void scatter_bout(std::span<const double> pattern_kg, Overlap overlap, std::span<double> bout_kg) {
  const long t = static_cast<long>(pattern_kg.size());
  const long n = static_cast<long>(bout_kg.size());
  const long excess = n - t;
  const bool half_offset = (excess % 2) != 0;
  const long offset = half_offset ? (excess - 1) / 2 : excess / 2;
  for (double& b : bout_kg) b = 0.0;
  // Passes whose trays [base, base + t + 1) can touch [0, n).
  const long k_first = floor_div(-offset - t - 1, n);
  const long k_last = floor_div(n - offset, n);
  for (long k = k_first; k <= k_last; ++k) {
    const long base = k * n + offset;
    const bool mirrored = overlap == Overlap::kToAndFro && (k % 2 != 0);
    if (half_offset) {
      add_pass(pattern_kg, mirrored, base, 0.5, bout_kg);
      add_pass(pattern_kg, mirrored, base + 1, 0.5, bout_kg);
    } else {
      add_pass(pattern_kg, mirrored, base, 1.0, bout_kg);
    }
  }
}

// CV of n values produced by `value(j)`: sample standard deviation (n - 1) / mean, two passes.
template <typename ValueAt>
double cv_of_values(int n, ValueAt value) {
  double total_kg = 0.0;
  for (int j = 0; j < n; ++j) total_kg += value(j);
  const double mean_kg = total_kg / n;
  if (!(mean_kg > 0.0)) return std::numeric_limits<double>::infinity();  // empty bout: fails any target
  if (n == 1) return 0.0;                                                // one tray: no spread
  double squares_kg2 = 0.0;
  for (int j = 0; j < n; ++j) {
    const double deviation_kg = value(j) - mean_kg;
    squares_kg2 += deviation_kg * deviation_kg;
  }
  return std::sqrt(squares_kg2 / (n - 1)) / mean_kg;
}

double cv_of_bout(std::span<const double> pattern_kg, int n, Overlap overlap) {
  if (n <= kStackBoutTrays) {
    double bout_kg[kStackBoutTrays];
    const std::span<double> bout(bout_kg, static_cast<std::size_t>(n));
    scatter_bout(pattern_kg, overlap, bout);
    return cv_of_values(n, [&bout](int j) { return bout[static_cast<std::size_t>(j)]; });
  }
  const BoutView view(pattern_kg, n, overlap);
  return cv_of_values(n, [&view](int j) { return view.tray_mass_kg(j); });
}

}  // namespace

int bout_tray_count(const TrayLayout& trays, double bout_width_m) {
  detail::require_valid_trays(trays, "bout_tray_count");
  if (!(std::isfinite(bout_width_m) && bout_width_m >= 0.0)) {
    throw std::invalid_argument("bout width must be finite and >= 0 m, got " + std::to_string(bout_width_m));
  }
  const double trays_in_bout = std::round(bout_width_m / trays.tray_width_m);
  if (trays_in_bout > 1e7) {
    throw std::invalid_argument("bout width " + std::to_string(bout_width_m) + " m is more than 1e7 trays");
  }
  return trays_in_bout < 1.0 ? 1 : static_cast<int>(trays_in_bout);
}

void overlapped_profile(std::span<const double> tray_mass_kg, const TrayLayout& trays, double bout_width_m,
                        Overlap overlap, std::span<double> bout_mass_kg) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "overlapped_profile", "tray_mass_kg");
  const int n = bout_tray_count(trays, bout_width_m);
  if (bout_mass_kg.size() != static_cast<std::size_t>(n)) {
    throw std::invalid_argument("overlapped_profile: bout_mass_kg has " + std::to_string(bout_mass_kg.size()) +
                                " entries but the bout of " + std::to_string(bout_width_m) + " m has " +
                                std::to_string(n) + " trays");
  }
  scatter_bout(tray_mass_kg, overlap, bout_mass_kg);
}

double cv_at_width(std::span<const double> tray_mass_kg, const TrayLayout& trays, double bout_width_m,
                   Overlap overlap) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "cv_at_width", "tray_mass_kg");
  return cv_of_bout(tray_mass_kg, bout_tray_count(trays, bout_width_m), overlap);
}

void cv_curve(std::span<const double> tray_mass_kg, const TrayLayout& trays,
              std::span<const double> widths_m, Overlap overlap, std::span<double> cv_out) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "cv_curve", "tray_mass_kg");
  detail::require_same_size(widths_m.size(), cv_out.size(), "cv_curve", "widths_m", "cv_out");
  for (std::size_t i = 0; i < widths_m.size(); ++i) {
    cv_out[i] = cv_of_bout(tray_mass_kg, bout_tray_count(trays, widths_m[i]), overlap);
  }
}

double effective_working_width(std::span<const double> tray_mass_kg, const TrayLayout& trays,
                               Overlap overlap, double cv_target) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "effective_working_width", "tray_mass_kg");
  if (std::isnan(cv_target)) {
    throw std::invalid_argument("effective_working_width: cv_target is NaN");
  }
  // Widest first: the first width meeting the target is the answer (CV(W) need not be monotone).
  for (int n = trays.tray_count; n >= 2; --n) {
    if (cv_of_bout(tray_mass_kg, n, overlap) <= cv_target) return n * trays.tray_width_m;
  }
  return 0.0;
}

}  // namespace spread::metrics
