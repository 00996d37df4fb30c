#pragma once
// Spread metrics (docs/design.md §3): transverse distribution in trays, overlap at a bout width
// (to-and-fro, racetrack), CV(W), effective working width, throw width, and the seed's R̄ and ξ
// (Eqs. 51–52). Functions taking spans do not allocate: the C API calls them in its control loop.
// Definitions, tray convention and edge cases: docs/metrics.md.
//
// Errors: programming errors (span sizes that do not match, tray width <= 0, negative or non-finite
// bout widths, mass fraction outside (0, 1]) throw std::invalid_argument naming the input; degenerate
// data (no landings, zero total mass, W wider than the layout) return the defined values documented on
// each function.
#include <cstddef>
#include <span>
#include <vector>

namespace spread::metrics {

// Trays across the driving direction, symmetric about the machine centre line x = 0:
// tray k covers [left_edge_m() + k·tray_width_m, left_edge_m() + (k+1)·tray_width_m).
struct TrayLayout {
  double tray_width_m = 0.5;   // ISO 5690 / EN 13739 practice
  int tray_count = 0;
  double left_edge_m() const { return -0.5 * tray_width_m * tray_count; }
  double centre_m(int k) const { return left_edge_m() + (k + 0.5) * tray_width_m; }
};
// The smallest symmetric layout whose trays cover [-half_extent_m, half_extent_m].
TrayLayout tray_layout_covering(double half_extent_m, double tray_width_m);

// One disc, or two counter-rotating discs: the samples given are those of the LEFT disc relative to
// its own centre, which sits at x = -disc_spacing_m / 2; the right disc is their mirror image x → -x
// about the centre line (docs/design.md §3). One disc sits at x = 0.
struct MachineLayout {
  int disc_count = 2;          // 1 or 2
  double disc_spacing_m = 0.0; // centre-to-centre, lateral; two discs only
};

enum class Overlap { kToAndFro, kRacetrack };

// Adds each landing's mass to its tray (machine frame; mirrored for the second disc). Landings outside
// the layout are counted in the returned "lost" mass (kg) and not added.
// The trays are NOT cleared first (so batches can be accumulated); tray_mass_kg.size() must equal
// trays.tray_count. With two discs every sample lands twice (left disc, mirrored right disc), each time
// with its full mass. Non-finite x counts as lost. Tray k is the half-open [edge_k, edge_k+1).
double accumulate_transverse(std::span<const double> x_m, std::span<const double> mass_kg,
                             const MachineLayout& machine, const TrayLayout& trays,
                             std::span<double> tray_mass_kg);

// Kernel density estimate of the transverse distribution: each landing's mass is spread over
// [x − h, x + h] with the Epanechnikov kernel K(u) = 3/4 (1 − u²), u = (x' − x)/h, and each tray receives
// the kernel's integral over it (exact: the kernel CDF is 1/2 + u (3 − u²)/4). A Monte Carlo pattern from
// N landings is noisy at the tray scale (a bout tray of a 12 m bout holds ~N/24 landings); the kernel
// trades that noise for a bias of order h² f''. h = 0 drops each landing into its tray
// (accumulate_transverse). Landings are already in the machine frame. Mass beyond the outer tray edges
// (and non-finite x) is returned as lost. Adds to tray_mass_kg (not cleared). Does not allocate.
double accumulate_transverse_kernel(std::span<const double> x_m, std::span<const double> mass_kg,
                                    const TrayLayout& trays, double kernel_half_width_m,
                                    std::span<double> tray_mass_kg);
// The same, and a kernel of at least kWideKernelTrays tray widths (wide_kernel.hpp) binned at a cost
// independent of its width when `scratch` holds wide_kernel_scratch_size(trays) values (within 1e-12 of
// the tray-by-tray sum).
double accumulate_transverse_kernel(std::span<const double> x_m, std::span<const double> mass_kg,
                                    const TrayLayout& trays, double kernel_half_width_m,
                                    std::span<double> tray_mass_kg, std::span<double> scratch);
namespace detail {
// accumulate_transverse_kernel's tray-by-tray binning with the landings taken `lanes` at a time: 1 (one by
// one), 4 (SSE or AVX registers) or 8 (AVX-512 ones where the processor has them, else 4), as the
// function itself takes them (the widest the processor has, for kernels a few trays wide). The same bits
// every way; for the tests that show it.
double accumulate_transverse_kernel_in_lanes(std::span<const double> x_m, std::span<const double> mass_kg,
                                             const TrayLayout& trays, double kernel_half_width_m,
                                             std::span<double> tray_mass_kg, std::size_t lanes);
}  // namespace detail
// The kernel's CDF at u = (x' − x)/h: 0 below −1, 1 above 1. Inline: the kernel binning and the standard
// errors call it once per tray a landing's kernel touches.
inline double epanechnikov_cdf(double u) {
  if (!(u > -1.0)) return 0.0;
  if (!(u < 1.0)) return 1.0;
  return 0.5 + 0.25 * u * (3.0 - u * u);
}

// Overlap on true trays (docs/metrics.md "Overlap at a bout width W"). A bout width W is a whole number
// n = round(W / w) >= 1 of trays, so every pass is the pattern shifted by whole trays and the overlapped
// distribution lives on the pattern's own tray grid: no tray is split or averaged. The bout [-W/2, W/2]
// holds n whole grid trays when n - T is even (T = pattern trays); otherwise each bout edge cuts a grid
// tray in half and those two trays count half each (exact: the overlapped distribution is periodic,
// racetrack, or mirror-symmetric about every bout edge, to-and-fro).
//
// Bouts up to this many grid trays are built in a stack buffer when the caller gives no scratch; wider
// ones are gathered tray by tray. Small on purpose: the C API states its stack need (docs/c-api.md
// "Stack"), and callers that evaluate wide bouts pass a scratch span instead (the overloads below).
inline constexpr int kStackBoutTrays = 128;  // 1 KiB of stack

// Number of trays of a bout of width W: round(W / tray_width), at least 1.
int bout_tray_count(const TrayLayout& trays, double bout_width_m);

// The grid trays a bout of n trays touches: grid_trays = n (edges on tray edges) or n + 1 (cut_edges:
// the first and last are cut in half by the bout edges). Grid index g covers
// [left_edge_m() + g·w, left_edge_m() + (g+1)·w) and may lie outside [0, T).
struct BoutTrays {
  int bout_trays = 1;   // n
  int first_tray = 0;   // grid index of the first tray touched
  int grid_trays = 1;   // n, or n + 1 with cut_edges
  bool cut_edges = false;
};
BoutTrays bout_trays(const TrayLayout& trays, int bout_tray_count);

// Coefficient of variation (fraction, 0.1 = 10 %) of the overlapped distribution over one bout at bout
// width W: CV = s / x̄ with x̄ = Σ w_j P_j / n and s² = Σ w_j (P_j − x̄)² / (n − 1), weights w_j = 1, or 1/2
// for a cut edge tray (all 1: the sample standard deviation). Passes: the pattern placed at every multiple
// of W; racetrack = shifted copies, to-and-fro = every other pass mirrored (x → -x).
// Returns 0 for a one-tray bout (no spread), +infinity when the bout holds no mass (nothing is uniform
// about an empty bout; it fails every CV target). W wider than the layout is allowed: the empty trays
// of the bout count.
double cv_at_width(std::span<const double> tray_mass_kg, const TrayLayout& trays, double bout_width_m,
                   Overlap overlap);
// The same for a bout of exactly `bout_tray_count` trays.
double cv_at_trays(std::span<const double> tray_mass_kg, const TrayLayout& trays, int bout_tray_count,
                   Overlap overlap);

// ∂CV/∂(mass of pattern tray i) (1/kg) at a bout of `bout_tray_count` trays, into gradient_per_kg (size T):
// the sensitivity the delta-method standard error of a predicted CV needs. Zero when the CV is infinite.
void cv_gradient(std::span<const double> tray_mass_kg, const TrayLayout& trays, int bout_tray_count,
                 Overlap overlap, std::span<double> gradient_per_kg);
// The same two with a caller's scratch for the bout: used when it holds at least
// bout_trays(trays, bout_tray_count).grid_trays values (n + 1 always suffices), otherwise as above.
// Bit for bit the same results.
double cv_at_trays(std::span<const double> tray_mass_kg, const TrayLayout& trays, int bout_tray_count,
                   Overlap overlap, std::span<double> scratch);
void cv_gradient(std::span<const double> tray_mass_kg, const TrayLayout& trays, int bout_tray_count,
                 Overlap overlap, std::span<double> gradient_per_kg, std::span<double> scratch);

// To-and-fro with a return pass of its own. The return pass meets a wind from the other side (a wind from
// the left on the way out comes from the right on the way back), so in wind its pattern is not the
// outgoing one: `return_tray_mass_kg` is the return pass's pattern in its own machine frame (on the same
// layout), laid down mirrored on the odd passes. The overlapped distribution then repeats every two bouts
// instead of being symmetric about every bout edge, so the CV is taken over both bouts with the variance
// pooled: x̄ = Σ w_j P_j / 2n, s² = Σ w_j (P_j − x̄)² / (2(n − 1)) — the one-bout CV when the return
// pattern is the outgoing one. A return span at the outgoing span's address IS the outgoing pattern (the
// one-pattern functions above, bit for bit). The gradient goes to each pattern's own trays
// (return_gradient_per_kg may be empty: left out); scratch as above, for two bouts.
double cv_at_trays(std::span<const double> tray_mass_kg, std::span<const double> return_tray_mass_kg,
                   const TrayLayout& trays, int bout_tray_count, std::span<double> scratch);
void cv_gradient(std::span<const double> tray_mass_kg, std::span<const double> return_tray_mass_kg,
                 const TrayLayout& trays, int bout_tray_count, std::span<double> gradient_per_kg,
                 std::span<double> return_gradient_per_kg, std::span<double> scratch);
// The two bouts' overlapped distribution (the bout centred on an outgoing pass, then the one centred on the
// return pass beside it): window_mass_kg.size() must be 2 · bout_trays(...).grid_trays.
void overlapped_profile(std::span<const double> tray_mass_kg, std::span<const double> return_tray_mass_kg,
                        const TrayLayout& trays, double bout_width_m, std::span<double> window_mass_kg);

// The overlapped distribution itself: mass per grid tray (kg) over the trays the bout touches, summed over
// all passes. bout_mass_kg.size() must be bout_trays(trays, bout_tray_count(trays, W)).grid_trays; entry j
// is grid tray first_tray + j (with cut_edges, entries 0 and grid_trays - 1 straddle the bout edges).
void overlapped_profile(std::span<const double> tray_mass_kg, const TrayLayout& trays, double bout_width_m,
                        Overlap overlap, std::span<double> bout_mass_kg);

// CV(W) at each width in `widths_m`, into `cv_out` (same size).
void cv_curve(std::span<const double> tray_mass_kg, const TrayLayout& trays,
              std::span<const double> widths_m, Overlap overlap, std::span<double> cv_out);

// Effective working width (docs/metrics.md "Effective working width"): CV(W) is evaluated at every
// whole-tray width from 2 trays to the layout width. A band is a run of widths with CV <= target; its
// ends are interpolated linearly in CV between the two whole-tray widths around each crossing (an end at
// the narrowest bout or at the layout width is that width). The working width is the upper end of the
// widest band: the largest bout width whose CV meets the target (ASAE S341.4 "effective swath width";
// docs/metrics.md gives the sources and why later bands are not skipped).
struct WidthBand {
  double lower_m = 0.0;          // narrowest width of the band (2 trays when the band starts there)
  double upper_m = 0.0;          // widest width of the band
  int trays_below = 0;           // the upper crossing lies between trays_below and trays_below + 1 trays
  double cv_below = 0.0;         // CV at trays_below trays (<= target)
  double cv_above = 0.0;         // CV at trays_below + 1 trays (> target; may be +inf); 0 when limited
  bool limited_by_layout = false;  // CV stays within the target up to the whole layout (upper = layout)
  int lowest_cv_trays = 0;       // the band's whole-tray width of lowest CV
  double lowest_cv = 0.0;        // and that CV
};
// Bands kept: the first kMaxWidthBands − 1 and the widest (a spreader pattern has one to three).
inline constexpr int kMaxWidthBands = 4;
struct WorkingWidth {
  double width_m = 0.0;          // the widest band's upper end; 0: no width meets the target
  int crossings = 0;             // times CV(W) crosses the target between 2 trays and the layout width
  int trays_below = 0;           // of the widest band (WidthBand::trays_below)
  double cv_below = 0.0;         // of the widest band
  double cv_above = 0.0;         // of the widest band
  bool limited_by_layout = false;  // of the widest band
  int band_count = 0;            // bands found; bands[0 .. min(band_count, kMaxWidthBands)) are kept
  WidthBand bands[kMaxWidthBands];
  // The first band's upper end: the working width read as the first rise above the target (what this
  // library reported before the widest band became the rule; 0 when no band).
  double first_band_upper_m() const { return band_count > 0 ? bands[0].upper_m : 0.0; }
  int stored_bands() const { return band_count < kMaxWidthBands ? band_count : kMaxWidthBands; }
};
WorkingWidth working_width(std::span<const double> tray_mass_kg, const TrayLayout& trays, Overlap overlap,
                           double cv_target);
// The to-and-fro working width with a return pass of its own (cv_at_trays with return_tray_mass_kg).
WorkingWidth working_width(std::span<const double> tray_mass_kg, std::span<const double> return_tray_mass_kg,
                           const TrayLayout& trays, double cv_target);
// The same rule on a CV(W) curve already sampled at increasing widths (plots, measured tray tests):
// `trays_below` is left 0. Throws std::invalid_argument when the sizes differ or widths do not increase.
WorkingWidth working_width_on_curve(std::span<const double> widths_m, std::span<const double> cv,
                                    double cv_target);

// Both working widths at once in O(T log T) instead of working_width's O(T²) (T = tray count; 4,000
// trays of 5 cm over ±100 m took 130 ms), with the same results. The sum of squares of the overlapped
// distribution over one bout is a sum of the pattern's autocorrelation R and self-convolution C at
// multiples of the bout: with n trays per bout and the pattern p,
//   racetrack (period n):            Σ_bout P² = Σ_d R(d·n)
//   to-and-fro (period 2n, mirrored): Σ_bout P² = Σ_{d even} R(d·n) + Σ_{d odd} C(T − 1 + d·n)
// (pass 0 against an unmirrored pass d·n away gives R(d·n), against a mirrored one C(T − 1 + d·n); the
// half-weight cut edge trays make one bout exactly half of a to-and-fro period or one racetrack period,
// as for cv_at_trays). R and C for all lags come from one FFT pair, and the sums over d are harmonic:
// Σ_n T/n = O(T log T). Then CV² = n (n Σ_bout P² / M² − 1) / (n − 1), M the total mass.
// The FFT's rounding (about ε·T·log₂T in CV²) only matters where CV(n) is within that of the target:
// there, and at the two widths around each crossing (interpolation, cv_below, cv_above), CV is
// evaluated exactly as cv_at_trays does — at most kExactWidthEvaluations widths per overlap, beyond
// which the fast value decides (a CV curve touching the target at so many widths to 1e-9 is not a
// spreader pattern). So the crossings, the widths and cv_below/cv_above are those of working_width.
// Trays with a negative or non-finite mass fall back to working_width. Does not allocate: `scratch`
// must hold working_widths_scratch_size(trays.tray_count) doubles (std::invalid_argument otherwise).
struct WorkingWidths {
  WorkingWidth to_and_fro;
  WorkingWidth racetrack;
};
inline constexpr int kExactWidthEvaluations = 64;
std::size_t working_widths_scratch_size(int tray_count);
WorkingWidths working_widths(std::span<const double> tray_mass_kg, const TrayLayout& trays, double cv_target,
                             std::span<double> scratch);
// Both, to-and-fro with a return pass of its own (cv_at_trays with return_tray_mass_kg): the window of two
// bouts holds Σ P² = Σ_{d even} (R_pp + R_rr)(d·n) + 2 Σ_{d odd > 0} [C_pr(T − 1 + d·n) + C_pr(T − 1 − d·n)]
// (R_pp, R_rr the patterns' autocorrelations, C_pr(s) = Σ_x p(x) r(s − x)), all from one FFT pair; the
// racetrack width is the outgoing pattern's. Same scratch.
WorkingWidths working_widths(std::span<const double> tray_mass_kg, std::span<const double> return_tray_mass_kg,
                             const TrayLayout& trays, double cv_target, std::span<double> scratch);

// working_width(...).width_m. Returns 0 when no width meets the target (also for zero mass or fewer than
// 2 trays).
double effective_working_width(std::span<const double> tray_mass_kg, const TrayLayout& trays,
                               Overlap overlap, double cv_target);

// Lateral extent (m) between the (1-f)/2 and (1+f)/2 mass quantiles, mass uniform within each tray.
// Returns 0 when the trays hold no mass. With mass_fraction = 1 it is the extent of the non-empty trays.
double throw_width(std::span<const double> tray_mass_kg, const TrayLayout& trays, double mass_fraction = 0.99);
// The two quantiles themselves (m, machine frame); {0, 0} when the trays hold no mass.
struct ThrowExtent {
  double left_m = 0.0, right_m = 0.0;
};
ThrowExtent throw_extent(std::span<const double> tray_mass_kg, const TrayLayout& trays, double mass_fraction = 0.99);

// Seed Eqs. 51–52 in the limit of small ground cells: R̄ = Σ m_i r_i / Σ m_i and
// ξ = Σ m_i |r_i − R̄| / Σ m_i, r measured from `centre` (the disc centre) in the ground plane.
// (Eq. 52 prints r̄; it is the R̄ of Eq. 51.) Landings with a NaN coordinate (not landed) are left out.
// No landings or zero total mass → {0, 0}.
struct RadialStats {
  double mean_radius_m = 0.0;   // R̄, Eq. 51
  double radial_width_m = 0.0;  // ξ, Eq. 52
};
RadialStats radial_statistics(std::span<const double> x_m, std::span<const double> y_m,
                              std::span<const double> mass_kg, double centre_x_m = 0.0,
                              double centre_y_m = 0.0);

// Ground pattern on a regular grid (mass per area, kg/m²); for plots and the DEM's full process.
struct GroundPattern {
  double x0_m = 0.0, y0_m = 0.0;   // lower-left corner
  double cell_m = 0.1;
  int nx = 0, ny = 0;
  std::vector<double> mass_kg;     // row-major, index iy * nx + ix
  double density_kg_m2(int ix, int iy) const { return mass_kg[static_cast<std::size_t>(iy * nx + ix)] / (cell_m * cell_m); }
};
// Pattern of the whole machine (both discs) on a grid fitted to the landings (plus a margin).
// Machine frame as accumulate_transverse (left disc sample x → x - spacing/2, right disc → spacing/2 - x,
// y unchanged). The grid is aligned to multiples of cell_m, symmetric in x about the centre line, with a
// one-cell margin round the landings; non-finite landings are skipped. No finite landing → nx = ny = 0.
// Throws std::invalid_argument when cell_m <= 0 or the grid would exceed 16 million cells.
GroundPattern ground_pattern(std::span<const double> x_m, std::span<const double> y_m,
                             std::span<const double> mass_kg, const MachineLayout& machine, double cell_m);

}  // namespace spread::metrics
