// Pattern calibration: synthetic tray tests made by the model itself (known parameters, seeded noise)
// are fitted back. The reported standard errors must be honest — over many noise seeds the truth lies
// within 2 standard errors in about 95 % of the fits (coverage) — and small enough to mean something; the
// original table file must be left byte-identical.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "libspread/analysis/calibration/calibrated_table.hpp"
#include "libspread/analysis/calibration/fit_acceptance.hpp"
#include "libspread/analysis/calibration/pass_scatter.hpp"
#include "libspread/analysis/calibration/synthetic_tray_test.hpp"
#include "libspread/analysis/calibration/pattern_fit.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "calibration_test_support.hpp"

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

// Trays over ±16 m (64 trays of 0.5 m), masses in grams from the model at `truth` (400 g per pass in the
// trays). The noise of the example file (docs/field-calibration.md): per pass 8 % of each tray plus a
// 0.15 g floor (readings below 0 written as 0), three passes.
cal::TrayNoise example_noise() {
  cal::TrayNoise noise;
  noise.relative_sd = 0.08;
  noise.floor_sd_g = 0.15;
  return noise;
}
constexpr int kPasses = 3;

cal::TrayTest synthetic_test(const cal::PatternModel& model, const cal::PatternParameters& truth, std::uint64_t seed,
                             const std::string& path) {
  const cal::SyntheticTrayTest t = cal::synthetic_tray_test(model, truth, 400.0, kPasses, example_noise(), seed);
  cal::write_tray_csv(path, t.position_m, t.pass_mass_g, {"synthetic tray test for test_pattern_fit"});
  return cal::read_tray_csv(path);
}

std::string write_synthetic_csv(const cal::PatternSetup& setup, const cal::PatternParameters& truth,
                                const std::string& path) {
  const cal::PatternModel model(setup, spread::metrics::TrayLayout{0.5, 64}, fast_options().model);
  synthetic_test(model, truth, 20261122, path);
  return path;
}

