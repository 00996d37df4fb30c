// Overlap at a bout width W (docs/design.md §3): the distribution across the field is the sum of the machine's
// pattern placed at every multiple of W, Σ_k pass_k(x − kW). Racetrack: every pass is the same pattern.
// To-and-fro: the machine turns at the headland, so odd passes are mirrored (x → −x).
//
// True trays. W is a whole number n of trays, so every pass is the pattern shifted by k·n trays: the
// overlapped distribution lives on the pattern's own tray grid and no tray is ever split or averaged
// (splitting a tray between two bout trays is a two-tray moving average, which lowers the CV). The bout
// [−W/2, W/2] holds n whole grid trays when n − T is even (T = pattern trays; the grid is symmetric about
// x = 0). When n − T is odd each bout edge runs through the middle of a grid tray: the bout then holds
// n − 1 whole trays and the two cut trays count half each. This is exact, not an approximation: the
// overlapped distribution is periodic (racetrack: period W, so the two cut trays are the same tray) or
// symmetric about every bout edge (to-and-fro: pass k and pass k+1 are mirror images about their
// midpoint), so one bout with half-weight edge trays holds the same tray values, with the same weights,
// as a whole period of whole trays.
//
// CV = s / x̄ over the bout's trays with weights w_j (1, or 1/2 for a cut tray; Σ w_j = n):
//   x̄ = Σ w_j P_j / n,   s² = Σ w_j (P_j − x̄)² / (n − 1)   (the sample standard deviation when all w_j = 1).
//
// Cost: each pattern tray of each pass lands at most once in the bout, so one bout costs O(T + n). The
// bout is scattered pass by pass into the caller's scratch span when one is given and large enough, else
// into a small stack buffer (bouts up to kStackBoutTrays); wider bouts are gathered tray by tray instead
// (integer divisions per tray), so nothing here touches the heap.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "libspread/analysis/metrics/input_checks.hpp"
#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::metrics {
namespace {

// floor(a / b) for b > 0 (C++ division truncates towards zero).
long floor_div(long a, long b) {
  const long q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

// Pattern tray i of pass k sits at grid index i + k·n (mirrored passes read tray T − 1 − i there).
// Grid index g of the pattern layout covers [left_edge + g·w, left_edge + (g+1)·w); g may be outside
// [0, T). The bout's first touched tray is BoutTrays::first_tray.

// The patterns the passes lay down. Racetrack: every pass is `outgoing`. To-and-fro: even passes are
// `outgoing`, odd passes `returning` mirrored (x → −x), `returning` being the return pass in its own
// machine frame — the outgoing pattern itself unless the return pass is given (in wind it meets the wind
// from the other side). With a return pass of its own the overlapped distribution is no longer symmetric
// about the bout edges: its period is two bouts, and the CV is taken over both (`bouts` = 2).
struct Passes {
  std::span<const double> outgoing;
  std::span<const double> returning;
  bool to_and_fro = false;
  int bouts = 1;
  long t() const { return static_cast<long>(outgoing.size()); }
  bool mirrored(long k) const { return to_and_fro && (k % 2 != 0); }
  std::span<const double> pattern(long k) const { return mirrored(k) ? returning : outgoing; }
};
Passes one_pattern(std::span<const double> pattern_kg, Overlap overlap) {
  return {pattern_kg, pattern_kg, overlap == Overlap::kToAndFro, 1};
}
// A return pattern at the outgoing one's address is the outgoing pattern: one bout, as one_pattern.
Passes to_and_fro_passes(std::span<const double> outgoing_kg, std::span<const double> return_kg) {
  return {outgoing_kg, return_kg, true, return_kg.data() == outgoing_kg.data() ? 1 : 2};
}

// Bout b of the window (b < passes.bouts): the bout centred on pass b.
BoutTrays window_bout(const BoutTrays& bout, int b) {
  BoutTrays shifted = bout;
  shifted.first_tray += b * bout.bout_trays;
  return shifted;
}

// Calls visit(k, i) for pass k and the pattern tray i it puts at grid index g, for every pass reaching g.
template <typename Visit>
void for_each_source(const Passes& passes, long n, long g, Visit visit) {
  const long t = passes.t();
  // Valid pattern index 0 <= g − k·n < T  ⇔  (g − T)/n < k <= g/n.
  const long k_first = floor_div(g - t, n) + 1;
  const long k_last = floor_div(g, n);
  for (long k = k_first; k <= k_last; ++k) {
    const long i = g - k * n;
    visit(k, static_cast<std::size_t>(passes.mirrored(k) ? t - 1 - i : i));
  }
}

// Mass at grid index g summed over every pass that reaches it.
double grid_tray_mass(const Passes& passes, long n, long g) {
  double sum_kg = 0.0;
  for_each_source(passes, n, g, [&](long k, std::size_t i) { sum_kg += passes.pattern(k)[i]; });
  return sum_kg;
}

// Adds (pattern tray i, or T−1−i when mirrored) to out[i + base] for every i landing in out, or — with
// `gather` — the reverse: adds out[i + base] to pattern-sized grad[source(i)]. Two branch-free loops each
// so the compiler can vectorise them.
void add_pass(std::span<const double> pattern_kg, bool mirrored, long base, std::span<double> out) {
  const long t = static_cast<long>(pattern_kg.size());
  const long m = static_cast<long>(out.size());
  const long i_begin = std::max(0L, -base), i_end = std::min(t, m - base);
  if (i_begin >= i_end) return;
  double* o = out.data() + base;
  const double* in = pattern_kg.data();
  if (mirrored) {
    for (long i = i_begin; i < i_end; ++i) o[i] += in[t - 1 - i];
  } else {
    for (long i = i_begin; i < i_end; ++i) o[i] += in[i];
  }
}

void gather_pass(std::span<const double> bout_values, bool mirrored, long base, std::span<double> pattern_out) {
  const long t = static_cast<long>(pattern_out.size());
  const long m = static_cast<long>(bout_values.size());
  const long i_begin = std::max(0L, -base), i_end = std::min(t, m - base);
  if (i_begin >= i_end) return;
  const double* b = bout_values.data() + base;
  double* o = pattern_out.data();
  if (mirrored) {
    for (long i = i_begin; i < i_end; ++i) o[t - 1 - i] += b[i];
  } else {
    for (long i = i_begin; i < i_end; ++i) o[i] += b[i];
  }
}

// Passes k whose trays [k·n − first, k·n − first + T) can touch [0, m).
template <typename PerPass>
void for_each_pass(long t, const BoutTrays& bout, PerPass per_pass) {
  const long n = bout.bout_trays, m = bout.grid_trays, first = bout.first_tray;
  const long k_first = floor_div(first - t, n);
  const long k_last = floor_div(first + m, n) + 1;
  for (long k = k_first; k <= k_last; ++k) per_pass(k, k * n - first);
}

// Σ_k pass_k into window_kg (passes.bouts bouts of bout.grid_trays, zeroed here).
void scatter_window(const Passes& passes, const BoutTrays& bout, std::span<double> window_kg) {
  std::fill(window_kg.begin(), window_kg.end(), 0.0);
  const auto m = static_cast<std::size_t>(bout.grid_trays);
  for (int b = 0; b < passes.bouts; ++b) {
    const std::span<double> out = window_kg.subspan(static_cast<std::size_t>(b) * m, m);
    for_each_pass(passes.t(), window_bout(bout, b), [&](long k, long base) {
      add_pass(passes.pattern(k), passes.mirrored(k), base, out);
    });
  }
}

// Weighted mean and CV of the window's trays (weights 1, or 1/2 for cut edge trays). Over two bouts the
// variance is pooled: s² = Σ w_j (P_j − x̄)² / (2(n − 1)) about the mean of both, which is the one bout's
// when the two bouts are mirror images (the return pass the outgoing one mirrored).
struct BoutMoments {
  double mean_kg = 0.0;
  double sd_kg = 0.0;
  double cv = 0.0;
};

template <typename ValueAt>
BoutMoments bout_moments(const BoutTrays& bout, int bouts, ValueAt value) {
  const int m = bout.grid_trays;
  const int count = bouts * m;
  const int n = bouts * bout.bout_trays;            // Σ w_j
  const int degrees_of_freedom = bouts * (bout.bout_trays - 1);
  auto weight = [&](int j) { return bout.cut_edges && (j % m == 0 || j % m == m - 1) ? 0.5 : 1.0; };
  double total_kg = 0.0;
  for (int j = 0; j < count; ++j) total_kg += weight(j) * value(j);
  BoutMoments r;
  r.mean_kg = total_kg / n;
  if (!(r.mean_kg > 0.0)) {  // empty bout: fails any target
    r.cv = std::numeric_limits<double>::infinity();
    return r;
  }
  if (bout.bout_trays == 1) return r;  // one tray: no spread
  double squares_kg2 = 0.0;
  for (int j = 0; j < count; ++j) {
    const double deviation_kg = value(j) - r.mean_kg;
    squares_kg2 += weight(j) * deviation_kg * deviation_kg;
  }
  r.sd_kg = std::sqrt(squares_kg2 / degrees_of_freedom);
  r.cv = r.sd_kg / r.mean_kg;
  return r;
}

// The window's values: scattered into the caller's scratch when it is large enough, else (with
// kStackBuffer) into a stack buffer up to kStackBoutTrays, else gathered tray by tray. Calls
// use(value_at, scattered values or an empty span) once. The gradient takes no stack buffer: its callers
// pass scratch, and the C API's stack budget (docs/c-api.md "Stack") has no room for a second kilobyte.
template <bool kStackBuffer, typename Use>
auto with_window(const Passes& passes, const BoutTrays& bout, std::span<double> scratch, Use use) {
  const auto grid = static_cast<std::size_t>(passes.bouts * bout.grid_trays);
  if (grid <= scratch.size()) {
    const std::span<double> values = scratch.first(grid);
    scatter_window(passes, bout, values);
    return use([&values](int j) { return values[static_cast<std::size_t>(j)]; }, values);
  }
  if constexpr (kStackBuffer) {
    if (grid <= static_cast<std::size_t>(kStackBoutTrays)) {
      double window_kg[kStackBoutTrays];
      const std::span<double> values(window_kg, grid);
      scatter_window(passes, bout, values);
      return use([&values](int j) { return values[static_cast<std::size_t>(j)]; }, values);
    }
  }
  const int m = bout.grid_trays;
  return use(
      [&](int j) { return grid_tray_mass(passes, bout.bout_trays, bout.first_tray + (j / m) * bout.bout_trays + j % m); },
      std::span<double>{});
}

double cv_of_window(const Passes& passes, const BoutTrays& bout, std::span<double> scratch = {}) {
  return with_window<true>(passes, bout, scratch,
                     [&](auto value, std::span<double>) { return bout_moments(bout, passes.bouts, value).cv; });
}

// ∂CV/∂(pattern tray) into the outgoing pattern's gradient and, to-and-fro with a return pass of its own,
// the return pattern's (left out when that span is empty); both zeroed here.
void window_gradient(const Passes& passes, const BoutTrays& bout, std::span<double> outgoing_gradient,
                     std::span<double> return_gradient, std::span<double> scratch) {
  std::fill(outgoing_gradient.begin(), outgoing_gradient.end(), 0.0);
  std::fill(return_gradient.begin(), return_gradient.end(), 0.0);
  const int m = bout.grid_trays;
  const auto target = [&](long k) { return passes.bouts == 2 && passes.mirrored(k) ? return_gradient : outgoing_gradient; };
  with_window<false>(passes, bout, scratch, [&](auto value, std::span<double> values) {
    const BoutMoments mo = bout_moments(bout, passes.bouts, value);
    const int n = passes.bouts * bout.bout_trays;
    const int degrees_of_freedom = passes.bouts * (bout.bout_trays - 1);
    if (!std::isfinite(mo.cv) || bout.bout_trays == 1) return 0;
    // ∂CV/∂P_j = w_j [ (P_j − x̄) / (dof · s x̄) − CV / (n x̄) ]   (Σ_k w_k (P_k − x̄) = 0 drops a term);
    // with s = 0 (a flat bout) the first term is left out (|·| has no derivative there).
    const double spread_term = mo.sd_kg > 0.0 ? 1.0 / (degrees_of_freedom * mo.sd_kg * mo.mean_kg) : 0.0;
    auto derivative = [&](int j, double p_kg) {
      const double w = bout.cut_edges && (j % m == 0 || j % m == m - 1) ? 0.5 : 1.0;
      return w * ((p_kg - mo.mean_kg) * spread_term - mo.cv / (n * mo.mean_kg));
    };
    // Each pattern tray's derivative is the sum over the window trays it reaches (one per pass).
    if (!values.empty()) {
      for (int j = 0; j < passes.bouts * m; ++j) {
        values[static_cast<std::size_t>(j)] = derivative(j, values[static_cast<std::size_t>(j)]);
      }
      for (int b = 0; b < passes.bouts; ++b) {
        const std::span<const double> bout_values = values.subspan(static_cast<std::size_t>(b * m), static_cast<std::size_t>(m));
        for_each_pass(passes.t(), window_bout(bout, b), [&](long k, long base) {
          if (!target(k).empty()) gather_pass(bout_values, passes.mirrored(k), base, target(k));
        });
      }
      return 0;
    }
    for (int j = 0; j < passes.bouts * m; ++j) {
      const double d = derivative(j, value(j));
      for_each_source(passes, bout.bout_trays, bout.first_tray + (j / m) * bout.bout_trays + j % m,
                      [&](long k, std::size_t i) {
                        if (!target(k).empty()) target(k)[i] += d;
                      });
    }
    return 0;
  });
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

BoutTrays bout_trays(const TrayLayout& trays, int bout_tray_count) {
  detail::require_valid_trays(trays, "bout_trays");
  if (bout_tray_count < 1) {
    throw std::invalid_argument("bout_trays: a bout holds at least one tray, got " + std::to_string(bout_tray_count));
  }
  BoutTrays b;
  b.bout_trays = bout_tray_count;
  const long excess = static_cast<long>(trays.tray_count) - bout_tray_count;  // T − n
  b.cut_edges = (excess % 2) != 0;
  // The bout's left edge −n·w/2 is at grid coordinate (T − n)/2.
  b.first_tray = static_cast<int>(b.cut_edges ? floor_div(excess - 1, 2) : excess / 2);
  b.grid_trays = b.cut_edges ? bout_tray_count + 1 : bout_tray_count;
  return b;
}

void overlapped_profile(std::span<const double> tray_mass_kg, const TrayLayout& trays, double bout_width_m,
                        Overlap overlap, std::span<double> bout_mass_kg) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "overlapped_profile", "tray_mass_kg");
  const BoutTrays bout = bout_trays(trays, bout_tray_count(trays, bout_width_m));
  if (bout_mass_kg.size() != static_cast<std::size_t>(bout.grid_trays)) {
    throw std::invalid_argument("overlapped_profile: bout_mass_kg has " + std::to_string(bout_mass_kg.size()) +
                                " entries but the bout of " + std::to_string(bout_width_m) + " m touches " +
                                std::to_string(bout.grid_trays) + " trays");
  }
  scatter_window(one_pattern(tray_mass_kg, overlap), bout, bout_mass_kg);
}

void overlapped_profile(std::span<const double> tray_mass_kg, std::span<const double> return_tray_mass_kg,
                        const TrayLayout& trays, double bout_width_m, std::span<double> window_mass_kg) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "overlapped_profile", "tray_mass_kg");
  detail::require_tray_span(return_tray_mass_kg.size(), trays, "overlapped_profile", "return_tray_mass_kg");
  const BoutTrays bout = bout_trays(trays, bout_tray_count(trays, bout_width_m));
  if (window_mass_kg.size() != static_cast<std::size_t>(2 * bout.grid_trays)) {
    throw std::invalid_argument("overlapped_profile: window_mass_kg has " + std::to_string(window_mass_kg.size()) +
                                " entries but two bouts of " + std::to_string(bout_width_m) + " m touch " +
                                std::to_string(2 * bout.grid_trays) + " trays");
  }
  // Both bouts even when the return pass is the outgoing one (the second bout is then the first mirrored).
  scatter_window({tray_mass_kg, return_tray_mass_kg, true, 2}, bout, window_mass_kg);
}

