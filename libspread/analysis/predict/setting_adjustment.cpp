#include "libspread/analysis/predict/setting_adjustment.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::predict {

const char* to_string(AdjustedSetting setting) {
  switch (setting) {
    case AdjustedSetting::kDiscSpeed: return "disc_speed";
    case AdjustedSetting::kBoutWidth: return "bout_width";
    case AdjustedSetting::kDiscHeight: return "disc_height";
  }
  return "?";
}

SettingAdjustments setting_adjustments(Predictor& predictor, const PredictionRequest& present) {
  const std::optional<std::size_t> index = predictor.find_material(present.material);
  if (!index) throw std::invalid_argument("material '" + std::string(present.material) + "' is not in the table");
  if (!(present.bout_width_m > 0.0)) throw std::invalid_argument("setting adjustments need a bout width > 0 m");
  SettingAdjustments out;
  Prediction p;
  auto predict = [&](const PredictionRequest& r) -> const Prediction& {
    const PredictStatus status = predictor.predict(r, p);
    ++out.predictions;
    if (status != PredictStatus::kOk) {
      throw std::invalid_argument(std::string("prediction for the setting adjustments refused: ") + to_string(status));
    }
    return p;
  };
  auto adjustment = [&](AdjustedSetting setting, const PredictionRequest& r, const Prediction& at) {
    SettingAdjustment a;
    a.setting = setting;
    a.rpm = r.rpm;
    a.bout_width_m = at.bout_width_m;
    a.disc_height_m = at.disc_height_m;
    a.cv_to_and_fro = at.cv_to_and_fro;
    a.cv_to_and_fro_se = at.cv_to_and_fro_se;
    a.meets_target = at.cv_to_and_fro <= r.cv_target;
    return a;
  };

  const Prediction now = predict(present);  // a copy: predict() reuses one Prediction
  out.present_cv_to_and_fro = now.cv_to_and_fro;
  out.present_bout_width_m = now.bout_width_m;
  out.present_disc_height_m = now.disc_height_m;

  // Disc speed: the lowest CV at the bout width over the rows' range.
  const double low = predictor.min_rpm(*index), high = predictor.max_rpm(*index);
  PredictionRequest r = present;
  SettingAdjustment best_speed;
  for (int k = 0; k < kAdjustmentScanPoints; ++k) {
    r.rpm = low + (high - low) * k / (kAdjustmentScanPoints - 1);
    const SettingAdjustment a = adjustment(AdjustedSetting::kDiscSpeed, r, predict(r));
    if (k == 0 || a.cv_to_and_fro < best_speed.cv_to_and_fro) best_speed = a;
  }
  out.adjustments.push_back(best_speed);

  // Bout width: the whole-tray bout nearest to the present one inside a band within the target at the
  // present rpm (docs/metrics.md "Effective working width": a pattern may have more than one band).
  {
    const double tray_m = present.tray_width_m;
    double nearest_m = 0.0;
    for (int b = 0; b < now.stored_bands_to_and_fro(); ++b) {
      const PredictedBand& band = now.bands_to_and_fro[b];
      const double first_m = std::ceil(band.lower_m / tray_m - 1e-9) * tray_m;
      const double last_m = std::floor(band.upper_m / tray_m + 1e-9) * tray_m;
      if (last_m < first_m || !(last_m > 0.0)) continue;
      const double candidate_m = std::clamp(present.bout_width_m, first_m, last_m);
      if (nearest_m == 0.0 || std::abs(candidate_m - present.bout_width_m) < std::abs(nearest_m - present.bout_width_m)) {
        nearest_m = candidate_m;
      }
    }
    if (nearest_m > 0.0) {
      r = present;
      r.bout_width_m = nearest_m;
      out.adjustments.push_back(adjustment(AdjustedSetting::kBoutWidth, r, predict(r)));
    }
  }

  // Disc height: a few steps either way, the disc kept at least 0.1 m above the ground.
  SettingAdjustment best_height;
  bool any_height = false;
  for (double step_m : kHeightSteps_m) {
    r = present;
    r.disc_height_m = out.present_disc_height_m + step_m;
    if (r.disc_height_m < 0.1) continue;
    const SettingAdjustment a = adjustment(AdjustedSetting::kDiscHeight, r, predict(r));
    if (!any_height || a.cv_to_and_fro < best_height.cv_to_and_fro) best_height = a;
    any_height = true;
  }
  if (any_height) out.adjustments.push_back(best_height);
  return out;
}

}  // namespace spread::predict
