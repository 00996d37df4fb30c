// What a technician types beside a test — tray area, rate, bout width, speed, catch mass and time —
// outside what a field can be is refused naming the range and, where one fits, the unit it was typed in.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "libspread/analysis/calibration/field_ranges.hpp"

namespace cal = spread::calibration;

TEST(FieldRanges, TheUsualValuesPass) {
  EXPECT_EQ(cal::field_range_problem(cal::kTrayAreaRange, "--tray-area", 0.25), "");
  EXPECT_EQ(cal::field_range_problem(cal::kRateRange, "--rate-kg-ha", 300.0), "");
  EXPECT_EQ(cal::field_range_problem(cal::kBoutWidthRange, "--width", 24.0), "");
  EXPECT_EQ(cal::field_range_problem(cal::kSpeedRange, "--speed", 12.0), "");
  EXPECT_EQ(cal::field_range_problem(cal::kCatchMassRange, "--mass", 25.0), "");
  EXPECT_EQ(cal::field_range_problem(cal::kCatchTimeRange, "--time", 60.0), "");
}

TEST(FieldRanges, TheLikelyUnitIsNamed) {
  EXPECT_EQ(cal::field_range_problem(cal::kTrayAreaRange, "--tray-area", 2500.0),
            "--tray-area 2500: a collecting tray's area is 0.01-0.5 m²; 2500 cm² is 0.25 m² — give it in m²");
  EXPECT_NE(cal::field_range_problem(cal::kTrayAreaRange, "--tray-area", 250000.0).find("250000 mm² is 0.25 m²"),
            std::string::npos);
  EXPECT_NE(cal::field_range_problem(cal::kRateRange, "--rate-kg-ha", 0.3).find("0.3 t/ha is 300 kg/ha"), std::string::npos);
  EXPECT_NE(cal::field_range_problem(cal::kRateRange, "--rate-kg-ha", 300000.0).find("300000 g/ha is 300 kg/ha"),
            std::string::npos);
  EXPECT_NE(cal::field_range_problem(cal::kBoutWidthRange, "--width", 2400.0).find("2400 cm is 24 m"), std::string::npos);
  EXPECT_NE(cal::field_range_problem(cal::kCatchMassRange, "--mass", 25000.0).find("25000 g is 25 kg"), std::string::npos);
  EXPECT_NE(cal::field_range_problem(cal::kSpeedRange, "--speed", 12000.0).find("12000 m/h is 12 km/h"), std::string::npos);
}

TEST(FieldRanges, AbsurdNumbersAreRefusedPlainly) {
  for (const double absurd : {1e300, 1e-300, 1e62, -5.0, 0.0, std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::quiet_NaN()}) {
    const std::string problem = cal::field_range_problem(cal::kRateRange, "--rate-kg-ha", absurd);
    EXPECT_EQ(problem.rfind("--rate-kg-ha ", 0), 0u) << absurd;
    EXPECT_NE(problem.find("an application rate is 1-20000 kg/ha"), std::string::npos) << problem;
    // A number of sixty digits is shown in a dozen characters at most.
    EXPECT_LT(problem.size(), 80u) << problem;
  }
}