double cv_at_width(std::span<const double> tray_mass_kg, const TrayLayout& trays, double bout_width_m,
                   Overlap overlap) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "cv_at_width", "tray_mass_kg");
  return cv_of_window(one_pattern(tray_mass_kg, overlap), bout_trays(trays, bout_tray_count(trays, bout_width_m)));
}

double cv_at_trays(std::span<const double> tray_mass_kg, const TrayLayout& trays, int bout_tray_count,
                   Overlap overlap) {
  return cv_at_trays(tray_mass_kg, trays, bout_tray_count, overlap, {});
}

double cv_at_trays(std::span<const double> tray_mass_kg, const TrayLayout& trays, int bout_tray_count,
                   Overlap overlap, std::span<double> scratch) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "cv_at_trays", "tray_mass_kg");
  return cv_of_window(one_pattern(tray_mass_kg, overlap), bout_trays(trays, bout_tray_count), scratch);
}

double cv_at_trays(std::span<const double> tray_mass_kg, std::span<const double> return_tray_mass_kg,
                   const TrayLayout& trays, int bout_tray_count, std::span<double> scratch) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "cv_at_trays", "tray_mass_kg");
  detail::require_tray_span(return_tray_mass_kg.size(), trays, "cv_at_trays", "return_tray_mass_kg");
  return cv_of_window(to_and_fro_passes(tray_mass_kg, return_tray_mass_kg), bout_trays(trays, bout_tray_count),
                      scratch);
}

