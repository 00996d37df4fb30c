#include "libspread/analysis/predict/wind_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>

#include "libspread/analysis/predict/golden_section.hpp"

namespace spread::predict {

WindCompensation compensate_wind(const Predictor& predictor, const PredictionRequest& request, Prediction& out,
                                 PredictorWorkspace& workspace, const WindCompensationLimits& limits) {
  WindCompensation result;
  if (!(request.bout_width_m > 0.0) || predictor.machine().disc_count < 2) {
    result.status = PredictStatus::kOutOfRange;
    return result;
  }
  const DiscSetting left = disc_setting(request, kLeftDisc), right = disc_setting(request, kRightDisc);
  // The present setting, each disc's own from here on.
  PredictionRequest search = request;
  search.rpm = 0.0;
  search.drop_point_turn_rad = 0.0;
  search.standard_errors = false;
  const auto set = [&](double offset_rpm, double turn_rad) {
    search.disc_rpm = {left.rpm + offset_rpm, right.rpm - offset_rpm};
    search.disc_drop_point_turn_rad = {left.drop_point_turn_rad + turn_rad, right.drop_point_turn_rad - turn_rad};
  };
  // The caller's `out` stays unchanged on a refusal: the present setting is tried in `out` only after a
  // request check that writes nothing (a refused predict() leaves its output alone).
  set(0.0, 0.0);
  result.status = predictor.predict(search, out, workspace);
  ++result.predictions;
  if (result.status != PredictStatus::kOk) return result;
  const auto cv_of = [](const Prediction& p) {
    return std::isnan(p.cv_to_and_fro) ? std::numeric_limits<double>::infinity() : p.cv_to_and_fro;
  };
  result.present_cv = cv_of(out);
  const auto cv_at = [&](double offset_rpm, double turn_rad) {
    set(offset_rpm, turn_rad);
    ++result.predictions;
    // Within the bounds below every setting is one the predictor takes.
    return predictor.predict(search, out, workspace) == PredictStatus::kOk ? cv_of(out)
                                                                            : std::numeric_limits<double>::infinity();
  };

  // The bounds: both discs within the material's rows and both drop points within ±π.
  const std::optional<std::size_t> material = predictor.find_material(request.material);
  const double min_rpm = predictor.min_rpm(*material), max_rpm = predictor.max_rpm(*material);
  const double offset_low = std::max({-limits.max_speed_offset_rpm, min_rpm - left.rpm, right.rpm - max_rpm});
  const double offset_high = std::min({limits.max_speed_offset_rpm, max_rpm - left.rpm, right.rpm - min_rpm});
  const double turn_low = std::max({-limits.max_drop_point_turn_rad, -kPi - left.drop_point_turn_rad,
                                    right.drop_point_turn_rad - kPi});
  const double turn_high = std::min({limits.max_drop_point_turn_rad, kPi - left.drop_point_turn_rad,
                                     right.drop_point_turn_rad + kPi});

  double best_offset = 0.0, best_turn = 0.0, best_cv = result.present_cv;
  const double offset_step = (offset_high - offset_low) / (kCoarseSteps - 1);
  const double turn_step = (turn_high - turn_low) / (kCoarseSteps - 1);
  for (int i = 0; i < kCoarseSteps; ++i) {
    for (int j = 0; j < kCoarseSteps; ++j) {
      const double offset = offset_low + i * offset_step, turn = turn_low + j * turn_step;
      const double cv = cv_at(offset, turn);
      if (cv < best_cv) {
        best_cv = cv;
        best_offset = offset;
        best_turn = turn;
      }
    }
  }
  std::tie(best_offset, best_cv) = golden_section_minimum(
      [&](double offset) { return cv_at(offset, best_turn); }, std::max(offset_low, best_offset - offset_step),
      std::min(offset_high, best_offset + offset_step), best_offset, best_cv, limits.speed_tolerance_rpm);
  std::tie(best_turn, best_cv) = golden_section_minimum(
      [&](double turn) { return cv_at(best_offset, turn); }, std::max(turn_low, best_turn - turn_step),
      std::min(turn_high, best_turn + turn_step), best_turn, best_cv, limits.drop_point_tolerance_rad);

  // The answer, with its standard errors.
  set(best_offset, best_turn);
  search.standard_errors = request.standard_errors;
  predictor.predict(search, out, workspace);
  ++result.predictions;
  result.speed_offset_rpm = best_offset;
  result.drop_point_turn_rad = best_turn;
  result.discs[kLeftDisc] = out.discs[kLeftDisc];
  result.discs[kRightDisc] = out.discs[kRightDisc];
  result.cv = cv_of(out);
  return result;
}

}  // namespace spread::predict
