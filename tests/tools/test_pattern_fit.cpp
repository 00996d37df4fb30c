// Pattern calibration: a synthetic tray test made by the model itself (known parameters, seeded noise)
// is fitted back; the fitted values must lie within 3 standard errors of the truth, the standard errors
// must be small enough to mean something, and the original table file must be left byte-identical.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "libspread/calibration/calibrated_table.hpp"
#include "libspread/calibration/normal_noise.hpp"
#include "libspread/calibration/pattern_fit.hpp"
#include "libspread/tables/table_reader.hpp"
#include "tools_test_support.hpp"

namespace cal = spread::calibration;
using spread::kPi;

namespace {

constexpr int kSamples = 256;  // per model evaluation: enough for a smooth pattern, fast enough for a test

cal::PatternFitOptions fast_options() {
  cal::PatternFitOptions o;
  o.model.sample_count = kSamples;
  o.model.flight = cal::pattern_flight_settings(4e-3);
  return o;
}

// Trays over ±16 m (64 trays of 0.5 m), masses in grams from the model at `truth`, total 400 g, with
// Gaussian noise of 2 % of the largest tray plus 0.2 g (the scale reading).
std::string synthetic_tray_test(const cal::PatternSetup& setup, const cal::PatternParameters& truth,
                                const std::string& path) {
  spread::metrics::TrayLayout layout{0.5, 64};
  const cal::PatternModel model(setup, layout, fast_options().model);
  const std::vector<double> fraction = model.tray_fractions(truth);
  double largest = 0.0;
  for (double f : fraction) largest = std::max(largest, f);
  cal::NormalNoise noise(20261122);
  std::vector<double> position, mass_g;
  for (int k = 0; k < layout.tray_count; ++k) {
    position.push_back(layout.centre_m(k));
    const double clean = 400.0 * fraction[static_cast<std::size_t>(k)];
    mass_g.push_back(std::max(0.0, clean + (0.02 * 400.0 * largest + 0.2) * noise.next()));
  }
  cal::write_tray_csv(path, position, {mass_g}, {"synthetic tray test for test_pattern_fit"});
  return path;
}

}  // namespace

// One table and one synthetic tray test for the whole suite (each takes a fraction of a second, but
// there is no need to redo them).
class PatternFit : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    table_ = new spread::testing::TempPath("urea.sqlite");
    spread::testing::build_urea_table(table_->path(), kSamples);
    contents_ = new spread::tables::TableContents(spread::tables::read_table_file(table_->path()));
    setup_ = new cal::PatternSetup(cal::pattern_setup_from_table(*contents_, "Urea", 500.0));
    csv_ = new spread::testing::TempPath("synthetic.csv");
    test_ = new cal::TrayTest(cal::read_tray_csv(synthetic_tray_test(*setup_, kTruth, csv_->path())));
  }
  static void TearDownTestSuite() {
    delete test_;
    delete csv_;
    delete setup_;
    delete contents_;
    delete table_;
  }

  static void report(const cal::PatternFitResult& fit) {
    std::printf("fit: %d iterations, %d evaluations; rms %.5f -> %.5f (fraction), %s\n", fit.iterations,
                fit.model_evaluations, fit.initial_residual_rms_fraction, fit.residual_rms_fraction,
                fit.stop_reason.c_str());
    std::printf("mu %.4f +- %.4f (true %.4f), k %.4f +- %.4f (true %.4f), offset %.3f +- %.3f deg (true %.3f)\n",
                fit.fitted.friction_wall, fit.standard_error.friction_wall, kTruth.friction_wall,
                fit.fitted.drag_diameter_factor, fit.standard_error.drag_diameter_factor, kTruth.drag_diameter_factor,
                fit.fitted.launch_angle_offset_rad * 180 / kPi, fit.standard_error.launch_angle_offset_rad * 180 / kPi,
                kTruth.launch_angle_offset_rad * 180 / kPi);
    std::printf("correlation mu-k %.3f, mu-offset %.3f, k-offset %.3f\n", fit.correlation[0][1],
                fit.correlation[0][2], fit.correlation[1][2]);
  }

  static inline const cal::PatternParameters kTruth{0.30, 1.25, 4.0 * kPi / 180.0};
  static inline spread::testing::TempPath* table_ = nullptr;
  static inline spread::tables::TableContents* contents_ = nullptr;
  static inline cal::PatternSetup* setup_ = nullptr;
  static inline spread::testing::TempPath* csv_ = nullptr;
  static inline cal::TrayTest* test_ = nullptr;
};

TEST_F(PatternFit, SetupComesFromTheStoredScene) {
  EXPECT_EQ(setup_->machine.vane_end_radius_m, 0.29);
  EXPECT_EQ(setup_->inlet.angle_rad, 1.0);
  EXPECT_EQ(setup_->material.name, "Urea");
  EXPECT_EQ(setup_->material.friction_wall, 0.4);
  EXPECT_EQ(test_->layout.tray_count, 64);
}

