#include "libspread/analysis/predict/setting_chart.hpp"

#include "libspread/analysis/predict/golden_section.hpp"
#include "libspread/analysis/predict/wind_compensation.hpp"

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

  // The chart's request at this setting and bout width.
  PredictionRequest request(double rpm, double turn_rad, double bout_width_m) const {
    PredictionRequest r = request_;
    r.rpm = rpm;
    r.drop_point_turn_rad = turn_rad;
    r.bout_width_m = bout_width_m;
    return r;
  }
  // The prediction at this setting; with standard errors, the CVs at `bout_width_m`.
  const Prediction& at(double rpm, double turn_rad, double bout_width_m, bool standard_errors) {
    PredictionRequest r = request(rpm, turn_rad, bout_width_m);
    r.standard_errors = standard_errors;
    const PredictStatus status = predictor_.predict(r, prediction_);
    ++predictions_;
    if (status != PredictStatus::kOk) {
      throw std::invalid_argument(std::string("prediction at ") + std::to_string(rpm) + " rpm, drop point turned " +
                                  std::to_string(turn_rad) + " rad refused: " + to_string(status));
    }
    return prediction_;
  }
  // The to-and-fro CVs at each of `widths_m` of one prediction (the trays do not depend on the bout: the
  // same values as a prediction at that bout); +infinity where undefined (nothing to rank).
  void cvs(double rpm, double turn_rad, std::span<const double> widths_m, std::span<double> out) {
    const Prediction& p = at(rpm, turn_rad, 0.0, false);
    for (std::size_t w = 0; w < widths_m.size(); ++w) {
      const int trays = metrics::bout_tray_count(p.trays, widths_m[w]);
      scratch_.resize(2 * (static_cast<std::size_t>(trays) + 1));  // two bouts with a return pass of its own
      const double value = metrics::cv_at_trays(p.tray_mass_fraction, p.return_tray_mass_fraction, p.trays, trays, scratch_);
      out[w] = std::isnan(value) ? std::numeric_limits<double>::infinity() : value;
    }
  }
  double cv(double rpm, double turn_rad, double width_m) {
    double value = 0.0;
    cvs(rpm, turn_rad, std::span(&width_m, 1), std::span(&value, 1));
    return value;
  }

 private:
  Predictor& predictor_;
  int& predictions_;
  PredictionRequest request_;
  Prediction prediction_;
  std::vector<double> scratch_;
};

// Every row of the material, and evenly spaced points between two rows at most `step_rpm` apart.
std::vector<double> speed_grid(std::span<const double> rows_rpm, double step_rpm) {
  std::vector<double> grid{rows_rpm.front()};
  for (std::size_t r = 1; r < rows_rpm.size(); ++r) {
    const double low = rows_rpm[r - 1], high = rows_rpm[r];
    const int steps = std::max(1, static_cast<int>(std::ceil((high - low) / step_rpm - 1e-9)));
    for (int k = 1; k < steps; ++k) grid.push_back(low + (high - low) * k / steps);
    grid.push_back(high);
  }
  return grid;
}

// 0 and every multiple of `step_rad` within ±max_rad and the validated turns, ascending.
std::vector<double> drop_point_grid(double max_rad, double step_rad, const TurnRange& valid) {
  const int steps = static_cast<int>(std::floor(max_rad / step_rad + 1e-9));
  std::vector<double> grid;
  for (int k = -steps; k <= steps; ++k) {
    if (k == 0 || valid.contains(k * step_rad)) grid.push_back(k * step_rad);
  }
  return grid;
}

