// A CV above the target is never printed onto it; the chart's bout numbers are those it draws.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "libspread/analysis/plot/cv_text.hpp"
#include "libspread/analysis/plot/transverse_bout.hpp"

namespace plot = spread::plot;

TEST(CvText, AboveTheTargetIsNeverShownAsTheTarget) {
  EXPECT_EQ(plot::cv_percent_text(0.1505, 0.15), "15.05 %");
  EXPECT_EQ(plot::cv_percent_text(0.15004, 0.15), "15.004 %");
  EXPECT_EQ(plot::cv_percent_text(0.1512, 0.15), "15.1 %");
  // At or below the target one decimal, whatever it rounds to.
  EXPECT_EQ(plot::cv_percent_text(0.15, 0.15), "15.0 %");
  EXPECT_EQ(plot::cv_percent_text(0.1496, 0.15), "15.0 %");
  EXPECT_EQ(plot::cv_percent_text(0.1506, std::numeric_limits<double>::quiet_NaN()), "15.1 %");
  EXPECT_EQ(plot::cv_percent_text(std::numeric_limits<double>::quiet_NaN(), 0.15), "none");
  EXPECT_EQ(plot::cv_percent_text(std::numeric_limits<double>::infinity(), 0.15), "empty");
}

TEST(TransverseBout, MissingTraysWithoutACvAreNone) {
  // Twelve trays of 0.5 m, a flat pattern; the middle four missing.
  const std::vector<double> mass(12, 0.01);
  spread::metrics::TrayLayout trays;
  trays.tray_width_m = 0.5;
  trays.tray_count = 12;
  plot::TransverseOptions options;
  options.bout_width_m = 3.0;
  options.mean_band = true;
  const plot::TransverseBout full = plot::transverse_bout(mass, trays, options);
  EXPECT_DOUBLE_EQ(full.bout_width_m, 3.0);
  EXPECT_TRUE(std::isfinite(full.cv));
  EXPECT_EQ(full.unit, "g");
  EXPECT_GT(full.mean_in_unit, 0.0);
  // With trays missing and no CV of the caller's, there is none: not the CV of the missing trays as empty.
  options.missing_trays.assign(12, false);
  for (int k = 4; k < 8; ++k) options.missing_trays[static_cast<std::size_t>(k)] = true;
  EXPECT_TRUE(std::isnan(plot::transverse_bout(mass, trays, options).cv));
  options.bout_cv = 0.07;
  EXPECT_DOUBLE_EQ(plot::transverse_bout(mass, trays, options).cv, 0.07);
  // On a tray area the mean is a rate in kg/ha.
  options.tray_area_m2 = 0.25;
  EXPECT_EQ(plot::transverse_bout(mass, trays, options).unit, "kg/ha");
}