void cv_gradient(std::span<const double> tray_mass_kg, const TrayLayout& trays, int bout_tray_count,
                 Overlap overlap, std::span<double> gradient_per_kg) {
  double buffer[kStackBoutTrays];
  cv_gradient(tray_mass_kg, trays, bout_tray_count, overlap, gradient_per_kg, std::span<double>(buffer));
}

void cv_gradient(std::span<const double> tray_mass_kg, const TrayLayout& trays, int bout_tray_count,
                 Overlap overlap, std::span<double> gradient_per_kg, std::span<double> scratch) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "cv_gradient", "tray_mass_kg");
  detail::require_same_size(tray_mass_kg.size(), gradient_per_kg.size(), "cv_gradient", "tray_mass_kg",
                            "gradient_per_kg");
  window_gradient(one_pattern(tray_mass_kg, overlap), bout_trays(trays, bout_tray_count), gradient_per_kg, {},
                  scratch);
}

void cv_gradient(std::span<const double> tray_mass_kg, std::span<const double> return_tray_mass_kg,
                 const TrayLayout& trays, int bout_tray_count, std::span<double> gradient_per_kg,
                 std::span<double> return_gradient_per_kg, std::span<double> scratch) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "cv_gradient", "tray_mass_kg");
  detail::require_tray_span(return_tray_mass_kg.size(), trays, "cv_gradient", "return_tray_mass_kg");
  detail::require_same_size(tray_mass_kg.size(), gradient_per_kg.size(), "cv_gradient", "tray_mass_kg",
                            "gradient_per_kg");
  if (!return_gradient_per_kg.empty()) {
    detail::require_same_size(tray_mass_kg.size(), return_gradient_per_kg.size(), "cv_gradient", "tray_mass_kg",
                              "return_gradient_per_kg");
  }
  window_gradient(to_and_fro_passes(tray_mass_kg, return_tray_mass_kg), bout_trays(trays, bout_tray_count),
                  gradient_per_kg, return_gradient_per_kg, scratch);
}

