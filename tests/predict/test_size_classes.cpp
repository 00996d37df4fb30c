// Size classes through the predictor's public API (libspread/analysis/size_classes): on synthetic rows
// whose granules all leave at the same speeds whatever their size, the classes' shares add up, the larger
// granules land further out (drag decelerates a small granule more), the classes' patterns add up to the
// product's, and the launched mass's d50 is the distribution's.
#include <gtest/gtest.h>

#include <cmath>

#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/analysis/size_classes/launch_sizes.hpp"
#include "libspread/analysis/size_classes/size_class_patterns.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace spread::size_classes {
namespace {

tables::TableContents contents() {
  // 2,000 samples per row, diameters uniform in number over 2.4–3.6 mm (synthetic_table.cpp).
  return testing::synthetic_contents({testing::SyntheticMaterial{"can", 1800.0, {500.0, 700.0}, 2000}});
}

predict::PredictionRequest request() {
  predict::PredictionRequest r;
  r.material = "can";
  r.rpm = 600.0;
  r.bout_width_m = 18.0;
  r.kernel_half_width_m = 0.0;  // point masses: a class's landings fall in the trays the product's do
  return r;
}

const std::vector<double> kBoundaries{2.8, 3.2};

TEST(SizeClasses, LaunchedMassMedianIsTheDistributions) {
  const tables::TableContents c = contents();
  // Number uniform on [2.4, 3.6] mm: mass ∝ d³, so d50⁴ = (2.4⁴ + 3.6⁴) / 2.
  const double d50 = std::pow(0.5 * (std::pow(2.4, 4) + std::pow(3.6, 4)), 0.25);
  const LaunchSizes sizes = launch_sizes(c.runs.front().samples);
  EXPECT_NEAR(sizes.d50_mm, d50, 0.01);
  EXPECT_NEAR(sizes.size_guide_number, 100.0 * d50, 1.0);
  EXPECT_GT(sizes.uniformity_index, 100.0 * 2.4 / 3.6);
  EXPECT_LT(sizes.uniformity_index, 100.0);
}

TEST(SizeClasses, SharesAddUpAndTheCoarseFlyFurther) {
  const SizeClassPatterns p = size_class_patterns(contents(), request(), kBoundaries);
  ASSERT_EQ(p.classes.size(), 3u);
  double share = 0.0;
  std::size_t samples = 0;
  for (const ClassPattern& c : p.classes) {
    ASSERT_EQ(c.status, predict::PredictStatus::kOk) << c.lower_mm;
    share += c.mass_fraction;
    samples += c.sample_count;
    EXPECT_GT(c.cv_to_and_fro, 0.0);
  }
  EXPECT_NEAR(share, 1.0, 1e-12);
  EXPECT_EQ(samples, 4000u);
  // Same launch speeds for every size: the landing radius grows with the diameter, class by class.
  EXPECT_LT(p.classes[0].mean_radius_m, p.classes[1].mean_radius_m);
  EXPECT_LT(p.classes[1].mean_radius_m, p.classes[2].mean_radius_m);
  EXPECT_LT(p.fine.mean_radius_m + 0.05, p.coarse.mean_radius_m);
  EXPECT_NEAR(p.fine.mass_fraction, 0.5, 0.01);
  EXPECT_NEAR(p.coarse.mass_fraction, 0.5, 0.01);
}

// With point masses each landing falls in one tray: the classes' patterns, each scaled to its share and
// aligned by tray centre, add up to the product's (up to the landing grid's own interpolation, a few landings changing trays).
TEST(SizeClasses, ClassPatternsAddUpToTheProducts) {
  predict::Predictor whole(contents());
  predict::Prediction product;
  ASSERT_EQ(whole.predict(request(), product), predict::PredictStatus::kOk);
  const std::vector<double> product_trays(product.tray_mass_fraction.begin(), product.tray_mass_fraction.end());
  const SizeClassPatterns p = size_class_patterns(contents(), request(), kBoundaries);
  std::vector<double> sum(product_trays.size(), 0.0);
  for (const ClassPattern& c : p.classes) {
    // Each layout covers its own landings, an even count of trays about the centre line: the same trays
    // as the product's, fewer where the class does not reach.
    ASSERT_LE(c.trays.tray_count, product.trays.tray_count);
    ASSERT_EQ((product.trays.tray_count - c.trays.tray_count) % 2, 0);
    const auto offset = static_cast<std::size_t>((product.trays.tray_count - c.trays.tray_count) / 2);
    for (std::size_t k = 0; k < c.tray_mass_fraction.size(); ++k) sum[offset + k] += c.tray_mass_fraction[k];
  }
  double l1 = 0.0;
  for (std::size_t k = 0; k < sum.size(); ++k) l1 += std::abs(sum[k] - product_trays[k]);
  EXPECT_LT(l1, 0.02);
}

TEST(SizeClasses, AClassWithoutGranulesHasNoPrediction) {
  const SizeClassPatterns p = size_class_patterns(contents(), request(), std::vector<double>{2.0, 5.0});
  ASSERT_EQ(p.classes.size(), 3u);
  EXPECT_EQ(p.classes[0].sample_count, 0u);
  EXPECT_EQ(p.classes[0].status, predict::PredictStatus::kRpmOutsideTable);
  EXPECT_TRUE(std::isnan(p.classes[0].cv_to_and_fro));
  EXPECT_EQ(p.classes[2].sample_count, 0u);
  EXPECT_NEAR(p.classes[1].mass_fraction, 1.0, 1e-12);
  EXPECT_TRUE(class_contents(contents(), "can", 5.0, 6.0).runs.empty());
}

TEST(SizeClasses, RefusesWhatItCannotJudge) {
  predict::PredictionRequest no_bout = request();
  no_bout.bout_width_m = 0.0;
  EXPECT_THROW(size_class_patterns(contents(), no_bout, kBoundaries), std::invalid_argument);
  EXPECT_THROW(size_class_patterns(contents(), request(), std::vector<double>{3.0, 2.0}), std::invalid_argument);
  predict::PredictionRequest unknown = request();
  unknown.material = "urea";
  EXPECT_THROW(size_class_patterns(contents(), unknown, kBoundaries), std::invalid_argument);
}

}  // namespace
}  // namespace spread::size_classes
