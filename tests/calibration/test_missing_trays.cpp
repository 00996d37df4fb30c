// Missing trays (NA or an empty cell): read as missing, left out of the CV instead of counted as empty.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "libspread/analysis/calibration/cv_without_missing.hpp"
#include "libspread/analysis/calibration/tray_analysis.hpp"

namespace cal = spread::calibration;
using spread::metrics::Overlap;

namespace {

// Eight 0.5 m trays of a flat pattern, 2 g each, across ±2 m; `middle` is the cell of the tray at 0.25 m.
std::string flat_with(const std::string& middle) {
  return "position_m,pass1_g\n-1.75,2\n-1.25,2\n-0.75,2\n-0.25,2\n0.25," + middle + "\n0.75,2\n1.25,2\n1.75,2\n";
}

}  // namespace

TEST(MissingTrays, NaAndEmptyCellsAreReadAsMissing) {
  const cal::TrayTest t = cal::parse_tray_csv(
      "position_m,pass1_g,pass2_g\n-1.0,1,3\n-0.5,NA,na\n0.0,,\n0.5,4,NA\n1.0,5,7\n1.5,1,1\n2.0,1,1\n", "t.csv");
  ASSERT_EQ(t.missing.size(), 7u);
  EXPECT_TRUE(t.missing[1]);
  EXPECT_TRUE(t.missing[2]);
  EXPECT_FALSE(t.missing[3]);  // read in one pass: the mean of the passes read
  EXPECT_NEAR(t.mass_kg[3], 4e-3, 1e-15);
  EXPECT_EQ(t.missing_trays(), 2);
  EXPECT_EQ(t.missing_cells, 5);
  EXPECT_TRUE(std::isnan(t.pass_mass_kg[1][3]));
  EXPECT_EQ(t.missing_positions_m(), (std::vector<double>{-0.5, 0.0}));
  EXPECT_EQ(t.partly_missing_positions_m(), (std::vector<double>{0.5}));
  ASSERT_EQ(t.layout.tray_count, 9);  // -2.0 .. 2.0 m: the left two trays padded
  EXPECT_TRUE(t.layout_missing[3]);   // -0.5 m
  EXPECT_FALSE(t.layout_missing[5]);  // 0.5 m
  EXPECT_FALSE(t.layout_missing[0]);  // padded: empty, not missing
  EXPECT_NEAR(t.total_mass_kg(), 14e-3, 1e-15);
}

TEST(MissingTrays, TooFewTraysReadIsRefused) {
  try {
    cal::parse_tray_csv("position_m,mass_g\n-1.0,1\n-0.5,NA\n0.0,2\n0.5,1\n1.0,1\n", "t.csv");
    FAIL() << "4 of 5 trays read must be refused";
  } catch (const cal::TrayCsvError& e) {
    EXPECT_NE(std::string(e.what()).find("1 of 5 trays are missing"), std::string::npos) << e.what();
  }
}

TEST(MissingTrays, MissingTrayIsLeftOutOfTheCv) {
  // A flat pattern spread at W = 2 m (four trays) is uniform: CV 0. Racetrack passes 2 m apart put two
  // pattern trays on each bout tray; a knocked-over tray entered as 0 leaves a hole: [4, 4, 4, 2] g,
  // mean 3.5, s = 1 → CV = 2/7. Left out, the CV is that of the three bout trays read: 0.
  const cal::TrayTest as_zero = cal::parse_tray_csv(flat_with("0"), "zero.csv");
  const cal::TrayTest as_na = cal::parse_tray_csv(flat_with("NA"), "na.csv");
  const cal::TrayTestAnalysis zero = cal::analyse_tray_test(as_zero, 0.15, 2.0);
  const cal::TrayTestAnalysis na = cal::analyse_tray_test(as_na, 0.15, 2.0);
  EXPECT_NEAR(zero.cv_racetrack, 2.0 / 7.0, 1e-12);
  EXPECT_NEAR(na.cv_racetrack, 0.0, 1e-12);
  EXPECT_NEAR(na.cv_to_and_fro, 0.0, 1e-12);
  // At W = 1 m the two-tray bout keeps one tray read: no spread to estimate (NaN, null in JSON; the
  // working width skips such widths). At W = 4 m (the curve's last point) the bout is the pattern alone.
  EXPECT_TRUE(std::isnan(na.cv_racetrack_curve.front()));
  EXPECT_NEAR(na.cv_racetrack_curve.back(), 0.0, 1e-12);
  EXPECT_GT(zero.cv_racetrack_curve.back(), 0.3);
}

TEST(MissingTrays, NothingMissingIsTheMetricsCv) {
  // With no flag set the weighted CV is metrics::cv_at_trays at every width, cut edges included.
  const cal::TrayTest t =
      cal::parse_tray_csv("position_m,mass_g\n-1.25,0\n-0.75,1\n-0.25,2\n0.25,3\n0.75,4\n1.25,0\n", "ramp.csv");
  const std::vector<bool> none(t.layout_mass_kg.size(), false);
  for (int n = 1; n <= t.layout.tray_count + 2; ++n) {
    for (Overlap overlap : {Overlap::kToAndFro, Overlap::kRacetrack}) {
      EXPECT_NEAR(cal::cv_without_missing(t.layout_mass_kg, none, t.layout, n, overlap),
                  spread::metrics::cv_at_trays(t.layout_mass_kg, t.layout, n, overlap), 1e-12)
          << n << " trays";
    }
  }
}

TEST(MissingTrays, NoCvFromLessThanTwoTraysWeight) {
  // 47 trays of 0.5 m (a triangle), the one at -4.5 m missing. At W = 1 m (two trays; 47 - 2 is odd, so
  // the bout edges cut their trays: weights 1/2, 1, 1/2) the missing tray feeds one edge tray of the
  // to-and-fro bout, leaving 1.5 trays' weight: no CV (cv_without_missing.hpp), not one from 1.5 trays.
  std::string text = "position_m,mass_g\n";
  for (int k = -23; k <= 23; ++k) {
    text += std::to_string(0.5 * k) + "," + (k == -9 ? std::string("NA") : std::to_string(24 - std::abs(k))) + "\n";
  }
  const cal::TrayTest t = cal::parse_tray_csv(text, "t.csv");
  ASSERT_EQ(t.layout.tray_count, 47);
  const cal::TrayTestAnalysis a = cal::analyse_tray_test(t, 0.15, 1.0);
  EXPECT_TRUE(std::isnan(a.cv_to_and_fro)) << a.cv_to_and_fro;
  EXPECT_TRUE(std::isnan(a.cv_to_and_fro_curve[0])) << a.cv_to_and_fro_curve[0];
  // Three trays keep at least two trays' weight: a CV.
  EXPECT_TRUE(std::isfinite(a.cv_to_and_fro_curve[1]));
}