void cv_curve(std::span<const double> tray_mass_kg, const TrayLayout& trays,
              std::span<const double> widths_m, Overlap overlap, std::span<double> cv_out) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "cv_curve", "tray_mass_kg");
  detail::require_same_size(widths_m.size(), cv_out.size(), "cv_curve", "widths_m", "cv_out");
  for (std::size_t i = 0; i < widths_m.size(); ++i) {
    cv_out[i] = cv_of_window(one_pattern(tray_mass_kg, overlap), bout_trays(trays, bout_tray_count(trays, widths_m[i])));
  }
}

namespace {

// The working-width rule (docs/metrics.md "Effective working width") on a CV(W) curve sampled at
// `count` increasing widths width_at(i): within(i) says whether sample i meets the target, exact_cv(i)
// is its CV (called around each crossing, for the interpolation, and once at each band's lowest point),
// rough_cv(i) ranks the samples inside a band, trays_at(i) is sample i's whole-tray count (0 for a curve
// not on trays). Each band's ends are interpolated linearly in CV between the samples around the
// crossing; an infinite CV puts the crossing at the finite sample.
template <typename WidthAt, typename Within, typename ExactCv, typename RoughCv, typename TraysAt>
WorkingWidth scan_bands(std::size_t count, WidthAt width_at, Within within, ExactCv exact_cv, RoughCv rough_cv,
                        TraysAt trays_at, double cv_target) {
  WorkingWidth r;
  if (count == 0) return r;
  WidthBand band;
  std::size_t lowest_index = 0;
  double lowest_rough = 0.0;
  const auto open_band = [&](std::size_t i, double lower_m) {
    band = WidthBand{};
    band.lower_m = lower_m;
    lowest_index = i;
    lowest_rough = rough_cv(i);
  };
  const auto close_band = [&](std::size_t i_below, double upper_m, double cv_below, double cv_above, bool limited) {
    band.upper_m = upper_m;
    band.trays_below = trays_at(i_below);
    band.cv_below = cv_below;
    band.cv_above = cv_above;
    band.limited_by_layout = limited;
    band.lowest_cv_trays = trays_at(lowest_index);
    band.lowest_cv = lowest_index == i_below ? cv_below : exact_cv(lowest_index);
    // The first kMaxWidthBands − 1 bands stay; the last slot always holds the latest (widest) one.
    r.bands[r.band_count < kMaxWidthBands ? r.band_count : kMaxWidthBands - 1] = band;
    ++r.band_count;
  };
  bool below = within(0);
  if (below) open_band(0, width_at(0));
  for (std::size_t i = 1; i < count; ++i) {
    const bool now_below = within(i);
    if (now_below == below) {
      if (below) {
        const double rough = rough_cv(i);
        if (rough < lowest_rough) {
          lowest_rough = rough;
          lowest_index = i;
        }
      }
      continue;
    }
    ++r.crossings;
    const double previous_cv = exact_cv(i - 1), cv = exact_cv(i);
    const double lower = width_at(i - 1), upper = width_at(i);
    if (below) {  // leaving the band: CV rises through the target
      const double fraction = std::isfinite(cv) ? (cv_target - previous_cv) / (cv - previous_cv) : 0.0;
      close_band(i - 1, lower + std::clamp(fraction, 0.0, 1.0) * (upper - lower), previous_cv, cv, false);
    } else {  // entering a band: CV falls through the target
      const double fraction = std::isfinite(previous_cv) ? (previous_cv - cv_target) / (previous_cv - cv) : 1.0;
      open_band(i, lower + std::clamp(fraction, 0.0, 1.0) * (upper - lower));
    }
    below = now_below;
  }
  if (below) close_band(count - 1, width_at(count - 1), exact_cv(count - 1), 0.0, true);
  if (r.band_count > 0) {
    const WidthBand& widest = r.bands[r.stored_bands() - 1];
    r.width_m = widest.upper_m;
    r.trays_below = widest.trays_below;
    r.cv_below = widest.cv_below;
    r.cv_above = widest.cv_above;
    r.limited_by_layout = widest.limited_by_layout;
  }
  return r;
}

// The last two CVs evaluated, so that scan_bands' classification and interpolation of one sample do not
// evaluate its bout twice.
template <typename Cv>
class RecentCv {
 public:
  explicit RecentCv(Cv cv) : cv_(cv) {}
  double operator()(std::size_t i) {
    for (int k = 0; k < 2; ++k) {
      if (valid_[k] && index_[k] == i) return value_[k];
    }
    const int slot = next_;
    next_ = 1 - next_;
    valid_[slot] = true;
    index_[slot] = i;
    value_[slot] = cv_(i);
    return value_[slot];
  }

