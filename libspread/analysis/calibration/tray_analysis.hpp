#pragma once
// What a tray test says about the spreader (docs/field-calibration.md, step 2): CV at a bout width for
// to-and-fro and racetrack driving, the CV(W) curves, and the effective working widths — all from the
// measured trays, through spread::metrics on the tray test's symmetric layout.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "libspread/analysis/calibration/tray_csv.hpp"

namespace spread::calibration {

struct TrayTestAnalysis {
  double total_mass_kg = 0.0;              // sum over the measured trays (mean of the passes)
  double throw_width_m = 0.0;              // lateral extent of 99 % of the mass
  double cv_target = 0.15;                 // fraction
  // The widest band's upper end (measured trays have no sampling error to establish a band by;
  // docs/metrics.md "Effective working width"); 0 = none.
  double working_width_to_and_fro_m = 0.0;
  double working_width_racetrack_m = 0.0;
  // Every band of bout widths with CV <= target, [lower, upper] (m), narrowest first (the first three
  // and the widest are kept).
  std::vector<std::pair<double, double>> bands_to_and_fro_m, bands_racetrack_m;
  // A tray test resolves the bout in whole trays: the CVs are at the requested width rounded to the
  // nearest whole number of trays (metrics::bout_tray_count). Both are reported, and the tools warn
  // when they differ, so "at W = 3.3 m" is never printed for the CV of 3.5 m.
  double requested_bout_width_m = 0.0;     // as asked (0 = none asked)
  double bout_width_m = 0.0;               // the W the CVs below are at (0 = none asked)
  bool bout_width_rounded() const { return std::abs(bout_width_m - requested_bout_width_m) > 1e-9; }
  double cv_to_and_fro = 0.0;              // fraction, at bout_width_m
  double cv_racetrack = 0.0;
  // CV(W) on the tray grid from two trays up to the layout width.
  std::vector<double> widths_m;
  std::vector<double> cv_to_and_fro_curve;
  std::vector<double> cv_racetrack_curve;
};

// The CV target a technician gives in per cent, as a fraction. Targets are 10–20 % in practice
// (EN 13739-2 reports the CV against 15 %) and no spreader is uniform to 1 %, so a value below
// kLeastCvTargetPercent is a fraction typed where a percentage belongs ("0.15" for 15 %): refused with
// that hint (std::invalid_argument naming `option`), as is a value above 100 %.
inline constexpr double kLeastCvTargetPercent = 1.0;
double cv_target_from_percent(double percent, const std::string& option);

// cv_target as a fraction (0.15 = 15 %) in (0, 1]; bout_width_m >= 0 (0: no CV at a single width; a
// width that is not a whole number of trays is rounded to one, see bout_width_m above).
// Throws std::invalid_argument naming a bad cv_target or bout width.
TrayTestAnalysis analyse_tray_test(const TrayTest& test, double cv_target, double bout_width_m);

}  // namespace spread::calibration
