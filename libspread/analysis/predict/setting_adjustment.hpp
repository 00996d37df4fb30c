#pragma once
// What to adjust when the predicted CV at the bout width is above the target (docs/field-calibration.md,
// "Guidance"): each setting the table can predict, moved on its own, with the CV predicted there — not a
// rule of thumb. From the same Predictor as `spread predict`:
//   disc speed   the rpm of the material's rows (kAdjustmentScanPoints evenly over them) with the lowest
//                to-and-fro CV at the bout width;
//   bout width   the whole-tray bout nearest the present one inside a band of bout widths within the
//                target at the present rpm (Prediction::bands_to_and_fro), and its CV;
//   disc height  the present height ± kHeightSteps, the lowest CV at the bout width.
// A drop point or vane setting is not in a launch table (its runs were made with one feed): a table built
// for another setting predicts that.
#include <cstddef>
#include <limits>
#include <string_view>
#include <vector>

#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

inline constexpr int kAdjustmentScanPoints = 13;
inline constexpr double kHeightSteps_m[] = {-0.2, -0.1, 0.1, 0.2};

enum class AdjustedSetting { kDiscSpeed, kBoutWidth, kDiscHeight };
const char* to_string(AdjustedSetting setting);

struct SettingAdjustment {
  AdjustedSetting setting = AdjustedSetting::kDiscSpeed;
  // The settings of the suggestion (the unadjusted ones as now).
  double rpm = 0.0;
  double bout_width_m = 0.0;
  double disc_height_m = 0.0;
  // Predicted there, fractions, with their standard errors over the launch samples.
  double cv_to_and_fro = std::numeric_limits<double>::quiet_NaN();
  double cv_to_and_fro_se = std::numeric_limits<double>::quiet_NaN();
  bool meets_target = false;  // cv_to_and_fro <= the target
};

struct SettingAdjustments {
  double present_cv_to_and_fro = 0.0;  // at the present settings
  double present_bout_width_m = 0.0;   // the bout width as evaluated (whole trays)
  double present_disc_height_m = 0.0;
  std::vector<SettingAdjustment> adjustments;  // disc speed, bout width, disc height (those that exist)
  int predictions = 0;
};

// `request`: the present settings (rpm, bout_width_m > 0, disc height, CV target, tray width, kernel).
// Throws std::invalid_argument for an unknown material, a bout width of 0 or a refused prediction (with
// its status).
SettingAdjustments setting_adjustments(Predictor& predictor, const PredictionRequest& request);

}  // namespace spread::predict
