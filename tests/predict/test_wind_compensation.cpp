// Wind compensation on the synthetic table: in a crosswind the discs set apart lower the CV at the bout
// (never raise it), stay within the table and the limits, and the answer is the predictor's own at that
// setting; requests it cannot serve are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "libspread/analysis/predict/wind_compensation.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace spread::predict {
namespace {

PredictionRequest windy(double wind_x_m_s) {
  PredictionRequest r;
  r.material = "can";
  r.rpm = 650.0;
  r.bout_width_m = 12.0;
  r.wind_x_m_s = wind_x_m_s;
  return r;
}

TEST(WindCompensation, LowersTheCvWithinTheLimitsAndIsThePredictorsOwn) {
  Predictor predictor(testing::synthetic_contents());
  PredictorWorkspace workspace(predictor);
  for (const double wind_x_m_s : {3.0, -3.0}) {
    Prediction out;
    const WindCompensationLimits limits;
    const WindCompensation found = compensate_wind(predictor, windy(wind_x_m_s), out, workspace, limits);
    ASSERT_EQ(found.status, PredictStatus::kOk) << wind_x_m_s;
    EXPECT_LT(found.cv, found.present_cv) << wind_x_m_s;
    for (const DiscSetting& disc : found.discs) {
      EXPECT_LE(std::abs(disc.rpm - 650.0), limits.max_speed_offset_rpm);
      EXPECT_LE(std::abs(disc.drop_point_turn_rad), limits.max_drop_point_turn_rad);
      EXPECT_GE(disc.rpm, 500.0);
      EXPECT_LE(disc.rpm, 800.0);
    }
    EXPECT_NE(found.discs[kLeftDisc], found.discs[kRightDisc]);
    EXPECT_LT(found.predictions, 250);
    EXPECT_TRUE(std::isfinite(out.cv_to_and_fro_se));
    // The answer is a prediction at that setting like any other, the discs swapping settings on the return
    // pass (which meets the wind from the other side).
    PredictionRequest at = windy(wind_x_m_s);
    at.return_pass = ReturnPassSettings::kSwapped;
    at.rpm = 0.0;
    at.disc_rpm = {found.discs[kLeftDisc].rpm, found.discs[kRightDisc].rpm};
    at.disc_drop_point_turn_rad = {found.discs[kLeftDisc].drop_point_turn_rad, found.discs[kRightDisc].drop_point_turn_rad};
    Prediction again;
    ASSERT_EQ(predictor.predict(at, again), PredictStatus::kOk);
    EXPECT_EQ(again.cv_to_and_fro, out.cv_to_and_fro);
    // Swapped with the heading in a lateral wind, the return pass lands as the outgoing one: racetrack.
    EXPECT_EQ(out.return_pass, ReturnPass::kRacetrack);
    EXPECT_EQ(out.cv_to_and_fro, out.cv_racetrack);
    EXPECT_EQ(again.cv_to_and_fro_se, out.cv_to_and_fro_se);
  }
  // A wind from the other side asks for the mirror-image answer.
  Prediction right_wind, left_wind;
  const WindCompensation a = compensate_wind(predictor, windy(3.0), right_wind, workspace);
  const WindCompensation b = compensate_wind(predictor, windy(-3.0), left_wind, workspace);
  for (int d = 0; d < 2; ++d) {
    EXPECT_NEAR(a.discs[d].rpm, b.discs[1 - d].rpm, 1e-6) << d;
    EXPECT_NEAR(a.discs[d].drop_point_turn_rad, b.discs[1 - d].drop_point_turn_rad, 1e-9) << d;
  }
  EXPECT_NEAR(a.cv, b.cv, 1e-9);
}

TEST(WindCompensation, RefusesWhatItCannotServe) {
  Predictor predictor(testing::synthetic_contents());
  PredictorWorkspace workspace(predictor);
  Prediction out;
  PredictionRequest no_bout = windy(3.0);
  no_bout.bout_width_m = 0.0;
  EXPECT_EQ(compensate_wind(predictor, no_bout, out, workspace).status, PredictStatus::kOutOfRange);
  PredictionRequest outside = windy(3.0);
  outside.rpm = 900.0;
  EXPECT_EQ(compensate_wind(predictor, outside, out, workspace).status, PredictStatus::kRpmOutsideTable);
  Predictor single(testing::synthetic_contents(testing::default_synthetic_materials(), 1));
  PredictorWorkspace single_workspace(single);
  EXPECT_EQ(compensate_wind(single, windy(3.0), out, single_workspace).status, PredictStatus::kOutOfRange);
}

}  // namespace
}  // namespace spread::predict
