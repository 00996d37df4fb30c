#pragma once
// The report's table of CV per working width: which widths, and their CVs read off a CV(W) curve.
//
// The rows are taken from the CV(W) curve the command already computed and prints as `cv_curve` in its
// --json (metrics::cv_curve / cv_at_trays on the trays; for a tray test with missing trays, the curve
// that leaves them out): no second overlap computation, so the table, the JSON and the text report
// cannot disagree, and predicted and measured trays go through the same code.
#include <span>
#include <vector>

namespace spread::plot {

struct CvTableRow {
  double bout_width_m = 0.0;
  double cv_to_and_fro = 0.0;  // fraction; +inf: the bout holds no mass; NaN: no CV (missing trays)
  double cv_racetrack = 0.0;
};

// The usual working widths of twin-disc spreaders (m).
inline constexpr double kStandardWidths_m[] = {12.0, 15.0, 18.0, 21.0, 24.0};

// Widths for the table, each one of `curve_widths_m` (whole trays, increasing): the standard widths when
// at least three of them are within the throw width, otherwise five widths fitting the pattern, k × s
// for k = 1..5 with s a sixth of the throw width (so the last is below the throw width, where a CV
// still means something). Each is the curve width nearest to it; duplicates and widths beyond the curve
// are dropped. Empty when the curve is.
std::vector<double> cv_table_widths_m(double throw_width_m, std::span<const double> curve_widths_m);

// `widths_m` (increasing) with the driven bout's width added in order when it is a curve width (within a
// millimetre) and not there yet: the table then holds the CV the report's verdict is about. A bout of
// 0 (none driven) leaves the widths as they are.
std::vector<double> with_bout_width_m(std::vector<double> widths_m, double bout_width_m,
                                      std::span<const double> curve_widths_m);

// The rows at `widths_m`, each read at the curve point of the same width (within a millimetre); widths
// that are not curve points are left out. Throws std::invalid_argument when the curves' sizes differ.
std::vector<CvTableRow> cv_table(std::span<const double> widths_m, std::span<const double> curve_widths_m,
                                 std::span<const double> cv_to_and_fro, std::span<const double> cv_racetrack);

}  // namespace spread::plot