 private:
  Cv cv_;
  bool valid_[2] = {false, false};
  std::size_t index_[2] = {0, 0};
  double value_[2] = {0.0, 0.0};
  int next_ = 0;
};

}  // namespace

namespace {

// working_width's whole-tray scan on any passes.
WorkingWidth scan_whole_trays(const Passes& passes, const TrayLayout& trays, double cv_target) {
  const int widest = trays.tray_count;
  if (widest < 2) return {};
  // CV(W) at every whole-tray width from the narrowest bout of two trays up.
  const auto count = static_cast<std::size_t>(widest - 1);
  const auto trays_at = [](std::size_t i) { return static_cast<int>(i) + 2; };
  RecentCv cv([&](std::size_t i) { return cv_of_window(passes, bout_trays(trays, trays_at(i))); });
  return scan_bands(
      count, [&](std::size_t i) { return trays_at(i) * trays.tray_width_m; },
      [&](std::size_t i) { return cv(i) <= cv_target; }, [&](std::size_t i) { return cv(i); },
      [&](std::size_t i) { return cv(i); }, trays_at, cv_target);
}

}  // namespace

WorkingWidth working_width(std::span<const double> tray_mass_kg, const TrayLayout& trays, Overlap overlap,
                           double cv_target) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "working_width", "tray_mass_kg");
  if (std::isnan(cv_target)) throw std::invalid_argument("working_width: cv_target is NaN");
  return scan_whole_trays(one_pattern(tray_mass_kg, overlap), trays, cv_target);
}

WorkingWidth working_width(std::span<const double> tray_mass_kg, std::span<const double> return_tray_mass_kg,
                           const TrayLayout& trays, double cv_target) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "working_width", "tray_mass_kg");
  detail::require_tray_span(return_tray_mass_kg.size(), trays, "working_width", "return_tray_mass_kg");
  if (std::isnan(cv_target)) throw std::invalid_argument("working_width: cv_target is NaN");
  return scan_whole_trays(to_and_fro_passes(tray_mass_kg, return_tray_mass_kg), trays, cv_target);
}

WorkingWidth working_width_on_curve(std::span<const double> widths_m, std::span<const double> cv,
                                    double cv_target) {
  if (widths_m.size() != cv.size()) {
    throw std::invalid_argument("working_width_on_curve: " + std::to_string(widths_m.size()) + " widths but " +
                                std::to_string(cv.size()) + " CV values");
  }
  if (std::isnan(cv_target)) throw std::invalid_argument("working_width_on_curve: cv_target is NaN");
  for (std::size_t i = 1; i < widths_m.size(); ++i) {
    if (!(widths_m[i] > widths_m[i - 1])) throw std::invalid_argument("working_width_on_curve: widths_m must increase");
  }
  const auto cv_at = [&](std::size_t i) { return cv[i]; };
  return scan_bands(
      widths_m.size(), [&](std::size_t i) { return widths_m[i]; }, [&](std::size_t i) { return cv[i] <= cv_target; },
      cv_at, cv_at, [](std::size_t) { return 0; }, cv_target);
}

