// Every column of a tray file is read or refused by name: a pass is never dropped without a word.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "libspread/analysis/calibration/tray_csv.hpp"
#include "tests/calibration/calibration_test_support.hpp"

namespace cal = spread::calibration;

namespace {

using spread::testing::tray_csv_error;

// Five trays, three cells each after the position.
const std::string kRows = "-1.0,1,2,3\n-0.5,2,3,4\n0.0,3,4,5\n0.5,2,3,4\n1.0,1,2,3\n";

}  // namespace

TEST(TrayColumns, UnitInParenthesesIsRead) {
  const cal::TrayTest t = cal::parse_tray_csv("position_m,pass1_g,pass2 (g),Pass3 [g]\n" + kRows, "t.csv");
  EXPECT_EQ(t.mass_columns, (std::vector<std::string>{"pass1_g", "pass2 (g)", "Pass3 [g]"}));
  EXPECT_NEAR(t.mass_kg[0], 2e-3, 1e-15);  // the mean of 1, 2 and 3 g
  const cal::TrayTest kg = cal::parse_tray_csv("Position (m);Mass (kg)\n-1;0,001\n-0.5;0,002\n0;0,003\n0.5;0,002\n1;0,001\n",
                                               "t.csv");
  EXPECT_NEAR(kg.mass_kg[2], 3e-3, 1e-15);
}

TEST(TrayColumns, MassInAnotherUnitIsRefusedByName) {
  const std::string message = tray_csv_error("position_m,pass1_lb,pass2_g,pass3_g\n" + kRows);
  EXPECT_NE(message.find("t.csv:1: column 'pass1_lb': mass in 'lb' is not read — mass columns are in grams (*_g "
                         "or '(g)') or kilograms (*_kg or '(kg)')"),
            std::string::npos)
      << message;
  EXPECT_NE(tray_csv_error("position_m,pass1_g,pass2 (oz),pass3_g\n" + kRows).find("column 'pass2 (oz)': mass in 'oz'"),
            std::string::npos);
}

TEST(TrayColumns, UnknownColumnIsRefusedByName) {
  const std::string message = tray_csv_error("position_m,pass1_g,pass2_g,weight\n" + kRows);
  EXPECT_NE(message.find("t.csv:1: column 'weight' is not one the reader knows"), std::string::npos) << message;
  EXPECT_NE(tray_csv_error("position_cm,pass1_g,pass2_g,pass3_g\n" + kRows).find("column 'position_cm': positions are read in "
                                                                           "metres only"),
            std::string::npos);
}

TEST(TrayColumns, TrayNumberNotesAndEmptyTrailingColumnAreIgnored) {
  const cal::TrayTest t = cal::parse_tray_csv(
      "Tray no.,position_m,mass_g,Notes,\n1,-1.0,1,,\n2,-0.5,2,wet,\n3,0.0,3,,\n4,0.5,2,,\n5,1.0,1,,\n", "t.csv");
  EXPECT_EQ(t.mass_columns, (std::vector<std::string>{"mass_g"}));
  EXPECT_NEAR(t.total_mass_kg(), 9e-3, 1e-15);
  // A column without a name that holds a value is not dropped.
  EXPECT_NE(tray_csv_error("position_m,mass_g,\n-1.0,1,\n-0.5,2,7\n0.0,3,\n0.5,2,\n1.0,1,\n")
                .find("t.csv:3: cell 3 '7' is in a column without a name"),
            std::string::npos);
}
