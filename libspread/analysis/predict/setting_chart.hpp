#pragma once
// The setting chart a spreader's manual prints, from a launch table: for each working width, the disc
// speed that spreads it — the rpm within the table's rows at which the predicted to-and-fro effective
// working width (at the CV target) equals the width — with the CVs at that width and their standard
// errors (docs/field-calibration.md, "Spread chart").
//
// Search: the working width W(rpm) is evaluated on a grid of kScanPoints rpm over the material's rows;
// the lowest grid interval where W(rpm) − width changes sign is bisected down to `rpm_tolerance`. The
// working width is a first crossing of a sampled CV(W) curve (metrics.hpp): it can jump when a dip of the
// curve moves under the target, so the found rpm is accepted only when W(rpm) there is within half a tray
// of the width; otherwise the row says the width is jumped over (not reachable). A width outside what the
// grid's rpm give is not reachable either, and the row says which end of the range it lies beyond.
#include <cstddef>
#include <optional>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

struct SettingChartOptions {
  double cv_target = 0.15;         // fraction
  double tray_width_m = 0.5;
  double disc_height_m = std::numeric_limits<double>::quiet_NaN();  // NaN: the table's
  double rpm_tolerance = 0.5;      // r/min: bisection stops below this interval
};

inline constexpr int kScanPoints = 13;

enum class ChartReach {
  kReached,
  kTooNarrow,   // narrower than the working width at every rpm of the range
  kTooWide,     // wider than the working width at every rpm of the range
  kJumpedOver,   // W(rpm) jumps across the width (a dip of CV(W) under the target appears or vanishes)
};

struct SettingChartRow {
  double width_m = 0.0;
  ChartReach reach = ChartReach::kTooWide;
  double rpm = std::numeric_limits<double>::quiet_NaN();  // reached: the disc speed; jumped over: where
  // At `rpm` (reached or jumped over): the working width and, at a bout of width_m, the CVs (fractions)
  // with their standard errors over the launch samples (Prediction's delta-method errors).
  double working_width_to_and_fro_m = std::numeric_limits<double>::quiet_NaN();
  double working_width_to_and_fro_se_m = std::numeric_limits<double>::quiet_NaN();
  double bout_width_m = std::numeric_limits<double>::quiet_NaN();  // width_m in whole trays, as evaluated
  double cv_to_and_fro = std::numeric_limits<double>::quiet_NaN();
  double cv_to_and_fro_se = std::numeric_limits<double>::quiet_NaN();
  double cv_racetrack = std::numeric_limits<double>::quiet_NaN();
  double cv_racetrack_se = std::numeric_limits<double>::quiet_NaN();
  std::size_t sample_count = 0;
  // Grid intervals [low, high] rpm above the one bisected where W(rpm) crosses the width again: the working
  // width is not monotone in rpm, and the row gives the lowest rpm only.
  std::vector<std::pair<double, double>> other_crossings_rpm;
};

struct SettingChart {
  double min_rpm = 0.0, max_rpm = 0.0;                // the material's rows
  std::vector<double> scan_rpm, scan_working_width_m;  // the grid of the search, to-and-fro working widths
  std::vector<SettingChartRow> rows;                  // one per width asked, in that order
  int predictions = 0;                                // predictions made
};

// Throws std::invalid_argument naming the problem for an unknown material, widths that are not > 0 and
// finite, or options the predictor refuses (with its status).
SettingChart setting_chart(Predictor& predictor, std::string_view material, std::span<const double> widths_m,
                           const SettingChartOptions& options);

const char* to_string(ChartReach reach);

}  // namespace spread::predict
