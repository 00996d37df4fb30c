#pragma once
// Spread metrics (DESIGN.md §3): transverse distribution in trays, overlap at a bout width
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
// about the centre line (DESIGN.md §3). One disc sits at x = 0.
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

// Coefficient of variation (fraction, 0.1 = 10 %) of the overlapped distribution over one bout
// [-W/2, W/2] at bout width W (sample standard deviation / mean over the trays in the bout).
// Passes: the pattern placed at every multiple of W; racetrack = shifted copies, to-and-fro = every
// other pass mirrored (x → -x). W is rounded to a whole number of trays (>= 1).
// Returns 0 for a one-tray bout (no spread), +infinity when the bout holds no mass (nothing is uniform
// about an empty bout; it fails every CV target). W wider than the layout is allowed: the empty trays
// of the bout count.
double cv_at_width(std::span<const double> tray_mass_kg, const TrayLayout& trays, double bout_width_m,
                   Overlap overlap);

// Number of trays of a bout of width W on the tray grid: round(W / tray_width), at least 1.
int bout_tray_count(const TrayLayout& trays, double bout_width_m);

// The overlapped distribution itself: mass per tray (kg) of the bout [-W/2, W/2], summed over all passes
// (the tray grid of the bout starts at -W/2). bout_mass_kg.size() must be bout_tray_count(trays, W).
// When the bout and pattern tray grids are offset by half a tray (tray counts of different parity), each
// pattern tray gives half its mass to each bout tray it straddles (mass uniform within trays).
void overlapped_profile(std::span<const double> tray_mass_kg, const TrayLayout& trays, double bout_width_m,
                        Overlap overlap, std::span<double> bout_mass_kg);

// CV(W) at each width in `widths_m`, into `cv_out` (same size).
void cv_curve(std::span<const double> tray_mass_kg, const TrayLayout& trays,
              std::span<const double> widths_m, Overlap overlap, std::span<double> cv_out);

// Effective working width: the largest W on the tray grid (2 trays up to the layout width) with
// CV(W) <= cv_target (fraction). Returns 0 when no width meets the target (also for zero mass or
// fewer than 2 trays).
double effective_working_width(std::span<const double> tray_mass_kg, const TrayLayout& trays,
                               Overlap overlap, double cv_target);

// Lateral extent (m) between the (1-f)/2 and (1+f)/2 mass quantiles, mass uniform within each tray.
// Returns 0 when the trays hold no mass. With mass_fraction = 1 it is the extent of the non-empty trays.
double throw_width(std::span<const double> tray_mass_kg, const TrayLayout& trays, double mass_fraction = 0.99);

// Seed Eqs. 51–52 in the limit of small ground cells: R̄ = Σ m_i r_i / Σ m_i and
// ξ = Σ m_i |r_i − R̄| / Σ m_i, r measured from `centre` (the disc centre) in the ground plane.
// (Eq. 52 prints r̄; it is the R̄ of Eq. 51.) No landings or zero total mass → {0, 0}.
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