// Fits of `seeds` independent synthetic tray tests; per parameter (μ, k, δ) how many put the truth
// within 2 reported standard errors, and the rms of (fitted − truth) / standard error (1 when honest).
struct Coverage {
  int fits = 0;
  std::array<int, 3> within_two{};
  std::array<double, 3> rms_z{};
};
Coverage coverage(const cal::PatternSetup& setup, const cal::PatternParameters& truth,
                  const cal::PatternFitOptions& options, int seeds) {
  const cal::PatternModel model(setup, spread::metrics::TrayLayout{0.5, 64}, options.model);
  spread::testing::TempPath csv("coverage.csv");
  Coverage c;
  const std::array<double, 3> t{truth.friction_wall, truth.drag_diameter_factor, truth.launch_angle_offset_rad};
  for (int seed = 0; seed < seeds; ++seed) {
    const cal::PatternFitResult f =
        cal::fit_pattern(setup, synthetic_test(model, truth, 1000 + static_cast<std::uint64_t>(seed), csv.path()), options);
    const std::array<double, 3> v{f.fitted.friction_wall, f.fitted.drag_diameter_factor, f.fitted.launch_angle_offset_rad};
    const std::array<double, 3> e{f.standard_error.friction_wall, f.standard_error.drag_diameter_factor,
                                  f.standard_error.launch_angle_offset_rad};
    for (std::size_t i = 0; i < 3; ++i) {
      if (!f.fitted_mask[i]) continue;
      const double z = (v[i] - t[i]) / e[i];
      c.within_two[i] += std::abs(z) < 2.0;
      c.rms_z[i] += z * z;
    }
    ++c.fits;
  }
  for (double& z : c.rms_z) z = std::sqrt(z / c.fits);
  std::printf("coverage over %d seeds: within 2 SE mu %d, k %d, offset %d; rms z %.2f, %.2f, %.2f\n", c.fits,
              c.within_two[0], c.within_two[1], c.within_two[2], c.rms_z[0], c.rms_z[1], c.rms_z[2]);
  return c;
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
    test_ = new cal::TrayTest(cal::read_tray_csv(write_synthetic_csv(*setup_, kTruth, csv_->path())));
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

TEST_F(PatternFit, AllThreeParametersFromOneTrayTest) {
  // One seed, all three parameters: the fit converges, explains the pattern, and its k is usable.
  const cal::PatternFitResult fit = cal::fit_pattern(*setup_, *test_, fast_options());
  report(fit);
  EXPECT_TRUE(fit.converged) << fit.stop_reason;
  EXPECT_TRUE(fit.weighted);
  EXPECT_LT(fit.residual_rms_fraction, 0.5 * fit.initial_residual_rms_fraction);
  EXPECT_LT(std::abs(fit.fitted.drag_diameter_factor - kTruth.drag_diameter_factor),
            2.0 * fit.standard_error.drag_diameter_factor);
  EXPECT_LT(fit.standard_error.drag_diameter_factor, 0.05);
  // The variance model sees the relative noise (8 % per pass, three passes: ~4.6 % of a tray).
  EXPECT_GT(std::sqrt(fit.variance_model.relative), 0.02);
  EXPECT_LT(std::sqrt(fit.variance_model.relative), 0.08);
}

TEST_F(PatternFit, FrictionAndDragCoverTheTruthOverTwentySeeds) {
  // Offset fixed (the recommended --fit friction,drag), started away from the truth. An honest 95 %
  // interval (±2 SE) holds the truth in 19 of 20 fits on average; at least 17 of 20 leaves room for
  // sampling (P(<= 16 | p = 0.95) = 1.6 %). Before the weighted fit the unweighted s²(JᵀJ)⁻¹ of these
  // tests covered about half (docs/field-calibration.md, "Uncertainty").
  // 128 trajectories per evaluation keep 20 fits within a few seconds.
  cal::PatternFitOptions options = fast_options();
  options.model.sample_count = 128;
  options.use_start = true;
  options.start = {0.4, 1.0, kTruth.launch_angle_offset_rad};
  options.fit_angle_offset = false;
  const Coverage c = coverage(*setup_, kTruth, options, 20);
  EXPECT_GE(c.within_two[0], 17);
  EXPECT_GE(c.within_two[1], 17);
  EXPECT_LT(c.rms_z[0], 1.5);
  EXPECT_LT(c.rms_z[1], 1.5);
}

TEST_F(PatternFit, LongAllThreeCoverTheTruthOverTwentySeeds) {
  // The same for all three parameters (slower: three-parameter fits, ~1 s each): label long.
  const Coverage c = coverage(*setup_, kTruth, fast_options(), 20);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_GE(c.within_two[i], 17) << "parameter " << i;
    EXPECT_LT(c.rms_z[i], 1.5) << "parameter " << i;
  }
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

TEST_F(PatternFit, DemRowsAreCorrectedUnlessAnalyticIsAllowed) {
  // A DEM row keeps its own launches, corrected by the fitted parameters (source "dem", every sample);
  // with allow_analytic_for_dem it is rebuilt by the analytic model instead. Mark the 600 rpm row of a
  // copy as a DEM row.
  spread::testing::TempPath dem("dem.sqlite");
  std::filesystem::copy_file(table_->path(), dem.path());
  spread::tables::Run dem_run = contents_->runs[1];
  ASSERT_EQ(dem_run.rpm, 600.0);
  dem_run.source = "dem";
  spread::tables::TableWriter(dem.path()).write_run(dem_run, /*replace=*/true);
  const spread::tables::TableContents contents = spread::tables::read_table_file(dem.path());
  EXPECT_EQ(cal::non_analytic_rows(contents, "Urea"), (std::vector<double>{600.0}));
  EXPECT_TRUE(cal::non_analytic_rows(*contents_, "Urea").empty());

  const cal::PatternParameters correction{0.4, 1.1, 3.0 * kPi / 180.0, 1.05, 2.0 * kPi / 180.0};
  spread::testing::TempPath output("calibrated_dem.sqlite");
  cal::CalibratedTableRequest request;
  request.original_path = dem.path();
  request.output_path = output.path();
  request.material = "Urea";
  request.new_material_name = "Urea (calibrated)";
  request.parameters = correction;
  const cal::CalibratedTableSummary corrected = cal::write_calibrated_table(request);
  EXPECT_TRUE(corrected.replaced_dem_rpm.empty());
  const std::vector<spread::tables::LaunchSample> expected =
      cal::corrected_launch_samples(dem_run.samples, correction, contents.machine.rotation_sense);
  for (const spread::tables::Run& run : spread::tables::read_table_file(output.path()).runs) {
    if (run.material != "Urea (calibrated)") continue;
    if (run.rpm == 600.0) {
      EXPECT_EQ(run.source, "dem");
      EXPECT_NE(run.effects.find("launch_speed_factor=1.0500"), std::string::npos) << run.effects;
      ASSERT_EQ(run.samples.size(), expected.size());
      EXPECT_EQ(0, std::memcmp(run.samples.data(), expected.data(), expected.size() * sizeof expected[0]));
    } else {
      EXPECT_EQ(run.source, "analytic");
    }
  }

  spread::testing::TempPath analytic_output("calibrated_analytic.sqlite");
  request.output_path = analytic_output.path();
  request.allow_analytic_for_dem = true;
  const cal::CalibratedTableSummary summary = cal::write_calibrated_table(request);
  EXPECT_EQ(summary.replaced_dem_rpm, (std::vector<double>{600.0}));
  const spread::tables::TableContents copy = spread::tables::read_table_file(analytic_output.path());
  ASSERT_EQ(copy.runs.size(), 4u);
  for (const spread::tables::Run& run : copy.runs) {
    if (run.material != "Urea (calibrated)") continue;
    EXPECT_EQ(run.source, "analytic");
    EXPECT_EQ(run.effects.find("replaces_dem_run") != std::string::npos, run.rpm == 600.0) << run.effects;
  }
}

TEST_F(PatternFit, LaunchCorrectionOfTableSamplesIsRecovered) {
  // The fit on a table's own launch samples (a DEM row's path): both rows of a copy marked as DEM rows,
  // a synthetic tray test made from the 600 rpm row with a known launch correction, fitted back from no
  // correction. The correction must come back within one standard error (this seed, fixed: 0.5 SE for
  // both; over many seeds ±1 SE would hold the truth in about 2 of 3 fits).
  spread::testing::TempPath dem("dem_both.sqlite");
  std::filesystem::copy_file(table_->path(), dem.path());
  for (spread::tables::Run run : contents_->runs) {
    run.source = "dem";
    spread::tables::TableWriter(dem.path()).write_run(run, /*replace=*/true);
  }
  const cal::PatternSetup setup =
      cal::pattern_setup_from_table(spread::tables::read_table_file(dem.path()), "Urea", 600.0);
  ASSERT_EQ(setup.table_samples.size(), static_cast<std::size_t>(kSamples));
  EXPECT_EQ(setup.table_row_rpm, 600.0);
  const cal::PatternParameters truth{0.4, 1.0, 3.0 * kPi / 180.0, 1.06, 0.0};
  spread::testing::TempPath csv("dem_synthetic.csv");
  const cal::TrayTest test = cal::read_tray_csv(write_synthetic_csv(setup, truth, csv.path()));

  cal::PatternFitOptions options = fast_options();
  options.fit_drag_diameter = false;
  options.fit_launch_speed = true;
  EXPECT_THROW(cal::fit_pattern(setup, test, options), std::invalid_argument);  // friction: not in a DEM row
  options.fit_friction = false;
  const cal::PatternFitResult fit = cal::fit_pattern(setup, test, options);
  std::printf("s %.4f +- %.4f (true %.4f), offset %.3f +- %.3f deg (true 3), %d iterations\n",
              fit.fitted.launch_speed_factor, fit.standard_error.launch_speed_factor, truth.launch_speed_factor,
              fit.fitted.launch_angle_offset_rad * 180 / kPi, fit.standard_error.launch_angle_offset_rad * 180 / kPi,
              fit.iterations);
  EXPECT_TRUE(fit.table_samples);
  EXPECT_TRUE(fit.converged) << fit.stop_reason;
  EXPECT_TRUE(cal::assess_fit(fit, cal::pass_scatter(test)).accepted());
  EXPECT_LT(std::abs(fit.fitted.launch_speed_factor - truth.launch_speed_factor),
            fit.standard_error.launch_speed_factor);
  EXPECT_LT(std::abs(fit.fitted.launch_angle_offset_rad - truth.launch_angle_offset_rad),
            fit.standard_error.launch_angle_offset_rad);
  EXPECT_LT(fit.standard_error.launch_speed_factor, 0.02);
  EXPECT_EQ(fit.fitted.friction_wall, 0.4);  // fixed parameters stay where they started
  EXPECT_EQ(fit.fitted.drag_diameter_factor, 1.0);
}

TEST(LaunchCorrection, OneSampleByHand) {
  // A granule leaving along +x at 0.6 of the rim speed, rising at 0.1 of it, from (0.3, 0, 0).
  spread::tables::LaunchSample sample{};
  sample.x_m = 0.3f;
  sample.vx_norm = 0.6f;
  sample.vz_norm = 0.1f;
  sample.wz_norm = 1.0f;
  sample.diameter_m = 3e-3f;
  sample.mass_kg = 1e-5f;
  // ε turns the launch from its own elevation atan(0.1/0.6) to 20° above the horizontal; s = 1.5; δ = 90°
  // with rotation sense +1 turns x into y; k = 1.2 scales the diameter only.
  const double elevation0 = std::atan2(0.1, 0.6), speed0 = std::hypot(0.6, 0.1);
  const cal::PatternParameters p{0.4, 1.2, 0.5 * kPi, 1.5, 20.0 * kPi / 180.0 - elevation0};
  const spread::tables::LaunchSample c = cal::corrected_launch_samples({sample}, p, +1).front();
  EXPECT_NEAR(c.x_m, 0.0, 1e-7);
  EXPECT_NEAR(c.y_m, 0.3, 1e-7);
  EXPECT_NEAR(c.vx_norm, 0.0, 1e-6);
  EXPECT_NEAR(c.vy_norm, 1.5 * speed0 * std::cos(20.0 * kPi / 180.0), 1e-6);
  EXPECT_NEAR(c.vz_norm, 1.5 * speed0 * std::sin(20.0 * kPi / 180.0), 1e-6);
  EXPECT_EQ(c.wz_norm, 1.0f);
  EXPECT_NEAR(c.diameter_m, 3.6e-3, 1e-9);
  EXPECT_EQ(c.mass_kg, sample.mass_kg);
  // The other sense of rotation turns the other way.
  EXPECT_NEAR(cal::corrected_launch_samples({sample}, p, -1).front().y_m, -0.3, 1e-7);
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

TEST_F(PatternFit, RpmOutsideTheTableIsRefused) {
  // The table has rows at 500 and 600 rpm: a tray test at 3000 rpm (or 450) is not one it can calibrate.
  try {
    cal::pattern_setup_from_table(*contents_, "Urea", 3000.0);
    FAIL() << "3000 rpm must be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rpm 3000 is outside the table's range for 'Urea' (500 to 600 rpm)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(cal::pattern_setup_from_table(*contents_, "Urea", 450.0), std::invalid_argument);
  EXPECT_NO_THROW(cal::pattern_setup_from_table(*contents_, "Urea", 550.0));
}

TEST_F(PatternFit, MissingTrayIsLeftOutOfTheFit) {
  // The fullest tray knocked over: marked missing, the fit gives what the whole test gives (within a
  // standard error); entered as 0 it has to explain a hole the pattern does not have.
  cal::PatternFitOptions options = fast_options();
  options.fit_angle_offset = false;
  const cal::PatternFitResult whole = cal::fit_pattern(*setup_, *test_, options);
  std::size_t fullest = 0;
  for (std::size_t i = 0; i < test_->layout_mass_kg.size(); ++i) {
    if (test_->layout_mass_kg[i] > test_->layout_mass_kg[fullest]) fullest = i;
  }
  cal::TrayTest zero = *test_;  // the layout is the row of trays here (64 trays, none padded)
  zero.mass_kg[fullest] = zero.layout_mass_kg[fullest] = 0.0;
  cal::TrayTest missing = zero;
  missing.missing[fullest] = missing.layout_missing[fullest] = true;
  const cal::PatternFitResult left_out = cal::fit_pattern(*setup_, missing, options);
  const cal::PatternFitResult as_zero = cal::fit_pattern(*setup_, zero, options);
  report(left_out);
  report(as_zero);
  EXPECT_TRUE(left_out.converged);
  EXPECT_LT(std::abs(left_out.fitted.friction_wall - whole.fitted.friction_wall), whole.standard_error.friction_wall);
  EXPECT_LT(std::abs(left_out.fitted.drag_diameter_factor - whole.fitted.drag_diameter_factor),
            whole.standard_error.drag_diameter_factor);
  EXPECT_EQ(left_out.informative_trays, whole.informative_trays - 1);
  EXPECT_GT(as_zero.residual_rms_fraction, 2.0 * left_out.residual_rms_fraction);
}