namespace {

// FFT length for the linear (not circular) correlations of a T-tray pattern: lags up to 2T − 2.
std::size_t correlation_fft_size(int tray_count) {
  std::size_t size = 2;
  while (size < 2 * static_cast<std::size_t>(tray_count)) size *= 2;
  return size;
}

// In-place radix-2 FFT of `size` complex values stored (re, im) interleaved: X_k = Σ_j x_j e^{∓2πijk/size}
// (− forward, + inverse, unscaled). twiddle holds e^{−2πij/size} for j < size/2, interleaved.
void fft(std::span<double> data, std::size_t size, std::span<const double> twiddle, bool inverse) {
  for (std::size_t i = 1, j = 0; i < size; ++i) {  // bit-reversal permutation
    std::size_t bit = size >> 1;
    for (; (j & bit) != 0; bit >>= 1) j ^= bit;
    j |= bit;
    if (i < j) {
      std::swap(data[2 * i], data[2 * j]);
      std::swap(data[2 * i + 1], data[2 * j + 1]);
    }
  }
  const double sign = inverse ? -1.0 : 1.0;  // the inverse uses the conjugate twiddles
  for (std::size_t length = 2; length <= size; length *= 2) {
    const std::size_t half = length / 2, stride = size / length;
    for (std::size_t start = 0; start < size; start += length) {
      for (std::size_t k = 0; k < half; ++k) {
        const double wr = twiddle[2 * k * stride], wi = sign * twiddle[2 * k * stride + 1];
        double* a = &data[2 * (start + k)];
        double* b = &data[2 * (start + k + half)];
        const double vr = b[0] * wr - b[1] * wi, vi = b[0] * wi + b[1] * wr;
        b[0] = a[0] - vr;
        b[1] = a[1] - vi;
        a[0] += vr;
        a[1] += vi;
      }
    }
  }
}

// CV(n)² of one overlap from the correlations (metrics.hpp, working_widths) of the pattern scaled to total
// 1, interleaved as the inverse FFT leaves them: R(lag) = correlations[2·lag] for lag < T and
// C(s) = correlations[2·s + 1] for s <= 2T − 2.
double fast_cv_squared(std::span<const double> correlations, long t, long n, Overlap overlap) {
  const auto r = [&](long lag) { return correlations[2 * static_cast<std::size_t>(lag)]; };
  const auto c = [&](long s) { return correlations[2 * static_cast<std::size_t>(s) + 1]; };
  double squares = r(0);
  if (overlap == Overlap::kRacetrack) {
    for (long lag = n; lag < t; lag += n) squares += 2.0 * r(lag);
  } else {
    for (long lag = 2 * n; lag < t; lag += 2 * n) squares += 2.0 * r(lag);
    for (long shift = n; shift < t; shift += 2 * n) squares += c(t - 1 + shift) + c(t - 1 - shift);  // odd d
  }
  const double bout = static_cast<double>(n);
  return bout * (bout * squares - 1.0) / (bout - 1.0);
}

}  // namespace

std::size_t working_widths_scratch_size(int tray_count) {
  if (tray_count < 2) return 0;
  const std::size_t size = correlation_fft_size(tray_count);
  // Complex data, the twiddles, and two bouts (n + 1 <= T + 1 trays each: a to-and-fro window with a
  // return pass of its own) for the exact evaluations.
  return 2 * size + size + 2 * (static_cast<std::size_t>(tray_count) + 1);
}

