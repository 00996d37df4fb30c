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

namespace {

// The adjustments' stages over one context: the present setting's prediction, then each setting moved on
// its own — the disc speed over the rows' range, the bout width into a band within the target, the disc
// height a few steps either way.
class AdjustmentSearch {
 public:
  AdjustmentSearch(Predictor& predictor, const PredictionRequest& present, SettingAdjustments& out)
      : predictor_(predictor), present_(present), out_(out) {}

  // Returns the present prediction (a copy: predict() reuses one Prediction).
  Prediction present() {
    Prediction now = predict(present_);
    out_.present_cv_to_and_fro = now.cv_to_and_fro;
    out_.present_bout_width_m = now.bout_width_m;
    out_.present_disc_height_m = now.disc_height_m;
    return now;
  }

  // Disc speed: the lowest CV at the bout width over the rows' range.
  void speed(double low_rpm, double high_rpm) {
    PredictionRequest r = present_;
    SettingAdjustment best;
    for (int k = 0; k < kAdjustmentScanPoints; ++k) {
      r.rpm = low_rpm + (high_rpm - low_rpm) * k / (kAdjustmentScanPoints - 1);
      const SettingAdjustment a = adjustment(AdjustedSetting::kDiscSpeed, r, predict(r));
      if (k == 0 || a.cv_to_and_fro < best.cv_to_and_fro) best = a;
    }
    out_.adjustments.push_back(best);
  }

  // Bout width: the whole-tray bout nearest to the present one inside a band within the target at the
  // present rpm (docs/metrics.md "Effective working width": a pattern may have more than one band).
  void bout_width(const Prediction& now) {
    const double tray_m = present_.tray_width_m;
    double nearest_m = 0.0;
    for (int b = 0; b < now.stored_bands_to_and_fro(); ++b) {
      const PredictedBand& band = now.bands_to_and_fro[b];
      const double first_m = std::ceil(band.lower_m / tray_m - 1e-9) * tray_m;
      const double last_m = std::floor(band.upper_m / tray_m + 1e-9) * tray_m;
      if (last_m < first_m || !(last_m > 0.0)) continue;
      const double candidate_m = std::clamp(present_.bout_width_m, first_m, last_m);
      if (nearest_m == 0.0 || std::abs(candidate_m - present_.bout_width_m) < std::abs(nearest_m - present_.bout_width_m)) {
        nearest_m = candidate_m;
      }
    }
    if (!(nearest_m > 0.0)) return;
    PredictionRequest r = present_;
    r.bout_width_m = nearest_m;
    out_.adjustments.push_back(adjustment(AdjustedSetting::kBoutWidth, r, predict(r)));
  }

  // Disc height: a few steps either way, the disc kept at least 0.1 m above the ground.
  void height() {
    SettingAdjustment best;
    bool any = false;
    for (double step_m : kHeightSteps_m) {
      PredictionRequest r = present_;
      r.disc_height_m = out_.present_disc_height_m + step_m;
      if (r.disc_height_m < 0.1) continue;
      const SettingAdjustment a = adjustment(AdjustedSetting::kDiscHeight, r, predict(r));
      if (!any || a.cv_to_and_fro < best.cv_to_and_fro) best = a;
      any = true;
    }
    if (any) out_.adjustments.push_back(best);
  }

 private:
  const Prediction& predict(const PredictionRequest& r) {
    const PredictStatus status = predictor_.predict(r, p_);
    ++out_.predictions;
    if (status != PredictStatus::kOk) {
      throw std::invalid_argument(std::string("prediction for the setting adjustments refused: ") + to_string(status));
    }
    return p_;
  }
  static SettingAdjustment adjustment(AdjustedSetting setting, const PredictionRequest& r, const Prediction& at) {
    SettingAdjustment a;
    a.setting = setting;
    a.rpm = r.rpm;
    a.bout_width_m = at.bout_width_m;
    a.disc_height_m = at.disc_height_m;
    a.cv_to_and_fro = at.cv_to_and_fro;
    a.cv_to_and_fro_se = at.cv_to_and_fro_se;
    a.meets_target = at.cv_to_and_fro <= r.cv_target;
    return a;
  }

  Predictor& predictor_;
  const PredictionRequest& present_;
  SettingAdjustments& out_;
  Prediction p_;
};

}  // namespace

SettingAdjustments setting_adjustments(Predictor& predictor, const PredictionRequest& present) {
  const std::optional<std::size_t> index = predictor.find_material(present.material);
  if (!index) throw std::invalid_argument("material '" + std::string(present.material) + "' is not in the table");
  if (!(present.bout_width_m > 0.0)) throw std::invalid_argument("setting adjustments need a bout width > 0 m");
  SettingAdjustments out;
  AdjustmentSearch search(predictor, present, out);
  const Prediction now = search.present();
  search.speed(predictor.min_rpm(*index), predictor.max_rpm(*index));
  search.bout_width(now);
  search.height();
  return out;
}

}  // namespace spread::predict
