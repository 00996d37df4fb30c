// What to adjust when the CV at the bout width is above the target: every suggestion is the predictor's
// own answer at the setting it names, and the disc-speed one is the best of the rpm scan.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "libspread/analysis/predict/setting_adjustment.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace spread::predict {
namespace {

TEST(SettingAdjustment, EachSuggestionIsThePredictorsOwnAnswer) {
  Predictor predictor(testing::synthetic_contents());
  PredictionRequest present;
  present.material = "can";
  present.rpm = 500.0;
  Prediction p;
  ASSERT_EQ(predictor.predict(present, p), PredictStatus::kOk);
  // A bout 3 m wider than the working width at 500 rpm: its CV is above the target.
  present.bout_width_m = p.working_width_to_and_fro_m + 3.0;
  const SettingAdjustments a = setting_adjustments(predictor, present);
  ASSERT_GT(a.present_cv_to_and_fro, present.cv_target);
  ASSERT_EQ(a.adjustments.size(), 3u);
  EXPECT_EQ(a.adjustments[0].setting, AdjustedSetting::kDiscSpeed);
  EXPECT_EQ(a.adjustments[1].setting, AdjustedSetting::kBoutWidth);
  EXPECT_EQ(a.adjustments[2].setting, AdjustedSetting::kDiscHeight);
  for (const SettingAdjustment& s : a.adjustments) {
    PredictionRequest r = present;
    r.rpm = s.rpm;
    r.bout_width_m = s.bout_width_m;
    r.disc_height_m = s.disc_height_m;
    ASSERT_EQ(predictor.predict(r, p), PredictStatus::kOk) << to_string(s.setting);
    EXPECT_EQ(p.cv_to_and_fro, s.cv_to_and_fro) << to_string(s.setting);
    EXPECT_EQ(s.meets_target, p.cv_to_and_fro <= present.cv_target) << to_string(s.setting);
  }
  // The disc speed: no rpm of the scan gives a lower CV at the bout width.
  for (int k = 0; k < kAdjustmentScanPoints; ++k) {
    PredictionRequest r = present;
    r.rpm = 500.0 + 300.0 * k / (kAdjustmentScanPoints - 1);
    ASSERT_EQ(predictor.predict(r, p), PredictStatus::kOk);
    EXPECT_GE(p.cv_to_and_fro, a.adjustments[0].cv_to_and_fro) << r.rpm;
  }
  // The bout width: the working width at 500 rpm in whole trays, narrower than the bout asked.
  EXPECT_LT(a.adjustments[1].bout_width_m, present.bout_width_m);
  EXPECT_NEAR(std::fmod(a.adjustments[1].bout_width_m, present.tray_width_m), 0.0, 1e-9);
  EXPECT_EQ(a.adjustments[1].rpm, 500.0);
  // The disc height: within 0.2 m of the table's.
  EXPECT_LE(std::abs(a.adjustments[2].disc_height_m - a.present_disc_height_m), 0.2 + 1e-12);
}

TEST(SettingAdjustment, BadInputIsRefused) {
  Predictor predictor(testing::synthetic_contents());
  PredictionRequest r;
  r.material = "sand";
  r.rpm = 600.0;
  r.bout_width_m = 10.0;
  EXPECT_THROW(setting_adjustments(predictor, r), std::invalid_argument);
  r.material = "can";
  r.bout_width_m = 0.0;
  EXPECT_THROW(setting_adjustments(predictor, r), std::invalid_argument);
}

}  // namespace
}  // namespace spread::predict
