#include "libspread/analysis/predict/setting_adjustment.hpp"

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

  const Prediction& now = predict(present);
  out.present_cv_to_and_fro = now.cv_to_and_fro;
  out.present_bout_width_m = now.bout_width_m;
  out.present_disc_height_m = now.disc_height_m;
  const double working_width_m = now.working_width_to_and_fro_m;

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

  // Bout width: the working width at the present rpm, where the CV is at the target.
  if (working_width_m > 0.0) {
    r = present;
    r.bout_width_m = std::floor(working_width_m / present.tray_width_m + 1e-9) * present.tray_width_m;
    if (r.bout_width_m > 0.0) out.adjustments.push_back(adjustment(AdjustedSetting::kBoutWidth, r, predict(r)));
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
