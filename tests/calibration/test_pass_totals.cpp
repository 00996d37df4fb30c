// Passes of one tray test that do not carry alike — one typed in kilograms under a grams header, one
// a thousand times heavier, one from another test — are refused naming the pass and the likely unit;
// passes within the scatter of a real test are read as before.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "libspread/analysis/calibration/pass_totals.hpp"
#include "libspread/analysis/calibration/tray_csv.hpp"
#include "tests/calibration/calibration_test_support.hpp"

namespace cal = spread::calibration;

namespace {

using spread::testing::tray_csv_error;

// Five trays of three passes in `unit`, the masses times `scale`; `third` scales the third pass.
std::string three_passes(double third, const char* unit = "g", double scale = 1.0) {
  double masses[5] = {2.0, 11.0, 24.0, 12.0, 3.0};
  for (double& m : masses) m *= scale;
  std::string text = std::string("position_m,pass1_") + unit + ",pass2_" + unit + ",pass3_" + unit + "\n";
  for (int i = 0; i < 5; ++i) {
    char row[160];
    std::snprintf(row, sizeof row, "%.1f,%.6g,%.6g,%.6g\n", -1.0 + 0.5 * i, masses[i], 1.05 * masses[i],
                  third * masses[i]);
    text += row;
  }
  return text;
}

}  // namespace

TEST(PassTotals, AKilogramPassUnderAGramsHeaderIsNamed) {
  const std::string message = tray_csv_error(three_passes(1e-3));
  EXPECT_NE(message.find("pass3_g holds 0.052 g in the trays read in every pass, 1/1025 of the 53.3 g of "
                         "pass1_g, pass2_g"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("kilograms in a grams column? enter it in grams (× 1000)"), std::string::npos) << message;
}

TEST(PassTotals, AThousandfoldPassIsNamedWithItsUnit) {
  // Light trays (tenths of a gram), the third pass in milligrams.
  const std::string mg = tray_csv_error(three_passes(1e3, "g", 1e-2));
  EXPECT_NE(mg.find("pass3_g holds 520 g in the trays read in every pass, 976 times the 0.533 g"), std::string::npos) << mg;
  EXPECT_NE(mg.find("milligrams in a grams column? enter it in grams (÷ 1000)"), std::string::npos) << mg;
  // Under a kilograms header a pass in grams is a thousand times heavier (the trays stay under the
  // heaviest catch, tray_plausibility.hpp, at these small masses).
  const std::string kg = tray_csv_error(three_passes(1e3, "kg", 1e-5));
  EXPECT_NE(kg.find("grams in a kilograms column? enter it in kilograms (÷ 1000)"), std::string::npos) << kg;
}

TEST(PassTotals, APassOffByAFactorOfThreeIsRefusedWithoutAUnit) {
  const std::string message = tray_csv_error(three_passes(3.0));
  EXPECT_NE(message.find("pass3_g holds 156 g"), std::string::npos) << message;
  EXPECT_NE(message.find("a pass from another test, or a column typed in another unit?"), std::string::npos) << message;
}

TEST(PassTotals, PassesWithinTheScatterOfARealTestAreRead) {
  EXPECT_EQ(tray_csv_error(three_passes(0.9)), "");
  EXPECT_EQ(tray_csv_error(three_passes(1.6)), "");
  // The shipped example: three passes 8 % noisy, totals within 3 % of each other.
  EXPECT_NO_THROW(cal::read_tray_csv(std::string(SPREAD_SOURCE_DIR) + "/scenes/field/tray_test_3passes.csv"));
}

TEST(PassTotals, OfTwoPassesTheLikelySlipIsNamed) {
  // Grams test: the lighter pass is the one typed in kilograms.
  const std::string grams = tray_csv_error("position_m,a_g,b_g\n-1,2,0.002\n-0.5,11,0.011\n0,24,0.024\n0.5,12,0.012\n1,3,0.003\n");
  EXPECT_NE(grams.find("b_g holds 0.052 g"), std::string::npos) << grams;
  EXPECT_NE(grams.find("kilograms in a grams column"), std::string::npos) << grams;
}

TEST(PassTotals, AMissingTrayDoesNotCountAgainstItsPass) {
  // The third pass misses the fullest tray: compared over the trays read in every pass, it carries alike.
  EXPECT_EQ(tray_csv_error("position_m,p1_g,p2_g,p3_g\n-1,2,2,2\n-0.5,11,11,11\n0,24,24,NA\n0.5,12,12,12\n1,3,3,3\n"),
            "");
  const cal::TrayTest t =
      cal::parse_tray_csv("position_m,p1_g,p2_g,p3_g\n-1,2,2,2\n-0.5,11,11,11\n0,24,24,NA\n0.5,12,12,12\n1,3,3,3\n", "t.csv");
  const std::vector<double> totals = cal::pass_totals_kg(t);
  ASSERT_EQ(totals.size(), 3u);
  EXPECT_NEAR(totals[2], 0.028, 1e-12);
  EXPECT_NEAR(totals[0], totals[2], 1e-12);
}