TEST_F(PatternFit, AllThreeParametersWithinThreeSigma) {
  const cal::PatternFitResult fit = cal::fit_pattern(*setup_, *test_, fast_options());
  report(fit);
  EXPECT_TRUE(fit.converged) << fit.stop_reason;
  EXPECT_LT(fit.residual_rms_fraction, 0.5 * fit.initial_residual_rms_fraction);
  EXPECT_LT(std::abs(fit.fitted.friction_wall - kTruth.friction_wall), 3.0 * fit.standard_error.friction_wall);
  EXPECT_LT(std::abs(fit.fitted.drag_diameter_factor - kTruth.drag_diameter_factor),
            3.0 * fit.standard_error.drag_diameter_factor);
  EXPECT_LT(std::abs(fit.fitted.launch_angle_offset_rad - kTruth.launch_angle_offset_rad),
            3.0 * fit.standard_error.launch_angle_offset_rad);
  EXPECT_LT(fit.standard_error.drag_diameter_factor, 0.05);
}

TEST_F(PatternFit, FrictionAndDragWithOffsetFixedAreTight) {
  cal::PatternFitOptions options = fast_options();
  options.use_start = true;
  options.start = {0.4, 1.0, kTruth.launch_angle_offset_rad};
  options.fit_angle_offset = false;
  const cal::PatternFitResult fit = cal::fit_pattern(*setup_, *test_, options);
  report(fit);
  EXPECT_TRUE(fit.converged) << fit.stop_reason;
  EXPECT_EQ(fit.standard_error.launch_angle_offset_rad, 0.0);
  EXPECT_LT(std::abs(fit.fitted.friction_wall - kTruth.friction_wall), 3.0 * fit.standard_error.friction_wall);
  EXPECT_LT(std::abs(fit.fitted.drag_diameter_factor - kTruth.drag_diameter_factor),
            3.0 * fit.standard_error.drag_diameter_factor);
  // Meaningful: each uncertainty well below the distance from the start to the truth (0.1 and 0.25).
  EXPECT_LT(fit.standard_error.friction_wall, 0.02);
  EXPECT_LT(fit.standard_error.drag_diameter_factor, 0.05);
}

TEST_F(PatternFit, CalibratedMaterialGoesIntoNewFileAndOriginalIsUntouched) {
  const std::vector<char> before = spread::testing::file_bytes(table_->path());
  spread::testing::TempPath output("calibrated.sqlite");
  cal::CalibratedTableRequest request;
  request.original_path = table_->path();
  request.output_path = output.path();
  request.material = "Urea";
  request.new_material_name = cal::calibrated_material_name("Urea", "2026-11-22");
  request.parameters = kTruth;
  request.calibration_json = "{\"test\":true}";
  const cal::CalibratedTableSummary summary = cal::write_calibrated_table(request);
  EXPECT_EQ(summary.rpm_rows, (std::vector<double>{500.0, 600.0}));
  EXPECT_EQ(summary.samples_per_run, kSamples);
  EXPECT_EQ(spread::testing::file_bytes(table_->path()), before);

  const spread::tables::TableContents copy = spread::tables::read_table_file(output.path());
  ASSERT_EQ(copy.materials.size(), 2u);
  const spread::tables::Material& calibrated = copy.materials[1];
  EXPECT_EQ(calibrated.name, "Urea (calibrated 2026-11-22)");
  EXPECT_NEAR(calibrated.friction_wall, 0.30, 1e-12);
  EXPECT_NEAR(calibrated.diameter_mean_m, 1.25 * 3.2e-3, 1e-12);
  EXPECT_NEAR(calibrated.density_kg_m3, 1257.0 / (1.25 * 1.25 * 1.25), 1e-9);
  EXPECT_EQ(copy.runs.size(), 4u);
  // The original material's runs are copied unchanged.
  for (std::size_t i = 0; i < contents_->runs.size(); ++i) {
    const auto& a = contents_->runs[i];
    const auto& b = copy.runs[i];
    ASSERT_EQ(a.material, b.material);
    EXPECT_EQ(a.samples.size(), b.samples.size());
    EXPECT_EQ(0, std::memcmp(a.samples.data(), b.samples.data(), a.samples.size() * sizeof a.samples[0]));
  }
  // The calibrated runs are the fitted model's launches, turned by the offset.
  const std::vector<spread::tables::LaunchSample> expected = cal::calibrated_launch_samples(*setup_, kTruth, 500.0, kSamples);
  const spread::tables::Run& run = copy.runs[2];
  ASSERT_EQ(run.material, calibrated.name);
  ASSERT_EQ(run.samples.size(), expected.size());
  EXPECT_EQ(0, std::memcmp(run.samples.data(), expected.data(), expected.size() * sizeof expected[0]));

  // Never overwrite: not the existing output, not the original.
  EXPECT_THROW(cal::write_calibrated_table(request), std::invalid_argument);
  request.output_path = table_->path();
  EXPECT_THROW(cal::write_calibrated_table(request), std::invalid_argument);
  EXPECT_EQ(spread::testing::file_bytes(table_->path()), before);
}

TEST_F(PatternFit, ModelIsSmoothInTheParameters) {
  // The fit differentiates the model numerically: halving the step must halve a forward difference's
  // change (first order) — a step-function model (no kernel, adaptive steps) fails this.
  const cal::PatternModel model(*setup_, test_->layout, fast_options().model);
  auto distance = [&](double dmu) {
    const std::vector<double> a = model.tray_fractions(kTruth);
    cal::PatternParameters p = kTruth;
    p.friction_wall += dmu;
    const std::vector<double> b = model.tray_fractions(p);
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += (b[i] - a[i]) * (b[i] - a[i]);
    return std::sqrt(sum);
  };
  const double big = distance(2e-3), small = distance(1e-3);
  EXPECT_GT(big, 0.0);
  EXPECT_NEAR(small / big, 0.5, 0.02);
}