namespace {

// working_widths' scratch: the FFT's complex data, its twiddles and the exact evaluations' window.
struct Spectra {
  std::size_t size = 0;
  std::span<double> data, twiddle, window;
};

Spectra spectra_in(std::span<double> scratch, int widest) {
  Spectra s;
  s.size = correlation_fft_size(widest);
  s.data = scratch.first(2 * s.size);
  s.twiddle = scratch.subspan(2 * s.size, s.size);
  s.window = scratch.subspan(3 * s.size, 2 * (static_cast<std::size_t>(widest) + 1));
  // e^{−2πij/size}: the second quarter from the first (multiplying by e^{−iπ/2} = −i maps (c, s) to
  // (s, −c)), so only size/4 cos/sin pairs are evaluated.
  const std::size_t quarter = s.size / 4;
  for (std::size_t j = 0; j < std::max<std::size_t>(quarter, 1); ++j) {
    const double angle = -2.0 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(s.size);
    s.twiddle[2 * j] = std::cos(angle);
    s.twiddle[2 * j + 1] = std::sin(angle);
  }
  for (std::size_t j = quarter; j < s.size / 2; ++j) {
    s.twiddle[2 * j] = s.twiddle[2 * (j - quarter) + 1];
    s.twiddle[2 * j + 1] = -s.twiddle[2 * (j - quarter)];
  }
  return s;
}

void inverse_scaled(const Spectra& s) {
  fft(s.data, s.size, s.twiddle, true);
  const double scale = 1.0 / static_cast<double>(s.size);
  for (double& v : s.data) v *= scale;
}

// The pattern's autocorrelation R (real parts) and self-convolution C (imaginary parts), the pattern
// scaled to total 1.
void pattern_correlations(std::span<const double> pattern_kg, double total_kg, const Spectra& s) {
  std::fill(s.data.begin(), s.data.end(), 0.0);
  for (std::size_t i = 0; i < pattern_kg.size(); ++i) s.data[2 * i] = pattern_kg[i] / total_kg;
  fft(s.data, s.size, s.twiddle, false);
  // With X = FFT(p) for a real p, |X|² is the spectrum of R and X² that of C; both are Hermitian, so one
  // inverse FFT of |X|² + i·X² returns R in the real part and C in the imaginary part.
  for (std::size_t k = 0; k < s.size; ++k) {
    const double a = s.data[2 * k], b = s.data[2 * k + 1];
    s.data[2 * k] = a * a + b * b - 2.0 * a * b;
    s.data[2 * k + 1] = a * a - b * b;
  }
  inverse_scaled(s);
}

// For an outgoing pattern p and a return pattern r (both times `scale`): R_pp + R_rr (real parts) and the
// cross-convolution C_pr(s) = Σ_x p(x) r(s − x) (imaginary parts). One forward FFT of p + i·r gives both
// spectra, P_k = (Z_k + conj Z_{N−k}) / 2 and Q_k = (Z_k − conj Z_{N−k}) / 2i; |P|² + |Q|² and P·Q are
// Hermitian, so one inverse FFT of |P|² + |Q|² + i·P·Q returns the two real sequences.
void two_way_correlations(std::span<const double> outgoing_kg, std::span<const double> return_kg, double scale,
                          const Spectra& s) {
  std::fill(s.data.begin(), s.data.end(), 0.0);
  for (std::size_t i = 0; i < outgoing_kg.size(); ++i) {
    s.data[2 * i] = outgoing_kg[i] * scale;
    s.data[2 * i + 1] = return_kg[i] * scale;
  }
  fft(s.data, s.size, s.twiddle, false);
  for (std::size_t k = 0; k <= s.size / 2; ++k) {
    const std::size_t j = (s.size - k) % s.size;
    const double zr = s.data[2 * k], zi = s.data[2 * k + 1], wr = s.data[2 * j], wi = s.data[2 * j + 1];
    const double pr = 0.5 * (zr + wr), pi = 0.5 * (zi - wi), qr = 0.5 * (zi + wi), qi = 0.5 * (wr - zr);
    const double power = pr * pr + pi * pi + qr * qr + qi * qi;
    const double br = pr * qr - pi * qi, bi = pr * qi + pi * qr;  // P_k·Q_k; at N − k its conjugate
    s.data[2 * k] = power - bi;
    s.data[2 * k + 1] = br;
    s.data[2 * j] = power + bi;
    s.data[2 * j + 1] = br;
  }
  inverse_scaled(s);
}

// CV(n)² to-and-fro with a return pass of its own, from two_way_correlations of p and r scaled by
// 2 / (M_p + M_r) (so the window's mean tray is 1/n). Over the window of two bouts (one period):
// pass 0 against even passes d·n away gives R_pp(d·n), pass 1 against them R_rr(d·n), and each against
// the odd passes C_pr(T − 1 ± d·n), so Σ_window P² = Σ_{d even} (R_pp + R_rr)(d·n)
// + 2 Σ_{d odd > 0} [C_pr(T − 1 + d·n) + C_pr(T − 1 − d·n)], and with the pooled variance (bout_moments)
// CV² = n (n Σ P² − 2) / (2 (n − 1)). With r = p this is the one-pattern to-and-fro CV².
double fast_two_way_cv_squared(std::span<const double> correlations, long t, long n) {
  const auto e = [&](long lag) { return correlations[2 * static_cast<std::size_t>(lag)]; };
  const auto c = [&](long s) { return correlations[2 * static_cast<std::size_t>(s) + 1]; };
  double squares = e(0);
  for (long lag = 2 * n; lag < t; lag += 2 * n) squares += 2.0 * e(lag);
  for (long shift = n; shift < t; shift += 2 * n) squares += 2.0 * (c(t - 1 + shift) + c(t - 1 - shift));
  const double bout = static_cast<double>(n);
  return bout * (bout * squares - 2.0) / (2.0 * (bout - 1.0));
}

// working_width's rule over whole-tray widths with each width classified by its fast CV² and, where that
// is within the FFT's rounding of the target, by the exact CV (working_widths in metrics.hpp).
template <typename FastCvSquared>
WorkingWidth fast_scan(const Passes& passes, const TrayLayout& trays, double cv_target, const Spectra& s,
                       FastCvSquared fast_cv_squared) {
  const long t = trays.tray_count;
  // Rounding of the correlations: each is within about ε·log₂(size) of Σ p² <= 1, and CV² sums up to
  // 2T/n of them times n: |ΔCV²| ≲ 2·ε·T·log₂(size). The guard band is 128 times that.
  const double guard = 256.0 * std::numeric_limits<double>::epsilon() * static_cast<double>(t) *
                       std::log2(static_cast<double>(s.size));
  const double target_squared = cv_target * cv_target;
  int exact_left = kExactWidthEvaluations;
  auto exact_cv = [&](long n) { return cv_of_window(passes, bout_trays(trays, static_cast<int>(n)), s.window); };
  auto within = [&](long n) {
    const double cv_squared = fast_cv_squared(n);
    if (std::abs(cv_squared - target_squared) <= guard && exact_left > 0) {
      --exact_left;
      return exact_cv(n) <= cv_target;
    }
    return cv_target >= 0.0 && cv_squared <= target_squared;
  };
  // working_width's rule (scan_bands) with these classifications; sample i is a bout of i + 2 trays.
  const auto trays_at = [](std::size_t i) { return static_cast<int>(i) + 2; };
  RecentCv exact([&](std::size_t i) { return exact_cv(trays_at(i)); });
  return scan_bands(
      static_cast<std::size_t>(t - 1), [&](std::size_t i) { return trays_at(i) * trays.tray_width_m; },
      [&](std::size_t i) { return within(trays_at(i)); }, exact,
      [&](std::size_t i) { return std::sqrt(std::max(fast_cv_squared(trays_at(i)), 0.0)); }, trays_at, cv_target);
}

// Every tray finite and >= 0 (the FFT path's condition), and the total.
bool plain_pattern(std::span<const double> pattern_kg, double& total_kg) {
  bool plain = true;
  total_kg = 0.0;
  for (double m : pattern_kg) {
    plain = plain && std::isfinite(m) && m >= 0.0;
    total_kg += m;
  }
  return plain && std::isfinite(total_kg);
}

void require_widths_input(std::size_t pattern_size, const TrayLayout& trays, double cv_target, std::size_t scratch_size,
                          const char* span_name) {
  detail::require_tray_span(pattern_size, trays, "working_widths", span_name);
  if (std::isnan(cv_target)) throw std::invalid_argument("working_widths: cv_target is NaN");
  if (trays.tray_count >= 2 && scratch_size < working_widths_scratch_size(trays.tray_count)) {
    throw std::invalid_argument("working_widths: scratch has " + std::to_string(scratch_size) + " values, needs " +
                                std::to_string(working_widths_scratch_size(trays.tray_count)));
  }
}

}  // namespace

