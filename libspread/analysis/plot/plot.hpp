#pragma once
// PNG plots of spread results (cairo): the ground pattern as a heat map, the transverse distribution in
// trays (optionally with a second series and the overlapped profile at a bout width), and the CV(W)
// curves with the target line and the effective working widths. Every writer throws
// std::runtime_error naming the path when the file cannot be written, and std::invalid_argument naming
// the offending input when the data cannot be plotted (empty, mismatched sizes, non-finite).
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::plot {

// What every writer throws (std::runtime_error, after the path) in a build configured without cairo.
inline constexpr char kWithoutPlots[] = "built without plots (SPREAD_WITH_PLOTS=OFF)";

// Every PNG is this size (pixels), so callers and tests know what to expect.
inline constexpr int kImageWidth_px = 1000;
inline constexpr int kImageHeight_px = 650;

// What the masses handed to a writer are: kilograms, or fractions of the total mass (the axis then
// shows percent of the mass instead of kg/g/mg).
enum class MassUnits { kKilograms, kFraction };

// Heat map of mass per area (kg/m²) with a colour bar, axes in metres (x lateral, y driving
// direction), and the disc centres of `machine` marked (two discs at x = ∓spacing/2, one at x = 0,
// all at y = 0 — the frame ground_pattern() uses).
void write_ground_pattern_png(const metrics::GroundPattern& pattern, const std::string& path,
                              const std::string& title,
                              const metrics::MachineLayout& machine = metrics::MachineLayout{},
                              MassUnits units = MassUnits::kKilograms);

// Optional extras for the transverse-distribution plot.
struct TransverseOptions {
  std::string series_label = "predicted";          // legend entry of the main series
  std::span<const double> second_tray_mass_kg{};   // e.g. a tray test; empty = none; same layout
  std::string second_label = "measured";
  double bout_width_m = 0.0;                       // > 0: also draw the overlapped profile over one bout
  metrics::Overlap overlap = metrics::Overlap::kToAndFro;  // how that profile is overlapped
  MassUnits units = MassUnits::kKilograms;         // of both series
  // With bout_width_m > 0: the CV the legend states and the band below show. NaN: metrics::cv_at_width of
  // the main series (a caller whose CV leaves missing trays out passes its own).
  // With missing_trays, a NaN bout_cv is no CV at all (too few trays of the bout were read): the legend
  // says so rather than count the missing trays as empty.
  double bout_cv = std::numeric_limits<double>::quiet_NaN();
  // The CV target (fraction) the legend's CV is printed against (cv_text.hpp); NaN: one decimal.
  double cv_target = std::numeric_limits<double>::quiet_NaN();
  // With bout_width_m > 0: also the bout's mean mass per tray (a line) and the band mean × (1 ± CV).
  bool mean_band = false;
  // > 0 (with kKilograms): the catching area of one tray (m²); the bars are then shown as kg/ha
  // (mass ÷ area · 10 000), what a technician sets the spreader to.
  double tray_area_m2 = 0.0;
  // One flag per layout tray (empty = none): a tray without a reading (a tray test's NA). It is marked
  // with a cross; the overlapped profile has a gap over every bout tray it would feed and the bout's
  // mean leaves those out, as the CV does (calibration/cv_without_missing.hpp) — a line dropping to 0
  // there would show a hole the spreader did not make.
  std::vector<bool> missing_trays;
};
// Bars per tray (mass per tray; the unit — kg, g or mg — is picked from the data and named on the axis),
// x in metres.
void write_transverse_png(std::span<const double> tray_mass_kg, const metrics::TrayLayout& trays,
                          const std::string& path, const std::string& title,
                          const TransverseOptions& options = TransverseOptions{});

// Optional extras for the CV(W) plot.
struct CvCurveOptions {
  std::string series_label;                   // "" or a prefix of the two curves' legend ("calibrated")
  std::span<const double> second_to_and_fro{};  // e.g. the tray test's to-and-fro CV(W); same widths; empty = none
  std::string second_label = "measured";
};

// CV(W) in percent against bout width W (m) for to-and-fro and racetrack, the target line, and each
// curve's effective working width (metrics::working_width_on_curve: the widest band's upper end, the
// headline rule on a curve without standard errors) marked by a dot on the curve, which the legend shows with the curve. `widths_m` increase;
// `cv_*` are fractions (0.1 = 10 %), the same size as `widths_m`; infinite CV values (empty bouts) are
// clipped to the top. The W axis ends one width after the last point of any curve on the CV axis (where
// the pattern lives; beyond, the bouts outgrow the throw and the CV only climbs). Either curve may be
// empty (not drawn).
void write_cv_curve_png(std::span<const double> widths_m, std::span<const double> cv_to_and_fro,
                        std::span<const double> cv_racetrack, double cv_target, const std::string& path,
                        const std::string& title, const CvCurveOptions& options = CvCurveOptions{});

}  // namespace spread::plot
