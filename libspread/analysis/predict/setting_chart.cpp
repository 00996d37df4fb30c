#include "libspread/analysis/predict/setting_chart.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::predict {
namespace {

class Search {
 public:
  Search(Predictor& predictor, std::string_view material, const SettingChartOptions& options, int& predictions)
      : predictor_(predictor), options_(options), predictions_(predictions) {
    request_.material = material;
    request_.cv_target = options.cv_target;
    request_.tray_width_m = options.tray_width_m;
    request_.disc_height_m = options.disc_height_m;
  }

  // The prediction at `rpm` with the CVs at `bout_width_m` (0: at the working width).
  const Prediction& at(double rpm, double bout_width_m) {
    request_.rpm = rpm;
    request_.bout_width_m = bout_width_m;
    const PredictStatus status = predictor_.predict(request_, prediction_);
    ++predictions_;
    if (status != PredictStatus::kOk) {
      throw std::invalid_argument(std::string("prediction at ") + std::to_string(rpm) + " rpm refused: " +
                                  to_string(status));
    }
    return prediction_;
  }
  double working_width_m(double rpm) { return at(rpm, 0.0).working_width_to_and_fro_m; }

 private:
  Predictor& predictor_;
  const SettingChartOptions& options_;
  int& predictions_;
  PredictionRequest request_;
  Prediction prediction_;
};

}  // namespace

const char* to_string(ChartReach reach) {
  switch (reach) {
    case ChartReach::kReached: return "reached";
    case ChartReach::kTooNarrow: return "too_narrow";
    case ChartReach::kTooWide: return "too_wide";
    case ChartReach::kJumpedOver: return "jumped_over";
  }
  return "?";
}

SettingChart setting_chart(Predictor& predictor, std::string_view material, std::span<const double> widths_m,
                           const SettingChartOptions& options) {
  const std::optional<std::size_t> index = predictor.find_material(material);
  if (!index) throw std::invalid_argument("material '" + std::string(material) + "' is not in the table");
  for (double w : widths_m) {
    if (!std::isfinite(w) || !(w > 0.0)) throw std::invalid_argument("widths must be finite and > 0 m");
  }
  if (!(options.rpm_tolerance > 0.0)) throw std::invalid_argument("rpm_tolerance must be > 0");
  SettingChart chart;
  chart.min_rpm = predictor.min_rpm(*index);
  chart.max_rpm = predictor.max_rpm(*index);
  Search search(predictor, material, options, chart.predictions);
  for (int k = 0; k < kScanPoints; ++k) {
    const double rpm = chart.min_rpm + (chart.max_rpm - chart.min_rpm) * k / (kScanPoints - 1);
    chart.scan_rpm.push_back(rpm);
    chart.scan_working_width_m.push_back(search.working_width_m(rpm));
    if (chart.max_rpm == chart.min_rpm) break;
  }
  double narrowest_m = chart.scan_working_width_m[0], widest_m = narrowest_m;
  for (double w : chart.scan_working_width_m) {
    narrowest_m = std::min(narrowest_m, w);
    widest_m = std::max(widest_m, w);
  }

  for (double width_m : widths_m) {
    SettingChartRow row;
    row.width_m = width_m;
    // The lowest grid interval whose ends lie on either side of the width (or one end on it).
    std::size_t bracket = chart.scan_rpm.size();
    for (std::size_t k = 0; k + 1 < chart.scan_rpm.size(); ++k) {
      const double a = chart.scan_working_width_m[k] - width_m, b = chart.scan_working_width_m[k + 1] - width_m;
      if ((a <= 0.0 && b >= 0.0) || (a >= 0.0 && b <= 0.0)) {
        bracket = k;
        break;
      }
    }
    if (bracket == chart.scan_rpm.size()) {
      row.reach = width_m < narrowest_m ? ChartReach::kTooNarrow : ChartReach::kTooWide;
      chart.rows.push_back(row);
      continue;
    }
    // Later crossings (a grid point on the width counts once: the interval after it must change sign).
    for (std::size_t k = bracket + 1; k + 1 < chart.scan_rpm.size(); ++k) {
      const double a = chart.scan_working_width_m[k] - width_m, b = chart.scan_working_width_m[k + 1] - width_m;
      const double before = chart.scan_working_width_m[k - 1] - width_m;
      const bool crosses = (a < 0.0 && b >= 0.0) || (a > 0.0 && b <= 0.0) || (a == 0.0 && (before < 0.0) != (b < 0.0));
      if (crosses) row.other_crossings_rpm.emplace_back(chart.scan_rpm[k], chart.scan_rpm[k + 1]);
    }
    double lo = chart.scan_rpm[bracket], hi = chart.scan_rpm[bracket + 1];
    const bool rising = chart.scan_working_width_m[bracket + 1] >= chart.scan_working_width_m[bracket];
    while (hi - lo > options.rpm_tolerance) {
      const double mid = 0.5 * (lo + hi);
      const bool beyond = search.working_width_m(mid) > width_m;
      ((beyond == rising) ? hi : lo) = mid;
    }
    row.rpm = 0.5 * (lo + hi);
    const Prediction& p = search.at(row.rpm, width_m);
    row.working_width_to_and_fro_m = p.working_width_to_and_fro_m;
    row.working_width_to_and_fro_se_m = p.working_width_to_and_fro_se_m;
    row.bout_width_m = p.bout_width_m;
    row.cv_to_and_fro = p.cv_to_and_fro;
    row.cv_to_and_fro_se = p.cv_to_and_fro_se;
    row.cv_racetrack = p.cv_racetrack;
    row.cv_racetrack_se = p.cv_racetrack_se;
    row.sample_count = p.sample_count;
    row.reach = std::abs(p.working_width_to_and_fro_m - width_m) <= 0.5 * options.tray_width_m ? ChartReach::kReached
                                                                                                : ChartReach::kJumpedOver;
    chart.rows.push_back(row);
  }
  return chart;
}

}  // namespace spread::predict
