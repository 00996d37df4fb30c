#pragma once
// The setting chart a spreader's manual prints, from a launch table: for each tramline (bout) width W,
// the setting of both discs alike — disc speed and drop point — with the lowest predicted to-and-fro CV
// at W, that CV and the racetrack CV with their standard errors, and every span of disc speeds (at that
// drop point) that keeps the CV within the target (docs/field-calibration.md, "Spread chart").
//
// Search: one prediction per setting gives the CV at every width (the trays do not depend on the bout),
// without standard errors (PredictionRequest::standard_errors). CV(rpm, drop point) is evaluated on a
// grid: every table row and steps of at most kChartGridStep_rpm between rows, times drop-point turns in
// steps of `drop_point_step_rad` within ±max_drop_point_turn_rad and the turns the table validates
// (Predictor::drop_point_turn_range). At each W the best grid point is then
// refined by golden-section search along the speed (the two grid intervals around it, down to
// `rpm_tolerance`), along the drop point (the two steps around it, down to `drop_point_tolerance_rad`),
// and along the speed once more; a refinement only keeps a point lower than the best so far. CV between
// rows is an interpolation of launch samples (launch_interpolation.hpp), smooth on the grid's scale; the
// CV over the drop point is not monotonic (the fan turns against the neighbouring pass), hence the grid
// over the whole range first. The spans come from a finer scan of the speed (every row and steps of at
// most kChartScanStep_rpm) at the chosen drop point, their ends interpolated linearly in CV. A width is
// reachable when some setting's CV meets the target there. In a lateral wind each row also gets the discs
// set apart from its setting (compensate_wind), the answer to the wind a twin-disc spreader has.
//
// The setting the chart gives is the one that holds, not the knife edge: the lowest-CV setting and the
// kChartCandidates grid points of lowest CV at W are predicted with their standard errors (the launch
// samples' and, between DEM rows, the interpolation's own), and the chart takes the one whose CV + 1.96 SE
// is lowest. Between rows the lowest CV the search finds is often where the interpolation's smoothing is
// largest (docs/metrics.md "Between rows"); a setting on a row or whose CV the samples establish then
// wins. The lowest-CV setting stays in the row (lowest_cv_*), and the spans are read at the chosen drop
// point.
#include <cstddef>
#include <limits>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

struct SettingChartOptions {
  double cv_target = 0.15;         // fraction
  double tray_width_m = 0.5;
  double disc_height_m = std::numeric_limits<double>::quiet_NaN();  // NaN: the table's
  double wind_x_m_s = 0.0;         // lateral wind of the day (the search then predicts in it)
  double wind_y_m_s = 0.0;
  double rpm_tolerance = 0.5;      // r/min: the refinement stops below this interval
  // The drop points searched: turns from the table's within ±max_drop_point_turn_rad (0: the table's drop
  // point only) and the table's validated turns, on a grid of drop_point_step_rad, refined down to
  // drop_point_tolerance_rad.
  double max_drop_point_turn_rad = 1.5707963267948966;  // ±90°
  double drop_point_step_rad = 0.08726646259971647;     // 5°
  double drop_point_tolerance_rad = 0.0017453292519943296;  // 0.1°
};

// Largest step of the spans' speed scan (r/min): a fifth of the 25 rpm a technician turns the dial by.
inline constexpr double kChartScanStep_rpm = 5.0;
// Largest speed step of the search grid over speed and drop point (r/min).
inline constexpr double kChartGridStep_rpm = 15.0;
// Grid points of lowest CV at a width that compete with the lowest-CV setting on their 95 % upper bound.
inline constexpr int kChartCandidates = 8;

enum class ChartReach {
  kReached,      // the best setting's CV + 1.96 SE is within the target
  kMarginal,     // the best setting's CV is within the target but its 95 % interval reaches over it
  kNotReached,   // no setting of the table's range has a CV within the target at this width
};

struct SettingChartRow {
  double width_m = 0.0;
  ChartReach reach = ChartReach::kNotReached;
  // The chart's setting, both discs alike: speed and drop-point turn — of the candidates, the lowest
  // to-and-fro CV + 1.96 SE at W.
  double rpm = std::numeric_limits<double>::quiet_NaN();
  double drop_point_turn_rad = std::numeric_limits<double>::quiet_NaN();
  // At `rpm`: the CVs (fractions) at a bout of width_m in whole trays, with their standard errors over
  // the launch samples, and the headline working width there (Prediction's rule).
  double bout_width_m = std::numeric_limits<double>::quiet_NaN();
  double cv_to_and_fro = std::numeric_limits<double>::quiet_NaN();
  double cv_to_and_fro_se = std::numeric_limits<double>::quiet_NaN();
  double cv_racetrack = std::numeric_limits<double>::quiet_NaN();
  double cv_racetrack_se = std::numeric_limits<double>::quiet_NaN();
  double working_width_to_and_fro_m = std::numeric_limits<double>::quiet_NaN();
  double working_width_to_and_fro_se_m = std::numeric_limits<double>::quiet_NaN();
  std::size_t sample_count = 0;
  // The lowest to-and-fro CV the search found at W, where, and its standard error (equal to the chart's
  // setting when that one also has the lowest upper bound).
  double lowest_cv_rpm = std::numeric_limits<double>::quiet_NaN();
  double lowest_cv_drop_point_turn_rad = std::numeric_limits<double>::quiet_NaN();
  double lowest_cv = std::numeric_limits<double>::quiet_NaN();
  double lowest_cv_se = std::numeric_limits<double>::quiet_NaN();
  // Spans [low, high] of disc speed (r/min) whose to-and-fro CV at W is within the target, at the
  // chosen drop point.
  std::vector<std::pair<double, double>> within_target_rpm;
  // In a lateral wind: the discs set apart from the setting above (wind_compensation.hpp), with the
  // to-and-fro CV at W there and its standard error (fractions); compensated false otherwise.
  bool compensated = false;
  DiscSetting compensated_discs[2];
  double compensated_cv = std::numeric_limits<double>::quiet_NaN();
  double compensated_cv_se = std::numeric_limits<double>::quiet_NaN();
};

struct SettingChart {
  double min_rpm = 0.0, max_rpm = 0.0;  // the material's rows
  std::vector<double> grid_rpm;         // the search grid: speeds …
  std::vector<double> grid_drop_point_turn_rad;  // … times drop-point turns
  std::vector<double> scan_rpm;         // the spans' speed scan
  // scan_cv_to_and_fro[w * scan_rpm.size() + k]: the CV at width w (the order asked) and scan speed k, at
  // that width's chosen drop point.
  std::vector<double> scan_cv_to_and_fro;
  std::vector<SettingChartRow> rows;    // one per width asked, in that order
  int predictions = 0;                  // predictions made
};

// Throws std::invalid_argument naming the problem for an unknown material, widths that are not > 0 and
// finite, a drop-point range outside [0, π] or a step or tolerance not > 0, or options the predictor
// refuses (with its status).
SettingChart setting_chart(Predictor& predictor, std::string_view material, std::span<const double> widths_m,
                           const SettingChartOptions& options);

const char* to_string(ChartReach reach);

}  // namespace spread::predict
