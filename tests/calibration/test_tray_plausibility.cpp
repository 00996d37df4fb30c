// Numbers a tray test cannot hold — grams in a kilogram column, a tray of 1e300 g, positions in
// centimetres, a bout wider than the trays — are refused with the likely mistake named.
#include <gtest/gtest.h>

#include <string>

#include "libspread/analysis/calibration/tray_csv.hpp"
#include "libspread/analysis/calibration/tray_plausibility.hpp"
#include "tests/calibration/calibration_test_support.hpp"

namespace cal = spread::calibration;

namespace {

using spread::testing::tray_csv_error;

}  // namespace

TEST(TrayPlausibility, HeaviestTrayIsOneKilogram) {
  // 20 t/ha on a 0.5 m² tray.
  EXPECT_DOUBLE_EQ(cal::heaviest_tray_mass_kg(), 1.0);
}

TEST(TrayPlausibility, GramsInAKilogramColumnAreNamed) {
  const std::string message = tray_csv_error("position_m,pass1_kg\n-1.0,0.8\n-0.5,12.4\n0.0,30\n0.5,12\n1.0,1\n");
  EXPECT_NE(message.find("t.csv:3: pass1_kg: 12.4 kg in one tray is 248 t/ha even on a 0.5 m² tray, more than any "
                         "spreader applies (20 t/ha): grams in a kilogram column? 12.4 g is a tray's catch — name "
                         "the column *_g"),
            std::string::npos)
      << message;
  // The same masses in grams are a tray test.
  EXPECT_NO_THROW(cal::parse_tray_csv("position_m,pass1_g\n-1.0,0.8\n-0.5,12.4\n0.0,30\n0.5,12\n1.0,1\n", "t.csv"));
}

TEST(TrayPlausibility, AbsurdAndNonFiniteMassesAreRefused) {
  EXPECT_NE(tray_csv_error("position_m,pass1_g\n-1.0,1\n-0.5,1e300\n0.0,3\n0.5,2\n1.0,1\n")
                .find("t.csv:3: pass1_g: 1e+300 g in one tray is 2e+298 t/ha"),
            std::string::npos);
  EXPECT_NE(tray_csv_error("position_m,pass1_g\n-1.0,1\n-0.5,inf\n0.0,3\n0.5,2\n1.0,1\n").find("t.csv:3: pass1_g: 'inf' is not a number"),
            std::string::npos);
}

TEST(TrayPlausibility, PositionsBeyondAnyThrowAreRefused) {
  // Centimetres read as metres: the first tray is 175 m out.
  const std::string message = tray_csv_error("position_m,mass_g\n-175,1\n-125,2\n-75,3\n-25,4\n25,4\n75,3\n125,2\n175,1\n");
  EXPECT_NE(message.find("t.csv:2: position_m -175 is 175 m from the centre line: no spreader throws beyond about "
                         "50 m, and trays are read up to 100 m — position_m in centimetres or millimetres?"),
            std::string::npos)
      << message;
  EXPECT_NE(tray_csv_error("position_m,mass_g\n-0.002,1\n-0.001,2\n0,3\n0.001,2\n0.002,1\n").find("t.csv:3: the trays are "
                                                                                            "0.001 m apart"),
            std::string::npos);
}

TEST(TrayPlausibility, BoutWiderThanTheTraysIsNamed) {
  const cal::TrayTest t = cal::parse_tray_csv(
      "position_m,mass_g\n-2.75,1\n-2.25,2\n-1.75,3\n-1.25,4\n-0.75,5\n-0.25,6\n0.25,6\n0.75,5\n1.25,4\n1.75,3\n"
      "2.25,2\n2.75,1\n",
      "t.csv");
  EXPECT_EQ(cal::bout_width_problem(t.layout, 6.0), "");
  EXPECT_EQ(cal::bout_width_problem(t.layout, 6.2), "");  // rounds to the 12 trays
  EXPECT_NE(cal::bout_width_problem(t.layout, 500.0).find("500 m is wider than the trays reach (6.00 m"),
            std::string::npos);
}