// The grid neighbours of index k: [grid[k − 1], grid[k + 1]] within the grid.
std::pair<double, double> around(const std::vector<double>& grid, std::size_t k) {
  return {grid[k == 0 ? 0 : k - 1], grid[std::min(k + 1, grid.size() - 1)]};
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

namespace {

void check_chart_options(std::span<const double> widths_m, const SettingChartOptions& options) {
  for (double w : widths_m) {
    if (!std::isfinite(w) || !(w > 0.0)) throw std::invalid_argument("widths must be finite and > 0 m");
  }
  if (!(options.rpm_tolerance > 0.0)) throw std::invalid_argument("rpm_tolerance must be > 0");
  if (!(options.max_drop_point_turn_rad >= 0.0 && options.max_drop_point_turn_rad <= kPi)) {
    throw std::invalid_argument("max_drop_point_turn_rad must be within [0, pi]");
  }
  if (!(options.drop_point_step_rad > 0.0) || !(options.drop_point_tolerance_rad > 0.0)) {
    throw std::invalid_argument("drop_point_step_rad and drop_point_tolerance_rad must be > 0");
  }
}

// A disc setting: speed and drop-point turn.
struct ChartSetting {
  double rpm = 0.0;
  double turn_rad = 0.0;
  bool operator==(const ChartSetting&) const = default;
};

// The chart's stages over one context: the grid of CVs at every width (grid_cvs), then per width the
// lowest-CV setting (lowest_cv_setting: the grid's best refined along the speed and the drop point, then a
// finer scan of the speed), the candidates the chart chooses among (candidates, choose), the speeds within
// the target at the chosen drop point (within_target), and the row at the chosen setting (fill_row,
// compensate).
class ChartBuilder {
 public:
  ChartBuilder(Predictor& predictor, std::string_view material, std::span<const double> widths_m,
               const SettingChartOptions& options, SettingChart& chart)
      : predictor_(predictor), widths_m_(widths_m), options_(options), chart_(chart),
        search_(predictor, material, options, chart.predictions) {}

  void grid_cvs() {
    const std::size_t widths = widths_m_.size(), speeds = chart_.grid_rpm.size();
    grid_cv_.resize(chart_.grid_drop_point_turn_rad.size() * speeds * widths);
    for (std::size_t t = 0; t < chart_.grid_drop_point_turn_rad.size(); ++t) {
      for (std::size_t k = 0; k < speeds; ++k) {
        search_.cvs(chart_.grid_rpm[k], chart_.grid_drop_point_turn_rad[t], widths_m_,
                    std::span(grid_cv_).subspan((t * speeds + k) * widths, widths));
      }
    }
  }

  SettingChartRow row(std::size_t w) {
    SettingChartRow row;
    row.width_m = widths_m_[w];
    const ChartSetting lowest = lowest_cv_setting(w);
    const std::vector<ChartSetting> settings = candidates(w, lowest);
    const ChartSetting chosen = choose(w, settings, row);
    // The spans within the target at the chosen drop point, from the scan (at the lowest-CV drop point
    // already: scanned again only at another).
    if (chosen.turn_rad != lowest.turn_rad) scan(w, chosen.turn_rad);
    within_target(w, row);
    fill_row(w, chosen, row);
    compensate(w, chosen, row);
    if (!(row.cv_to_and_fro <= options_.cv_target)) {
      row.reach = ChartReach::kNotReached;
    } else {
      const double upper = row.cv_to_and_fro + kConfidence95 * (std::isfinite(row.cv_to_and_fro_se) ? row.cv_to_and_fro_se : 0.0);
      row.reach = upper <= options_.cv_target ? ChartReach::kReached : ChartReach::kMarginal;
    }
    return row;
  }

 private:
  double grid_at(std::size_t t, std::size_t k, std::size_t w) const {
    return grid_cv_[(t * chart_.grid_rpm.size() + k) * widths_m_.size() + w];
  }
  std::span<double> scan_cv(std::size_t w) {
    const std::size_t points = chart_.scan_rpm.size();
    return std::span(chart_.scan_cv_to_and_fro).subspan(w * points, points);
  }
  // The to-and-fro CV at every scan speed at this drop point and width w.
  void scan(std::size_t w, double turn_rad) {
    const std::span<double> cv = scan_cv(w);
    for (std::size_t k = 0; k < cv.size(); ++k) cv[k] = search_.cv(chart_.scan_rpm[k], turn_rad, widths_m_[w]);
  }

  // The grid's lowest CV at width w, refined along the speed, the drop point and the speed again (golden
  // sections between the grid neighbours), then the scan at that drop point, which may still find a lower
  // point (a finer speed step).
  ChartSetting lowest_cv_setting(std::size_t w) {
    const std::size_t turns = chart_.grid_drop_point_turn_rad.size(), speeds = chart_.grid_rpm.size();
    const double width_m = widths_m_[w];
    std::size_t best_t = 0, best_k = 0;
    for (std::size_t t = 0; t < turns; ++t) {
      for (std::size_t k = 0; k < speeds; ++k) {
        if (grid_at(t, k, w) < grid_at(best_t, best_k, w)) {
          best_t = t;
          best_k = k;
        }
      }
    }
    double best_rpm = chart_.grid_rpm[best_k], best_turn_rad = chart_.grid_drop_point_turn_rad[best_t];
    double best_cv = grid_at(best_t, best_k, w);
    if (std::isfinite(best_cv)) {
      const auto along_speed = [&](double rpm) { return search_.cv(rpm, best_turn_rad, width_m); };
      const auto along_turn = [&](double turn_rad) { return search_.cv(best_rpm, turn_rad, width_m); };
      const auto [low_rpm, high_rpm] = around(chart_.grid_rpm, best_k);
      std::tie(best_rpm, best_cv) = golden_section_minimum(along_speed, low_rpm, high_rpm, best_rpm, best_cv, options_.rpm_tolerance);
      const auto [low_turn, high_turn] = around(chart_.grid_drop_point_turn_rad, best_t);
      std::tie(best_turn_rad, best_cv) =
          golden_section_minimum(along_turn, low_turn, high_turn, best_turn_rad, best_cv, options_.drop_point_tolerance_rad);
      if (turns > 1) {
        const double step_rpm = 0.5 * (high_rpm - low_rpm);
        std::tie(best_rpm, best_cv) =
            golden_section_minimum(along_speed, std::max(chart_.min_rpm, best_rpm - step_rpm),
                                   std::min(chart_.max_rpm, best_rpm + step_rpm), best_rpm, best_cv, options_.rpm_tolerance);
      }
    }
    scan(w, best_turn_rad);
    const std::span<const double> cv = scan_cv(w);
    for (std::size_t k = 0; k < cv.size(); ++k) {
      if (cv[k] < best_cv) {
        best_cv = cv[k];
        best_rpm = chart_.scan_rpm[k];
      }
    }
    return {best_rpm, best_turn_rad};
  }

  // The candidates: the lowest-CV setting, then the kChartCandidates grid points of lowest CV at width w.
  std::vector<ChartSetting> candidates(std::size_t w, const ChartSetting& lowest) const {
    const std::size_t speeds = chart_.grid_rpm.size();
    std::vector<ChartSetting> settings{lowest};
    std::vector<std::size_t> order(chart_.grid_drop_point_turn_rad.size() * speeds);
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const auto cv_of = [&](std::size_t i) { return grid_cv_[i * widths_m_.size() + w]; };
    const std::size_t take = std::min<std::size_t>(order.size(), kChartCandidates);
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(take), order.end(),
                      [&](std::size_t a, std::size_t b) { return cv_of(a) < cv_of(b) || (cv_of(a) == cv_of(b) && a < b); });
    for (std::size_t i = 0; i < take; ++i) {
      if (!std::isfinite(cv_of(order[i]))) break;
      const ChartSetting point{chart_.grid_rpm[order[i] % speeds], chart_.grid_drop_point_turn_rad[order[i] / speeds]};
      if (!(point == settings.front())) settings.push_back(point);
    }
    return settings;
  }

  // The chart's setting: the lowest CV + 1.96 SE among the candidates (the first on a tie), a CV within the
  // target before one above it (the chart never trades a setting that meets the target for one that does
  // not). The first candidate's figures are the row's lowest-CV setting.
  ChartSetting choose(std::size_t w, const std::vector<ChartSetting>& settings, SettingChartRow& row) {
    const auto upper_bound = [](const Prediction& p) {
      return p.cv_to_and_fro + kConfidence95 * (std::isfinite(p.cv_to_and_fro_se) ? p.cv_to_and_fro_se : 0.0);
    };
    std::size_t chosen = 0;
    std::pair<bool, double> chosen_rank{true, std::numeric_limits<double>::infinity()};
    for (std::size_t c = 0; c < settings.size(); ++c) {
      const Prediction& p = search_.at(settings[c].rpm, settings[c].turn_rad, widths_m_[w], true);
      if (c == 0) {
        row.lowest_cv_rpm = settings[0].rpm;
        row.lowest_cv_drop_point_turn_rad = settings[0].turn_rad;
        row.lowest_cv = p.cv_to_and_fro;
        row.lowest_cv_se = p.cv_to_and_fro_se;
      }
      const std::pair<bool, double> rank{!(p.cv_to_and_fro <= options_.cv_target), upper_bound(p)};
      if (c == 0 || rank < chosen_rank) {
        chosen_rank = rank;
        chosen = c;
      }
    }
    return settings[chosen];
  }

  // The spans of speed within the target in the scan, ends interpolated linearly in CV.
  void within_target(std::size_t w, SettingChartRow& row) {
    const std::span<const double> cv = scan_cv(w);
    const std::size_t points = cv.size();
    const double target = options_.cv_target;
    const auto crossing = [&](std::size_t k) {  // between scan points k and k + 1
      const double a = cv[k], b = cv[k + 1];
      if (!std::isfinite(a) || !std::isfinite(b)) return std::isfinite(a) ? chart_.scan_rpm[k] : chart_.scan_rpm[k + 1];
      return chart_.scan_rpm[k] + (target - a) / (b - a) * (chart_.scan_rpm[k + 1] - chart_.scan_rpm[k]);
    };
    for (std::size_t k = 0; k < points; ++k) {
      if (!(cv[k] <= target)) continue;
      const double low = k == 0 ? chart_.scan_rpm[0] : crossing(k - 1);
      std::size_t last = k;
      while (last + 1 < points && cv[last + 1] <= target) ++last;
      const double high = last + 1 == points ? chart_.scan_rpm[last] : crossing(last);
      row.within_target_rpm.emplace_back(low, high);
      k = last;
    }
  }

  void fill_row(std::size_t w, const ChartSetting& chosen, SettingChartRow& row) {
    const Prediction& p = search_.at(chosen.rpm, chosen.turn_rad, widths_m_[w], true);
    row.rpm = chosen.rpm;
    row.drop_point_turn_rad = chosen.turn_rad;
    row.bout_width_m = p.bout_width_m;
    row.cv_to_and_fro = p.cv_to_and_fro;
    row.cv_to_and_fro_se = p.cv_to_and_fro_se;
    row.cv_racetrack = p.cv_racetrack;
    row.cv_racetrack_se = p.cv_racetrack_se;
    row.working_width_to_and_fro_m = p.working_width_to_and_fro_m;
    row.working_width_to_and_fro_se_m = p.working_width_to_and_fro_se_m;
    row.sample_count = p.sample_count;
  }

  // In a crosswind on a two-disc machine: each disc's own setting that compensates it at the chosen one.
  void compensate(std::size_t w, const ChartSetting& chosen, SettingChartRow& row) {
    if (options_.wind_x_m_s == 0.0 || predictor_.machine().disc_count != 2) return;
    Prediction compensated;
    const WindCompensation found = compensate_wind(predictor_, search_.request(chosen.rpm, chosen.turn_rad, widths_m_[w]),
                                                   compensated, predictor_.own_workspace());
    chart_.predictions += found.predictions;
    if (found.status != PredictStatus::kOk) return;
    row.compensated = true;
    row.compensated_discs[kLeftDisc] = found.discs[kLeftDisc];
    row.compensated_discs[kRightDisc] = found.discs[kRightDisc];
    row.compensated_cv = compensated.cv_to_and_fro;
    row.compensated_cv_se = compensated.cv_to_and_fro_se;
  }

  Predictor& predictor_;
  std::span<const double> widths_m_;
  const SettingChartOptions& options_;
  SettingChart& chart_;
  Search search_;
  std::vector<double> grid_cv_;  // grid_cv_[(t * speeds + k) * widths + w]
};

}  // namespace

SettingChart setting_chart(Predictor& predictor, std::string_view material, std::span<const double> widths_m,
                           const SettingChartOptions& options) {
  const std::optional<std::size_t> index = predictor.find_material(material);
  if (!index) throw std::invalid_argument("material '" + std::string(material) + "' is not in the table");
  check_chart_options(widths_m, options);
  SettingChart chart;
  chart.min_rpm = predictor.min_rpm(*index);
  chart.max_rpm = predictor.max_rpm(*index);
  chart.grid_rpm = speed_grid(predictor.row_rpm(*index), kChartGridStep_rpm);
  chart.grid_drop_point_turn_rad = drop_point_grid(options.max_drop_point_turn_rad, options.drop_point_step_rad,
                                                   predictor.drop_point_turn_range());
  chart.scan_rpm = speed_grid(predictor.row_rpm(*index), kChartScanStep_rpm);
  chart.scan_cv_to_and_fro.resize(widths_m.size() * chart.scan_rpm.size());
  ChartBuilder builder(predictor, material, widths_m, options, chart);
  builder.grid_cvs();
  for (std::size_t w = 0; w < widths_m.size(); ++w) chart.rows.push_back(builder.row(w));
  return chart;
}

}  // namespace spread::predict
