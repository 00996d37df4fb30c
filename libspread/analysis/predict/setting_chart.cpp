#include "libspread/analysis/predict/setting_chart.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>

namespace spread::predict {
namespace {

class Search {
 public:
  Search(Predictor& predictor, std::string_view material, const SettingChartOptions& options, int& predictions)
      : predictor_(predictor), predictions_(predictions) {
    request_.material = material;
    request_.cv_target = options.cv_target;
    request_.tray_width_m = options.tray_width_m;
    request_.disc_height_m = options.disc_height_m;
    request_.wind_x_m_s = options.wind_x_m_s;
    request_.wind_y_m_s = options.wind_y_m_s;
  }

  // The prediction at `rpm` with the CVs at `bout_width_m`.
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
  // The to-and-fro CV at bout_width_m; +infinity where it is undefined (nothing to rank).
  double cv(double rpm, double bout_width_m) {
    const double value = at(rpm, bout_width_m).cv_to_and_fro;
    return std::isnan(value) ? std::numeric_limits<double>::infinity() : value;
  }

 private:
  Predictor& predictor_;
  int& predictions_;
  PredictionRequest request_;
  Prediction prediction_;
};

// Every row of the material, and evenly spaced points between two rows at most kChartScanStep_rpm apart.
std::vector<double> scan_grid(std::span<const double> rows_rpm) {
  std::vector<double> grid{rows_rpm.front()};
  for (std::size_t r = 1; r < rows_rpm.size(); ++r) {
    const double low = rows_rpm[r - 1], high = rows_rpm[r];
    const int steps = std::max(1, static_cast<int>(std::ceil((high - low) / kChartScanStep_rpm - 1e-9)));
    for (int k = 1; k < steps; ++k) grid.push_back(low + (high - low) * k / steps);
    grid.push_back(high);
  }
  return grid;
}

// Golden-section search for the lowest CV over [low, high], starting from the grid's best `best_rpm`
// with `best_cv`; returns the lower of the two.
std::pair<double, double> refine(Search& search, double width_m, double low, double high, double best_rpm,
                                 double best_cv, double tolerance) {
  constexpr double kInverseGolden = 0.6180339887498949;  // (√5 − 1)/2
  double a = low, b = high;
  double c = b - kInverseGolden * (b - a), d = a + kInverseGolden * (b - a);
  double fc = search.cv(c, width_m), fd = search.cv(d, width_m);
  while (b - a > tolerance) {
    if (fc <= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - kInverseGolden * (b - a);
      fc = search.cv(c, width_m);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + kInverseGolden * (b - a);
      fd = search.cv(d, width_m);
    }
  }
  const double rpm = fc <= fd ? c : d, cv = std::min(fc, fd);
  return cv < best_cv ? std::pair{rpm, cv} : std::pair{best_rpm, best_cv};
}

}  // namespace

const char* to_string(ChartReach reach) {
  switch (reach) {
    case ChartReach::kReached: return "reached";
    case ChartReach::kMarginal: return "marginal";
    case ChartReach::kNotReached: return "not_reached";
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
  chart.scan_rpm = scan_grid(predictor.row_rpm(*index));
  const std::size_t points = chart.scan_rpm.size();
  chart.scan_cv_to_and_fro.resize(widths_m.size() * points);
  Search search(predictor, material, options, chart.predictions);

  for (std::size_t w = 0; w < widths_m.size(); ++w) {
    const double width_m = widths_m[w];
    SettingChartRow row;
    row.width_m = width_m;
    const std::span<double> cv = std::span(chart.scan_cv_to_and_fro).subspan(w * points, points);
    std::size_t best = 0;
    for (std::size_t k = 0; k < points; ++k) {
      cv[k] = search.cv(chart.scan_rpm[k], width_m);
      if (cv[k] < cv[best]) best = k;
    }
    // Spans within the target, ends interpolated linearly in CV between grid points.
    const double target = options.cv_target;
    const auto crossing = [&](std::size_t k) {  // between grid points k and k + 1
      const double a = cv[k], b = cv[k + 1];
      if (!std::isfinite(a) || !std::isfinite(b)) return std::isfinite(a) ? chart.scan_rpm[k] : chart.scan_rpm[k + 1];
      return chart.scan_rpm[k] + (target - a) / (b - a) * (chart.scan_rpm[k + 1] - chart.scan_rpm[k]);
    };
    for (std::size_t k = 0; k < points; ++k) {
      if (!(cv[k] <= target)) continue;
      const double low = k == 0 ? chart.scan_rpm[0] : crossing(k - 1);
      std::size_t last = k;
      while (last + 1 < points && cv[last + 1] <= target) ++last;
      const double high = last + 1 == points ? chart.scan_rpm[last] : crossing(last);
      row.within_target_rpm.emplace_back(low, high);
      k = last;
    }
    // The grid's best, refined between its neighbours.
    double best_rpm = chart.scan_rpm[best], best_cv = cv[best];
    if (points > 1 && std::isfinite(best_cv)) {
      const double low = chart.scan_rpm[best == 0 ? 0 : best - 1];
      const double high = chart.scan_rpm[std::min(best + 1, points - 1)];
      std::tie(best_rpm, best_cv) = refine(search, width_m, low, high, best_rpm, best_cv, options.rpm_tolerance);
    }
    const Prediction& p = search.at(best_rpm, width_m);
    row.rpm = best_rpm;
    row.bout_width_m = p.bout_width_m;
    row.cv_to_and_fro = p.cv_to_and_fro;
    row.cv_to_and_fro_se = p.cv_to_and_fro_se;
    row.cv_racetrack = p.cv_racetrack;
    row.cv_racetrack_se = p.cv_racetrack_se;
    row.working_width_to_and_fro_m = p.working_width_to_and_fro_m;
    row.working_width_to_and_fro_se_m = p.working_width_to_and_fro_se_m;
    row.sample_count = p.sample_count;
    if (!(row.cv_to_and_fro <= target)) {
      row.reach = ChartReach::kNotReached;
    } else {
      const double upper = row.cv_to_and_fro + kConfidence95 * (std::isfinite(row.cv_to_and_fro_se) ? row.cv_to_and_fro_se : 0.0);
      row.reach = upper <= target ? ChartReach::kReached : ChartReach::kMarginal;
    }
    chart.rows.push_back(std::move(row));
  }
  return chart;
}

}  // namespace spread::predict
