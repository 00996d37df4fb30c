// Implausible catch tests and settings are warned about (the arithmetic itself is tested in
// test_rate_calibration.cpp).
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "libspread/analysis/calibration/rate_plausibility.hpp"

namespace cal = spread::calibration;

namespace {

std::vector<std::string> warnings_of(const cal::CatchTest& first, const std::optional<cal::CatchTest>& second,
                                     double target_kg_ha, double width_m, double speed_km_h) {
  const cal::MeteringModel model =
      second ? cal::metering_from_two_catches(first, *second) : cal::metering_from_catch(first);
  const cal::RateSetting s = cal::rate_setting(model, target_kg_ha, width_m, speed_km_h, first.gate_opening);
  return cal::rate_warnings(first, second, s);
}

}  // namespace

TEST(RatePlausibility, TheDocumentedCatchTestIsQuiet) {
  // 25 kg in 60 s at 40 for 50 kg/ha at 24 m, 12 km/h: set the gate to 38.4 — near the catch.
  EXPECT_TRUE(warnings_of({25.0, 60.0, 40.0}, std::nullopt, 50.0, 24.0, 12.0).empty());
  EXPECT_TRUE(warnings_of({25.0, 60.0, 40.0}, cal::CatchTest{40.0, 60.0, 60.0}, 50.0, 24.0, 12.0).empty());
}

TEST(RatePlausibility, FarExtrapolatedGateWarns) {
  // 5000 kg/ha from the same catch needs a gate of 3840: 96 times the caught opening.
  const auto w = warnings_of({25.0, 60.0, 40.0}, std::nullopt, 5000.0, 24.0, 12.0);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("required gate opening 3840 is far outside the caught opening 40"), std::string::npos) << w[0];
}

TEST(RatePlausibility, GramsTypedAsKilogramsWarns) {
  // 25000 "kg" in 60 s: 417 kg/s, 52,083 kg/ha at the caught opening.
  const auto w = warnings_of({25000.0, 60.0, 40.0}, std::nullopt, 50.0, 24.0, 12.0);
  ASSERT_FALSE(w.empty());
  bool grams = false;
  for (const std::string& text : w) grams |= text.find("is --mass in grams?") != std::string::npos;
  EXPECT_TRUE(grams);
}

TEST(RatePlausibility, CatchesTooCloseTogetherWarn) {
  const auto w = warnings_of({25.0, 60.0, 40.0}, cal::CatchTest{25.1, 60.0, 40.1}, 50.0, 24.0, 12.0);
  bool close = false;
  for (const std::string& text : w) close |= text.find("0.1 gate units apart") != std::string::npos;
  EXPECT_TRUE(close);
}
