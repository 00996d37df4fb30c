#pragma once
// The setting chart a spreader's manual prints, from a launch table: for each tramline (bout) width W,
// the disc speed (both discs alike) with the lowest predicted to-and-fro CV at W, that CV and the
// racetrack CV with their standard errors, and every span of disc speeds that keeps the CV within the
// target (docs/field-calibration.md, "Spread chart").
//
// Search: CV(rpm) at each W is evaluated on a grid over the material's rows (every table row, and steps
// of at most kChartScanStep_rpm between them); the best grid point is then refined by golden-section
// search over the two grid intervals around it, down to `rpm_tolerance`. CV(rpm) between rows is an
// interpolation of launch samples (launch_interpolation.hpp), smooth on the scale of the grid; the
// refinement only keeps a point that is lower than the grid's best. A width is reachable when some
// setting's CV meets the target there; the span ends are interpolated linearly in CV between grid points.
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
};

// Largest grid step between two grid points (r/min): a fifth of the 25 rpm a technician turns the dial by.
inline constexpr double kChartScanStep_rpm = 5.0;

enum class ChartReach {
  kReached,      // the best setting's CV + 1.96 SE is within the target
  kMarginal,     // the best setting's CV is within the target but its 95 % interval reaches over it
  kNotReached,   // no setting of the table's range has a CV within the target at this width
};

struct SettingChartRow {
  double width_m = 0.0;
  ChartReach reach = ChartReach::kNotReached;
  double rpm = std::numeric_limits<double>::quiet_NaN();  // the best setting (lowest to-and-fro CV at W)
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
  // Spans [low, high] of disc speed (r/min) whose to-and-fro CV at W is within the target.
  std::vector<std::pair<double, double>> within_target_rpm;
};

struct SettingChart {
  double min_rpm = 0.0, max_rpm = 0.0;  // the material's rows
  std::vector<double> scan_rpm;         // the grid of the search
  // scan_cv_to_and_fro[w * scan_rpm.size() + k]: the CV at width w (the order asked) and grid point k.
  std::vector<double> scan_cv_to_and_fro;
  std::vector<SettingChartRow> rows;    // one per width asked, in that order
  int predictions = 0;                  // predictions made
};

// Throws std::invalid_argument naming the problem for an unknown material, widths that are not > 0 and
// finite, or options the predictor refuses (with its status).
SettingChart setting_chart(Predictor& predictor, std::string_view material, std::span<const double> widths_m,
                           const SettingChartOptions& options);

const char* to_string(ChartReach reach);

}  // namespace spread::predict