WorkingWidths working_widths(std::span<const double> tray_mass_kg, const TrayLayout& trays, double cv_target,
                             std::span<double> scratch) {
  require_widths_input(tray_mass_kg.size(), trays, cv_target, scratch.size(), "tray_mass_kg");
  if (trays.tray_count < 2) return {};
  double total_kg = 0.0;
  if (!plain_pattern(tray_mass_kg, total_kg)) {  // the total is not the bout's, or a bout may be empty
    return {working_width(tray_mass_kg, trays, Overlap::kToAndFro, cv_target),
            working_width(tray_mass_kg, trays, Overlap::kRacetrack, cv_target)};
  }
  if (!(total_kg > 0.0)) return {};  // every bout empty: CV infinite at every width, as working_width
  const Spectra s = spectra_in(scratch, trays.tray_count);
  pattern_correlations(tray_mass_kg, total_kg, s);
  const long t = trays.tray_count;
  auto fast = [&](Overlap overlap) { return [&s, t, overlap](long n) { return fast_cv_squared(s.data, t, n, overlap); }; };
  return {fast_scan(one_pattern(tray_mass_kg, Overlap::kToAndFro), trays, cv_target, s, fast(Overlap::kToAndFro)),
          fast_scan(one_pattern(tray_mass_kg, Overlap::kRacetrack), trays, cv_target, s, fast(Overlap::kRacetrack))};
}

WorkingWidths working_widths(std::span<const double> tray_mass_kg, std::span<const double> return_tray_mass_kg,
                             const TrayLayout& trays, double cv_target, std::span<double> scratch) {
  require_widths_input(tray_mass_kg.size(), trays, cv_target, scratch.size(), "tray_mass_kg");
  require_widths_input(return_tray_mass_kg.size(), trays, cv_target, scratch.size(), "return_tray_mass_kg");
  if (return_tray_mass_kg.data() == tray_mass_kg.data()) return working_widths(tray_mass_kg, trays, cv_target, scratch);
  if (trays.tray_count < 2) return {};
  double outgoing_kg = 0.0, return_kg = 0.0;
  const bool plain = plain_pattern(tray_mass_kg, outgoing_kg) && plain_pattern(return_tray_mass_kg, return_kg);
  if (!plain) {
    return {working_width(tray_mass_kg, return_tray_mass_kg, trays, cv_target),
            working_width(tray_mass_kg, trays, Overlap::kRacetrack, cv_target)};
  }
  WorkingWidths r;
  const Spectra s = spectra_in(scratch, trays.tray_count);
  const long t = trays.tray_count;
  if (outgoing_kg > 0.0) {
    pattern_correlations(tray_mass_kg, outgoing_kg, s);
    r.racetrack = fast_scan(one_pattern(tray_mass_kg, Overlap::kRacetrack), trays, cv_target, s,
                            [&](long n) { return fast_cv_squared(s.data, t, n, Overlap::kRacetrack); });
  }
  if (outgoing_kg + return_kg > 0.0) {
    two_way_correlations(tray_mass_kg, return_tray_mass_kg, 2.0 / (outgoing_kg + return_kg), s);
    r.to_and_fro = fast_scan(to_and_fro_passes(tray_mass_kg, return_tray_mass_kg), trays, cv_target, s,
                             [&](long n) { return fast_two_way_cv_squared(s.data, t, n); });
  }
  return r;
}

double effective_working_width(std::span<const double> tray_mass_kg, const TrayLayout& trays,
                               Overlap overlap, double cv_target) {
  detail::require_tray_span(tray_mass_kg.size(), trays, "effective_working_width", "tray_mass_kg");
  if (std::isnan(cv_target)) throw std::invalid_argument("effective_working_width: cv_target is NaN");
  return working_width(tray_mass_kg, trays, overlap, cv_target).width_m;
}

}  // namespace spread::metrics
