#include "tools/spread/setting_guidance.hpp"

#include <cmath>

#include "tools/spread/next_steps.hpp"
#include "tools/spread/number_format.hpp"

namespace spread::cli {
namespace {

// " ± x" with the 95 % half-interval (1.96 standard errors), or nothing when it is undefined.
std::string plus_minus_percent(double standard_error) {
  return std::isfinite(standard_error) ? format(" ± %.2f", 1.96 * 100.0 * standard_error) : "";
}

}  // namespace

SettingGuidance setting_guidance(predict::Predictor& predictor, const predict::PredictionRequest& request) {
  SettingGuidance g;
  const predict::SettingAdjustments adjustments = predict::setting_adjustments(predictor, request);
  if (!(adjustments.present_cv_to_and_fro > request.cv_target)) return g;
  g.adjustments = adjustments;
  // The predicted CV itself: on a calibration's page it stands beside the measured one, and "above the
  // target" without it read as contradicting a measured CV within it.
  g.lines.push_back("predicted for this material and setting, the CV at " +
                    format("%.2f m", adjustments.present_bout_width_m) + " is " +
                    format("%.1f %%", 100.0 * adjustments.present_cv_to_and_fro) + ", above the target " +
                    format("%g %%", 100.0 * request.cv_target) + "; predicted, one setting at a time:");
  for (const predict::SettingAdjustment& a : adjustments.adjustments) {
    std::string what;
    switch (a.setting) {
      case predict::AdjustedSetting::kDiscSpeed: what = "disc speed " + format("%.0f rpm", a.rpm); break;
      case predict::AdjustedSetting::kBoutWidth: what = "bout width " + format("%.2f m", a.bout_width_m); break;
      case predict::AdjustedSetting::kDiscHeight: what = "disc height " + format("%.2f m", a.disc_height_m); break;
    }
    g.lines.push_back("  " + what + ": CV " + format("%.1f %%", 100.0 * a.cv_to_and_fro) +
                      plus_minus_percent(a.cv_to_and_fro_se) + " to-and-fro" +
                      (a.meets_target ? " (meets the target)" : " (still above the target)"));
    // Another bout width at the same rate and speed is another mass flow: the gate moves with it.
    if (a.setting == predict::AdjustedSetting::kBoutWidth) {
      g.lines.push_back("    at " + format("%.2f m", a.bout_width_m) + " " +
                        gate_follows_width(adjustments.present_bout_width_m, a.bout_width_m));
    }
  }
  g.notes = g.lines;
  g.lines.push_back("  (the drop point too: `spread chart` searches it with the speed; vane settings are not in a "
                    "launch table: a table built for another setting predicts them)");
  return g;
}

nlohmann::json setting_guidance_present_json(const SettingGuidance& guidance) {
  if (!guidance.adjustments) return nullptr;
  return {{"bout_width_m", guidance.adjustments->present_bout_width_m},
          {"cv_to_and_fro_percent", 100.0 * guidance.adjustments->present_cv_to_and_fro}};
}

nlohmann::json setting_guidance_json(const SettingGuidance& guidance) {
  if (!guidance.adjustments) return nullptr;
  nlohmann::json list = nlohmann::json::array();
  auto number_or_null = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  for (const predict::SettingAdjustment& a : guidance.adjustments->adjustments) {
    list.push_back({{"setting", predict::to_string(a.setting)},
                    {"rpm", a.rpm},
                    {"bout_width_m", a.bout_width_m},
                    {"disc_height_m", a.disc_height_m},
                    {"cv_to_and_fro_percent", number_or_null(100.0 * a.cv_to_and_fro)},
                    {"cv_to_and_fro_se_percent", number_or_null(100.0 * a.cv_to_and_fro_se)},
                    {"meets_target", a.meets_target}});
    if (a.setting == predict::AdjustedSetting::kBoutWidth) {
      // The gate's change for the same rate (gate_follows_width), as the text states it.
      list.back()["gate_change_percent"] = 100.0 * (a.bout_width_m / guidance.adjustments->present_bout_width_m - 1.0);
    }
  }
  return list;
}

}  // namespace spread::cli
