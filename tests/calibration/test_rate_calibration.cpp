// Catch test → flow factor → gate opening for a target rate, and back.
#include <gtest/gtest.h>

#include <stdexcept>

#include "libspread/analysis/calibration/rate_calibration.hpp"

namespace cal = spread::calibration;

TEST(RateCalibration, RateFormulaByHand) {
  // 300 kg/ha over 24 m at 12 km/h: 24 m · 12/3.6 m/s = 80 m²/s = 0.008 ha/s → 2.4 kg/s.
  EXPECT_NEAR(cal::required_mass_flow_kg_s(300.0, 24.0, 12.0), 2.4, 1e-12);
  EXPECT_NEAR(cal::application_rate_kg_ha(2.4, 24.0, 12.0), 300.0, 1e-9);
}

TEST(RateCalibration, FlowFactorFromOneCatchRoundTrips) {
  // 25 kg in 60 s at opening 40: 0.41667 kg/s, factor 0.0104167 kg/s per unit.
  const cal::MeteringModel model = cal::metering_from_catch({25.0, 60.0, 40.0});
  EXPECT_NEAR(model.flow_factor_kg_s_per_unit, 25.0 / 60.0 / 40.0, 1e-15);
  EXPECT_EQ(model.zero_opening, 0.0);
  for (double rate : {80.0, 150.0, 300.0, 650.0}) {
    const double q = cal::required_mass_flow_kg_s(rate, 24.0, 12.0);
    const double opening = cal::gate_opening_for_mass_flow(model, q);
    EXPECT_NEAR(cal::mass_flow_at_opening_kg_s(model, opening), q, 1e-12);
    EXPECT_NEAR(cal::application_rate_kg_ha(cal::mass_flow_at_opening_kg_s(model, opening), 24.0, 12.0), rate, 1e-9);
  }
  // 2.4 kg/s is 5.76 times the caught 0.41667 kg/s: a line through zero needs 5.76 × 40 = 230.4.
  EXPECT_NEAR(cal::gate_opening_for_mass_flow(model, 2.4), 230.4, 1e-9);
}

TEST(RateCalibration, TwoPointFitRecoversLineWithDeadZone) {
  // True gate: Q = 0.02 kg/s per mm above 5 mm. Catches at 20 mm (0.3 kg/s) and 50 mm (0.9 kg/s).
  const cal::CatchTest a{0.3 * 45.0, 45.0, 20.0};
  const cal::CatchTest b{0.9 * 30.0, 30.0, 50.0};
  const cal::MeteringModel model = cal::metering_from_two_catches(a, b);
  EXPECT_NEAR(model.flow_factor_kg_s_per_unit, 0.02, 1e-12);
  EXPECT_NEAR(model.zero_opening, 5.0, 1e-9);
  EXPECT_EQ(cal::mass_flow_at_opening_kg_s(model, 4.0), 0.0);
  EXPECT_NEAR(cal::gate_opening_for_mass_flow(model, 0.5), 30.0, 1e-9);
  // Same fit whichever catch comes first.
  const cal::MeteringModel swapped = cal::metering_from_two_catches(b, a);
  EXPECT_NEAR(swapped.zero_opening, model.zero_opening, 1e-9);
}

TEST(RateCalibration, RateErrorOfCurrentSetting) {
  const cal::MeteringModel model{0.01, 0.0};  // 0.01 kg/s per unit
  // Target 200 kg/ha at 18 m, 10 km/h: Q = 1.0 kg/s → opening 100. At opening 110: 10 % too much.
  const cal::RateSetting s = cal::rate_setting(model, 200.0, 18.0, 10.0, 110.0);
  EXPECT_NEAR(s.required_mass_flow_kg_s, 1.0, 1e-12);
  EXPECT_NEAR(s.required_gate_opening, 100.0, 1e-9);
  EXPECT_NEAR(s.current_rate_kg_ha, 220.0, 1e-9);
  EXPECT_NEAR(s.rate_error, 0.10, 1e-12);
}

TEST(RateCalibration, BadInputNamesTheQuantity) {
  try {
    cal::metering_from_catch({25.0, 0.0, 40.0});
    FAIL() << "zero duration accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("duration"), std::string::npos) << e.what();
  }
  EXPECT_THROW(cal::metering_from_two_catches({1.0, 10.0, 20.0}, {2.0, 10.0, 20.0}), std::invalid_argument);
  EXPECT_THROW(cal::metering_from_two_catches({2.0, 10.0, 20.0}, {1.0, 10.0, 30.0}), std::invalid_argument);
  EXPECT_THROW(cal::required_mass_flow_kg_s(-1.0, 24.0, 12.0), std::invalid_argument);
}
