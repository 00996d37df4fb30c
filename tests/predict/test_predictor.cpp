// Predictor: pipeline against a hand-assembled reference, accuracy of the default integrator settings,
// symmetry (mirror trick, lateral wind), interpolation between rows, and every refusal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory_resource>
#include <numeric>
#include <string>
#include <vector>

#include "libspread/analysis/predict/flight_defaults.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/analysis/predict/run_flight_effects.hpp"
#include "libspread/analysis/predict/sample_influence.hpp"
#include "libspread/analysis/metrics/wide_kernel.hpp"
#include "tests/predict/synthetic_table.hpp"
#include "tests/support/temp_path.hpp"

namespace spread::predict {
namespace {

PredictionRequest request(const char* material, double rpm) {
  PredictionRequest r;
  r.material = material;
  r.rpm = rpm;
  return r;
}

std::vector<double> copy(std::span<const double> s) { return {s.begin(), s.end()}; }

TEST(Predictor, ListsMaterialsSortedWithRpmRanges) {
  Predictor p(testing::synthetic_contents());
  ASSERT_EQ(p.material_count(), 2u);
  EXPECT_EQ(p.material(0).name, "can");
  EXPECT_EQ(p.material(1).name, "urea");
  EXPECT_EQ(p.min_rpm(0), 500.0);
  EXPECT_EQ(p.max_rpm(0), 800.0);
  EXPECT_EQ(p.min_rpm(1), 500.0);
  EXPECT_EQ(p.max_rpm(1), 700.0);
  EXPECT_EQ(p.find_material("urea"), 1u);
  EXPECT_FALSE(p.find_material("Urea"));
}

// At an exact row the predictor must reproduce the steps written out by hand: scale, place, fly,
// mirror, accumulate.
TEST(Predictor, ExactRowMatchesHandAssembledPipeline) {
  const auto contents = testing::synthetic_contents();
  Predictor p(contents);
  Prediction out;
  PredictionRequest point_masses = request("can", 600.0);
  point_masses.kernel_half_width_m = 0.0;  // each landing into its tray, as accumulate_transverse does
  ASSERT_EQ(p.predict(point_masses, out), PredictStatus::kOk);

  const auto& run = contents.runs[1];
  ASSERT_EQ(run.rpm, 600.0);
  const double omega = 600.0 * 2.0 * kPi / 60.0, rim = omega * 0.3;
  std::vector<double> x, m;
  double total = 0;
  for (const auto& s : run.samples) {
    flight::Granule g{s.diameter_m, 1800.0};
    flight::State st;
    st.position_m = Vec3(s.x_m, s.y_m, s.z_m + 0.8);
    st.velocity_m_s = rim * Vec3(s.vx_norm, s.vy_norm, s.vz_norm);
    st.spin_rad_s = omega * Vec3(s.wx_norm, s.wy_norm, s.wz_norm);
    const auto l = flight::fly_to_ground(g, st, 0.0, flight::Air{}, flight::kDrag | flight::kMagnus | flight::kSpinDecay,
                                         default_flight_settings());
    ASSERT_TRUE(l.landed);
    x.push_back(l.state.position_m.x());
    m.push_back(s.mass_kg);
    total += 2.0 * s.mass_kg;
  }
  for (double& w : m) w /= total;
  std::vector<double> trays(static_cast<std::size_t>(out.trays.tray_count), 0.0);
  metrics::accumulate_transverse(x, m, metrics::MachineLayout{2, 1.0}, out.trays, trays);
  ASSERT_EQ(out.tray_mass_fraction.size(), trays.size());
  for (std::size_t k = 0; k < trays.size(); ++k) EXPECT_NEAR(out.tray_mass_fraction[k], trays[k], 1e-12) << k;
  EXPECT_EQ(out.flights, 256);
  EXPECT_DOUBLE_EQ(out.disc_height_m, 0.8);
  EXPECT_EQ(out.kernel_half_width_m, 0.0);

  // The automatic kernel: the same landings, each spread over its Epanechnikov kernel.
  ASSERT_EQ(p.predict(request("can", 600.0), out), PredictStatus::kOk);
  EXPECT_GT(out.kernel_half_width_m, 0.0);
  std::vector<double> smoothed(static_cast<std::size_t>(out.trays.tray_count), 0.0);
  metrics::accumulate_transverse_kernel(out.landing_x_m, out.landing_mass_fraction, out.trays,
                                        out.kernel_half_width_m, smoothed);
  for (std::size_t k = 0; k < smoothed.size(); ++k) EXPECT_NEAR(out.tray_mass_fraction[k], smoothed[k], 1e-12) << k;
}

TEST(Predictor, MassIsConservedAndResultsArePlausible) {
  Predictor p(testing::synthetic_contents());
  Prediction out;
  ASSERT_EQ(p.predict(request("can", 650.0), out), PredictStatus::kOk);
  const double caught = std::accumulate(out.tray_mass_fraction.begin(), out.tray_mass_fraction.end(), 0.0);
  EXPECT_NEAR(caught + out.lost_mass_fraction, 1.0, 1e-12);
  EXPECT_LT(out.lost_mass_fraction, 1e-12);  // fitted trays hold every landing
  EXPECT_GT(out.throw_width_m, 5.0);
  EXPECT_GT(out.working_width_to_and_fro_m, 0.0);
  EXPECT_LE(out.working_width_to_and_fro_m, out.trays.tray_count * out.trays.tray_width_m);
  EXPECT_GT(out.mean_radius_m, 2.0);
  EXPECT_GT(out.radial_width_m, 0.0);
  // The CV is reported at the widest whole-tray bout within the target, just below the working width.
  EXPECT_LE(out.bout_width_m, out.working_width_to_and_fro_m);
  EXPECT_GT(out.bout_width_m, out.working_width_to_and_fro_m - out.trays.tray_width_m);
  EXPECT_LE(out.cv_to_and_fro, 0.15);
  EXPECT_GT(out.working_width_to_and_fro_se_m, 0.0);
  EXPECT_GT(out.cv_to_and_fro_se, 0.0);
  EXPECT_EQ(out.sample_count, 256u);
  ASSERT_EQ(out.landing_x_m.size(), 512u);
}

TEST(Predictor, StillAirPatternIsMirrorSymmetric) {
  Predictor p(testing::synthetic_contents());
  Prediction out;
  ASSERT_EQ(p.predict(request("can", 700.0), out), PredictStatus::kOk);
  const auto t = copy(out.tray_mass_fraction);
  for (std::size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(t[k], t[t.size() - 1 - k], 1e-15);
}

// Default integrator settings land within 1 cm of a tight-tolerance reference.
TEST(Predictor, DefaultSettingsLandWithinOneCentimetreOfReference) {
  for (const char* material : {"can", "urea"}) {
    for (double rpm : {500.0, 600.0, 650.0, 700.0}) {
      Predictor p(testing::synthetic_contents());
      Prediction out;
      ASSERT_EQ(p.predict(request(material, rpm), out), PredictStatus::kOk);
      const auto x = copy(out.landing_x_m), y = copy(out.landing_y_m);
      p.set_flight_settings(reference_flight_settings());
      ASSERT_EQ(p.predict(request(material, rpm), out), PredictStatus::kOk);
      double worst = 0;
      for (std::size_t k = 0; k < x.size(); ++k) {
        worst = std::max(worst, std::hypot(x[k] - out.landing_x_m[k], y[k] - out.landing_y_m[k]));
      }
      EXPECT_LT(worst, 0.01) << material << " " << rpm;
    }
  }
}

// With a lateral wind the right disc is flown, not mirrored: the machine's pattern in wind +w must be
// the mirror image of the pattern in wind −w. (The mirror trick would give a symmetric pattern.)
TEST(Predictor, LateralWindFliesBothDiscsAndMirrorsWithTheWind) {
  Predictor p(testing::synthetic_contents());
  PredictionRequest r = request("can", 600.0);
  r.wind_x_m_s = 3.0;
  Prediction out;
  ASSERT_EQ(p.predict(r, out), PredictStatus::kOk);
  EXPECT_EQ(out.flights, 512);
  const auto plus = copy(out.tray_mass_fraction);
  r.wind_x_m_s = -3.0;
  ASSERT_EQ(p.predict(r, out), PredictStatus::kOk);
  const auto minus = copy(out.tray_mass_fraction);
  ASSERT_EQ(plus.size(), minus.size());
  double centroid = 0, asymmetry = 0;
  for (std::size_t k = 0; k < plus.size(); ++k) {
    EXPECT_NEAR(plus[k], minus[minus.size() - 1 - k], 1e-9) << k;
    centroid += plus[k] * out.trays.centre_m(static_cast<int>(k));
    asymmetry += std::abs(plus[k] - plus[plus.size() - 1 - k]);
  }
  EXPECT_GT(centroid, 0.3);    // blown to the right
  EXPECT_GT(asymmetry, 0.05);  // not symmetric any more
}

TEST(Predictor, WindAlongTheDrivingDirectionKeepsTheMirrorTrick) {
  Predictor p(testing::synthetic_contents());
  PredictionRequest r = request("can", 600.0);
  r.wind_y_m_s = 3.0;
  Prediction out;
  ASSERT_EQ(p.predict(r, out), PredictStatus::kOk);
  // One disc flown and mirrored, for the outgoing pass and for the return pass in the tailwind.
  EXPECT_EQ(out.flights, 2 * 256);
  EXPECT_EQ(out.return_pass, ReturnPass::kFlown);
  const auto t = copy(out.tray_mass_fraction);
  for (std::size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(t[k], t[t.size() - 1 - k], 1e-15);
  // Wind bit off: the wind is ignored.
  const auto windy_radius = out.mean_radius_m;
  r.effects = flight::kDrag | flight::kMagnus | flight::kSpinDecay;
  ASSERT_EQ(p.predict(r, out), PredictStatus::kOk);
  Prediction still;
  ASSERT_EQ(p.predict(request("can", 600.0), still), PredictStatus::kOk);
  EXPECT_EQ(out.mean_radius_m, still.mean_radius_m);
  EXPECT_NE(windy_radius, still.mean_radius_m);
}

TEST(Predictor, InterpolatedRpmLiesBetweenItsRows) {
  Predictor p(testing::synthetic_contents());
  Prediction lo, mid, hi;
  ASSERT_EQ(p.predict(request("can", 600.0), lo), PredictStatus::kOk);
  ASSERT_EQ(p.predict(request("can", 650.0), mid), PredictStatus::kOk);
  ASSERT_EQ(p.predict(request("can", 700.0), hi), PredictStatus::kOk);
  EXPECT_LT(lo.mean_radius_m, mid.mean_radius_m);
  EXPECT_LT(mid.mean_radius_m, hi.mean_radius_m);
  // Rows of different counts (urea: 200 and 256 samples) interpolate by quantile cells: every granule
  // of both rows flies.
  Prediction urea_lo, urea, urea_hi;
  ASSERT_EQ(p.predict(request("urea", 600.0), urea), PredictStatus::kOk);
  EXPECT_EQ(urea.flights, 456);
  ASSERT_EQ(p.predict(request("urea", 500.0), urea_lo), PredictStatus::kOk);
  EXPECT_EQ(urea_lo.flights, 200);
  ASSERT_EQ(p.predict(request("urea", 700.0), urea_hi), PredictStatus::kOk);
  EXPECT_LT(urea_lo.mean_radius_m, urea.mean_radius_m);
  EXPECT_LT(urea.mean_radius_m, urea_hi.mean_radius_m);
}

// Rows without sample correspondence (source "dem", different counts, stored in scrambled order) whose
// normalised speeds differ by ±10 %: the quantile-cell interpolation at mid-interval must reproduce what
// the pairwise interpolation of the complete, paired rows gives (the truth here: the speeds lerp to
// ×1.0), and do better on the throw width than the mass-weighted mixture of both rows (the earlier
// method, assembled here as one row of both rows' samples at half weight).
TEST(Predictor, CellInterpolationOfUnpairedRowsMatchesThePairedTruth) {
  auto scaled = [](std::vector<tables::LaunchSample> samples, float factor) {
    for (auto& s : samples) {
      s.vx_norm *= factor;
      s.vy_norm *= factor;
    }
    return samples;
  };
  tables::TableContents paired = testing::synthetic_contents({{"ref", 1330.0, {500.0, 700.0}, 300, -1}});
  paired.runs[0].samples = scaled(paired.runs[0].samples, 0.9f);
  paired.runs[1].samples = scaled(paired.runs[1].samples, 1.1f);

  tables::TableContents unpaired = paired;
  for (auto& run : unpaired.runs) run.source = "dem";
  std::vector<tables::LaunchSample> thinned;  // lower row: every 4th granule missing, scrambled order
  const auto& full = paired.runs[0].samples;
  for (std::size_t k = 0; k < full.size(); ++k) {
    const std::size_t from = (k * 7) % full.size();
    if (from % 4 != 3) thinned.push_back(full[from]);
  }
  unpaired.runs[0].samples = thinned;
  std::reverse(unpaired.runs[1].samples.begin(), unpaired.runs[1].samples.end());

  tables::TableContents mixture = unpaired;  // one row at 600 rpm: both rows' samples, mass × 1/2
  mixture.runs.resize(1);
  mixture.runs[0].rpm = 600.0;
  mixture.runs[0].samples.insert(mixture.runs[0].samples.end(), unpaired.runs[1].samples.begin(),
                                 unpaired.runs[1].samples.end());
  for (auto& s : mixture.runs[0].samples) s.mass_kg *= 0.5f;

  Prediction truth, ranked, mixed;
  ASSERT_EQ(Predictor(paired).predict(request("ref", 600.0), truth), PredictStatus::kOk);
  ASSERT_EQ(truth.flights, 300);
  Predictor rank_predictor(unpaired);
  ASSERT_EQ(rank_predictor.predict(request("ref", 600.0), ranked), PredictStatus::kOk);
  EXPECT_EQ(ranked.flights, 225 + 300);  // every granule of both rows
  ASSERT_EQ(Predictor(mixture).predict(request("ref", 600.0), mixed), PredictStatus::kOk);

  auto error = [&](double value, double reference) { return std::abs(value - reference) / reference; };
  EXPECT_LT(error(ranked.throw_width_m, truth.throw_width_m), 0.03);
  EXPECT_LT(error(ranked.mean_radius_m, truth.mean_radius_m), 0.01);
  // ξ is small here (~0.17 m, one launch speed per angle); the rows' own spreads inside the 2 × 2 cells
  // of 225-sample rows (≥ 32 samples a cell) widen it by ~10 %, the mixture by ~270 %.
  EXPECT_LT(error(ranked.radial_width_m, truth.radial_width_m), 0.15);
  EXPECT_GT(error(mixed.throw_width_m, truth.throw_width_m), 5.0 * error(ranked.throw_width_m, truth.throw_width_m));
  EXPECT_GT(error(mixed.radial_width_m, truth.radial_width_m), 5.0 * error(ranked.radial_width_m, truth.radial_width_m));

  // Deterministic: a second predictor from the same contents gives the same pattern. (Named: the
  // prediction's spans point into its predictor's workspace, so the predictor must outlive them.)
  Predictor again_predictor(unpaired);
  Prediction again;
  ASSERT_EQ(again_predictor.predict(request("ref", 600.0), again), PredictStatus::kOk);
  EXPECT_EQ(copy(again.tray_mass_fraction), copy(ranked.tray_mass_fraction));
}

TEST(Predictor, BoutWidthAndHeightAreHonoured) {
  Predictor p(testing::synthetic_contents());
  PredictionRequest r = request("can", 600.0);
  r.bout_width_m = 12.0;
  r.disc_height_m = 1.2;
  Prediction high;
  ASSERT_EQ(p.predict(r, high), PredictStatus::kOk);
  EXPECT_EQ(high.bout_width_m, 12.0);
  EXPECT_TRUE(std::isfinite(high.cv_to_and_fro));
  EXPECT_DOUBLE_EQ(high.disc_height_m, 1.2);
  Prediction low;
  ASSERT_EQ(p.predict(request("can", 600.0), low), PredictStatus::kOk);
  EXPECT_GT(high.mean_radius_m, low.mean_radius_m);  // higher disc, longer flights
}

// `count` landings of equal weight spread evenly over [-17, 17] m (golden-ratio steps), one of them NaN.
void spread_landings(int count, std::vector<double>& x, std::vector<double>& w) {
  for (int i = 0; i < count; ++i) {
    x.push_back(-17.0 + 34.0 * std::fmod(0.618033988749895 * i, 1.0));
    w.push_back(1.0 / count);
  }
  x[17] = std::numeric_limits<double>::quiet_NaN();
}

// A kernel many trays wide gives the standard errors of the tray-by-tray dot products from each
// gradient's prefix sums (wide_kernel.hpp), within the rounding the header states.
TEST(SampleInfluence, AWideKernelsStandardErrorsAreTrayByTraysWithinRounding) {
  metrics::TrayLayout trays;
  trays.tray_width_m = 0.1;
  trays.tray_count = 300;  // [-15, 15] m
  std::vector<double> x, w;
  spread_landings(2000, x, w);
  std::vector<double> a(300), b(300);
  for (std::size_t k = 0; k < a.size(); ++k) {
    a[k] = std::sin(0.05 * static_cast<double>(k));
    b[k] = 1e-4 * static_cast<double>(k * k) - 2.0;
  }
  std::vector<double> scratch(metrics::wide_kernel_sums_size(trays));
  for (double h : {0.8, 3.0}) {
    const SampleInfluence by_tray{x, w, 1000, 2, trays, h};
    const SampleInfluence by_sums{x, w, 1000, 2, trays, h, {}, scratch};
    const std::span<const double> gradients[2] = {a, b};
    double se_tray[2], se_sums[2];
    by_tray.standard_errors(gradients, se_tray);
    by_sums.standard_errors(gradients, se_sums);
    for (int g = 0; g < 2; ++g) {
      EXPECT_GT(se_tray[g], 0.0);
      EXPECT_NEAR(se_sums[g], se_tray[g], 1e-9 * se_tray[g]) << "h " << h << " gradient " << g;
    }
    EXPECT_NEAR(by_sums.standard_error(a), se_tray[0], 1e-9 * se_tray[0]);
  }
}

// The one-pass standard errors are the one-by-one standard errors, bit for bit; an empty gradient is NaN.
TEST(SampleInfluence, StandardErrorsInOnePassEqualOneByOne) {
  for (double h : {0.0, 0.7}) {
    const std::vector<double> x{-3.1, -0.2, 0.4, std::numeric_limits<double>::quiet_NaN(), 2.6, 5.9, -4.4, 1.1};
    const std::vector<double> w{0.1, 0.15, 0.05, 0.1, 0.2, 0.1, 0.2, 0.1};
    metrics::TrayLayout trays;
    trays.tray_width_m = 0.5;
    trays.tray_count = 24;
    const SampleInfluence influence{x, w, 4, 2, trays, h};
    std::vector<double> a(24), b(24), c(24);
    for (std::size_t k = 0; k < a.size(); ++k) {
      a[k] = std::sin(0.3 * static_cast<double>(k));
      b[k] = 0.01 * static_cast<double>(k * k) - 1.0;
      c[k] = std::cos(0.7 * static_cast<double>(k) + 0.2);
    }
    const std::span<const double> gradients[4] = {a, {}, b, c};
    double se[4];
    influence.standard_errors(gradients, se);
    EXPECT_EQ(se[0], influence.standard_error(a)) << h;
    EXPECT_TRUE(std::isnan(se[1]));
    EXPECT_EQ(se[2], influence.standard_error(b)) << h;
    EXPECT_EQ(se[3], influence.standard_error(c)) << h;
    EXPECT_GT(se[0], 0.0);
    // Blocks naming the same landings are the same samples; blocks in another order sum the same squares.
    const SampleBlock same[1] = {SampleBlock{4, {0, 4}}};
    const SampleInfluence by_block{x, w, 4, 1, trays, h, same};
    EXPECT_EQ(by_block.standard_error(a), influence.standard_error(a)) << h;
    const SampleBlock split[3] = {SampleBlock{2, {2, 6}}, SampleBlock{2, {0, SampleBlock::kNoLanding}},
                                  SampleBlock{2, {SampleBlock::kNoLanding, 4}}};
    const SampleInfluence unshared{x, w, 6, 1, trays, h, split};
    double split_se[4];
    unshared.standard_errors(gradients, split_se);
    EXPECT_EQ(split_se[2], unshared.standard_error(b)) << h;
    // Landings 0, 1 and 4, 5 as samples of their own instead of pairs: another variance.
    EXPECT_NE(split_se[0], se[0]) << h;
  }
}

// Several gradients in one pass over a wide kernel's sums (4 and 8 of them: every running value in
// registers; 9: through arrays) give each gradient's standard error bit for bit as a pass of its own.
TEST(SampleInfluence, AWideKernelsPassOfManyGradientsIsEachAloneBitForBit) {
  metrics::TrayLayout trays;
  trays.tray_width_m = 0.25;
  trays.tray_count = 120;  // [-15, 15] m
  std::vector<double> x, w;
  spread_landings(1200, x, w);
  std::vector<std::vector<double>> gradient(SampleInfluence::kMaxGradients, std::vector<double>(120));
  for (std::size_t g = 0; g < gradient.size(); ++g) {
    for (std::size_t k = 0; k < 120; ++k) gradient[g][k] = std::sin(0.05 * static_cast<double>(k * (g + 1)) + 0.3 * static_cast<double>(g));
  }
  std::vector<double> scratch(metrics::wide_kernel_sums_size(trays, SampleInfluence::kMaxGradients));
  for (double h : {0.3, 1.7}) {
    const SampleInfluence influence{x, w, 600, 2, trays, h, {}, scratch};
    for (std::size_t count : {4u, 8u, 9u}) {
      std::vector<std::span<const double>> gradients(gradient.begin(), gradient.begin() + static_cast<long>(count));
      std::vector<double> se(count);
      influence.standard_errors(gradients, se);
      for (std::size_t g = 0; g < count; ++g) {
        EXPECT_GT(se[g], 0.0);
        EXPECT_EQ(se[g], influence.standard_error(gradient[g])) << "h " << h << ", " << count << " gradients, " << g;
      }
    }
  }
}

TEST(Predictor, IsDeterministic) {
  Predictor a(testing::synthetic_contents()), b(testing::synthetic_contents());
  Prediction pa, pb;
  ASSERT_EQ(a.predict(request("urea", 611.0), pa), PredictStatus::kOk);
  ASSERT_EQ(b.predict(request("urea", 611.0), pb), PredictStatus::kOk);
  EXPECT_EQ(copy(pa.tray_mass_fraction), copy(pb.tray_mass_fraction));
  EXPECT_EQ(pa.working_width_racetrack_m, pb.working_width_racetrack_m);
}

// The samples read into one block from the predictor's memory (as the C API opens a table) predict the
// same bits as the samples read run by run, in still air and in a crosswind, by pairs and by cells.
TEST(Predictor, PooledSamplesPredictTheSameBits) {
  spread::testing::TempPath file("pooled");
  testing::write_synthetic_table(file.path());
  std::pmr::unsynchronized_pool_resource memory;
  Predictor pooled(tables::read_table_file(file.path(), &memory), PredictorLimits{}, &memory);
  Predictor plain(tables::read_table_file(file.path()));
  for (const char* material : {"can", "urea"}) {
    for (double wind_m_s : {0.0, 3.0}) {
      PredictionRequest r = request(material, 611.0);
      r.wind_x_m_s = wind_m_s;  // across the driving direction
      Prediction a, b;
      ASSERT_EQ(pooled.predict(r, a), PredictStatus::kOk) << material;
      ASSERT_EQ(plain.predict(r, b), PredictStatus::kOk) << material;
      EXPECT_EQ(copy(a.tray_mass_fraction), copy(b.tray_mass_fraction)) << material << " " << wind_m_s;
      EXPECT_EQ(a.working_width_racetrack_m, b.working_width_racetrack_m);
    }
  }
}

// Pooled contents that do not match their runs, or hold an impossible sample, are refused as plain ones.
TEST(Predictor, PooledContentsAreCheckedAsPlainOnes) {
  spread::testing::TempPath file("pooled_bad");
  testing::write_synthetic_table(file.path());
  std::pmr::unsynchronized_pool_resource memory;
  tables::TableContents short_offsets = tables::read_table_file(file.path(), &memory);
  short_offsets.pooled_offset.pop_back();
  EXPECT_THROW(Predictor(std::move(short_offsets), PredictorLimits{}, &memory), std::invalid_argument);
  tables::TableContents nan_sample = tables::read_table_file(file.path(), &memory);
  nan_sample.pooled_samples.at(nan_sample.pooled_offset.at(1) + 3).vx_norm = std::numeric_limits<float>::quiet_NaN();
  try {
    Predictor p(std::move(nan_sample), PredictorLimits{}, &memory);
    ADD_FAILURE() << "a NaN pooled sample accepted";
  } catch (const tables::TableError& e) {
    EXPECT_EQ(e.kind(), tables::TableErrorKind::kCorrupt);
    EXPECT_NE(std::string(e.what()).find("sample 3 vx_norm"), std::string::npos) << e.what();
  }
}

TEST(Predictor, SingleDiscFliesOneDisc) {
  Predictor p(testing::synthetic_contents(testing::default_synthetic_materials(), 1));
  Prediction out;
  ASSERT_EQ(p.predict(request("can", 600.0), out), PredictStatus::kOk);
  EXPECT_EQ(out.landing_x_m.size(), 256u);
  const double caught = std::accumulate(out.tray_mass_fraction.begin(), out.tray_mass_fraction.end(), 0.0);
  EXPECT_NEAR(caught, 1.0, 1e-12);
}

TEST(Predictor, RefusesBadRequestsWithTheirStatus) {
  Predictor p(testing::synthetic_contents());
  Prediction out;
  out.throw_width_m = -1.0;  // must stay untouched on refusal
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto with = [](auto change) {
    PredictionRequest r = request("can", 600.0);
    change(r);
    return r;
  };
  EXPECT_EQ(p.predict(with([](auto& r) { r.material = "gravel"; }), out), PredictStatus::kUnknownMaterial);
  EXPECT_EQ(p.predict(with([](auto& r) { r.rpm = 499.0; }), out), PredictStatus::kRpmOutsideTable);
  EXPECT_EQ(p.predict(with([](auto& r) { r.rpm = 801.0; }), out), PredictStatus::kRpmOutsideTable);
  EXPECT_EQ(p.predict(with([&](auto& r) { r.rpm = nan; }), out), PredictStatus::kNotFinite);
  EXPECT_EQ(p.predict(with([&](auto& r) { r.wind_x_m_s = inf; }), out), PredictStatus::kNotFinite);
  EXPECT_EQ(p.predict(with([&](auto& r) { r.cv_target = nan; }), out), PredictStatus::kNotFinite);
  EXPECT_EQ(p.predict(with([](auto& r) { r.disc_height_m = -0.1; }), out), PredictStatus::kOutOfRange);
  EXPECT_EQ(p.predict(with([](auto& r) { r.cv_target = 0.0; }), out), PredictStatus::kOutOfRange);
  EXPECT_EQ(p.predict(with([](auto& r) { r.bout_width_m = -1.0; }), out), PredictStatus::kOutOfRange);
  EXPECT_EQ(p.predict(with([](auto& r) { r.tray_width_m = 0.01; }), out), PredictStatus::kOutOfRange);
  EXPECT_EQ(p.predict(with([](auto& r) { r.effects = 0x10; }), out), PredictStatus::kUnknownEffect);
  // Finite but absurd values are out of range against PredictorLimits' upper bounds (the fuzzer's
  // bout width of 3.6e59 m used to end in an exception from the metrics: SPREAD_ERROR_INTERNAL).
  const PredictorLimits limits;
  EXPECT_EQ(p.predict(with([](auto& r) { r.bout_width_m = 3.55e59; }), out), PredictStatus::kOutOfRange);
  EXPECT_EQ(p.predict(with([&](auto& r) { r.bout_width_m = std::nextafter(limits.max_bout_width_m, inf); }), out),
            PredictStatus::kOutOfRange);
  EXPECT_EQ(p.predict(with([](auto& r) { r.disc_height_m = 1e300; }), out), PredictStatus::kOutOfRange);
  EXPECT_EQ(p.predict(with([&](auto& r) { r.disc_height_m = 1.01 * limits.max_disc_height_m; }), out),
            PredictStatus::kOutOfRange);
  EXPECT_EQ(p.predict(with([](auto& r) { r.wind_x_m_s = -1e200; }), out), PredictStatus::kOutOfRange);
  EXPECT_EQ(p.predict(with([&](auto& r) { r.wind_y_m_s = 1.01 * limits.max_wind_m_s; }), out),
            PredictStatus::kOutOfRange);
  EXPECT_EQ(p.predict(with([](auto& r) { r.cv_target = 1e308; }), out), PredictStatus::kOutOfRange);
  EXPECT_EQ(out.throw_width_m, -1.0);
  // The bounds themselves are accepted.
  EXPECT_EQ(p.predict(with([&](auto& r) { r.bout_width_m = limits.max_bout_width_m; }), out), PredictStatus::kOk);
  EXPECT_TRUE(std::isfinite(out.cv_to_and_fro));
  EXPECT_EQ(p.predict(with([&](auto& r) { r.wind_x_m_s = -limits.max_wind_m_s; }), out), PredictStatus::kOk);
  EXPECT_EQ(p.predict(with([&](auto& r) { r.cv_target = limits.max_cv_target; }), out), PredictStatus::kOk);
}

// Contents that did not come through the table reader get the same value checks: a NaN mass or a zero
// diameter never reaches the flight code (TableError kCorrupt naming the field).
TEST(Predictor, ImpossibleContentsAreRefusedAtConstruction) {
  for (int field : {0, 4, 10, 11}) {
    tables::TableContents contents = testing::synthetic_contents();
    float* values = &contents.runs.at(0).samples.at(3).x_m;
    values[field] = field == 10 ? 0.0f : std::numeric_limits<float>::quiet_NaN();
    try {
      Predictor p(std::move(contents));
      ADD_FAILURE() << "field " << field << " accepted";
    } catch (const tables::TableError& e) {
      EXPECT_EQ(e.kind(), tables::TableErrorKind::kCorrupt);
      EXPECT_NE(std::string(e.what()).find("sample 3"), std::string::npos) << e.what();
    }
  }
  tables::TableContents contents = testing::synthetic_contents();
  contents.materials.at(0).density_kg_m3 = std::numeric_limits<double>::infinity();
  EXPECT_THROW(Predictor{std::move(contents)}, tables::TableError);
}

TEST(Predictor, TrayCapacityBoundsEveryLayout) {
  Predictor p(testing::synthetic_contents());
  EXPECT_EQ(p.tray_capacity(0.01), 0);
  EXPECT_GE(p.tray_capacity(0.5), 400);
  PredictionRequest r = request("can", 800.0);
  r.tray_width_m = 0.05;
  Prediction out;
  ASSERT_EQ(p.predict(r, out), PredictStatus::kOk);
  EXPECT_LE(out.trays.tray_count, p.tray_capacity(0.05));
}

}  // namespace
}  // namespace spread::predict

namespace spread::predict {
namespace {

// The drop point turned by Δ predicts what a table whose launches were all turned by Δ about the disc axis
// predicts at the table's drop point: turned here by hand, in polar form, on a row and between rows, in
// still air and in a crosswind, from the landing grid and flown.
// Each disc at its own setting is that disc of the machine with both discs at that setting: the left
// disc's landings are those of the alike prediction at the left setting, the right disc's those at the
// right setting, each disc carries half the mass, and a launch sample of the table that feeds both discs
// is counted once in the uncertainty.
TEST(Predictor, EachDiscAtItsOwnSettingIsThatDiscOfTheAlikeMachine) {
  Predictor predictor(testing::synthetic_contents());
  struct Case {
    const char* material;
    DiscSetting left, right;
  };
  const Case cases[] = {
      {"can", {640.0, 0.0}, {660.0, 0.0}},     // pairwise, the same rows
      {"can", {600.0, 0.0}, {750.0, 0.3}},     // a row, and a pair with its own drop point
      {"urea", {550.0, -0.2}, {650.0, 0.0}},   // quantile cells, the same rows
      {"urea", {500.0, 0.0}, {700.0, 0.0}},    // two rows, no row shared
  };
  for (const bool cached : {true, false}) {
    predictor.set_landing_grid_enabled(cached);
    for (const Case& c : cases) {
      for (const double wind_x_m_s : {0.0, 2.0}) {
        const std::string where = std::string(c.material) + " " + std::to_string(c.left.rpm) + "/" +
                                  std::to_string(c.right.rpm) + (cached ? " cached" : " flown") + " wind " +
                                  std::to_string(wind_x_m_s);
        PredictionRequest r = request(c.material, 0.0);
        r.wind_x_m_s = wind_x_m_s;
        r.disc_rpm = {c.left.rpm, c.right.rpm};
        r.disc_drop_point_turn_rad = {c.left.drop_point_turn_rad, c.right.drop_point_turn_rad};
        Prediction own;
        ASSERT_EQ(predictor.predict(r, own), PredictStatus::kOk) << where;
        EXPECT_EQ(own.discs[kLeftDisc], c.left) << where;
        EXPECT_EQ(own.discs[kRightDisc], c.right) << where;
        const std::vector<double> own_x = copy(own.landing_x_m), own_mass = copy(own.landing_mass_fraction);
        const std::size_t own_samples = own.sample_count;
        double tray_sum = 0.0;
        for (double m : own.tray_mass_fraction) tray_sum += m;
        EXPECT_NEAR(tray_sum + own.lost_mass_fraction, 1.0, 1e-9) << where;

        std::size_t alike_samples[2] = {0, 0};
        std::size_t left_count = 0;
        for (int d = 0; d < 2; ++d) {
          const DiscSetting setting = d == kLeftDisc ? c.left : c.right;
          PredictionRequest alike = request(c.material, setting.rpm);
          alike.wind_x_m_s = wind_x_m_s;
          alike.drop_point_turn_rad = setting.drop_point_turn_rad;
          Prediction both;
          ASSERT_EQ(predictor.predict(alike, both), PredictStatus::kOk) << where;
          const std::size_t n = both.landing_x_m.size() / 2;
          alike_samples[d] = both.sample_count;
          if (d == kLeftDisc) left_count = n;
          const std::size_t own_first = d == kLeftDisc ? 0 : left_count;
          ASSERT_GE(own_x.size(), own_first + n) << where;
          double disc_mass = 0.0;
          for (std::size_t i = 0; i < n; ++i) {
            const double expected_x = both.landing_x_m[d == kLeftDisc ? i : n + i];
            EXPECT_NEAR(own_x[own_first + i], expected_x, 1e-9) << where << " disc " << d << " landing " << i;
            disc_mass += own_mass[own_first + i];
          }
          EXPECT_NEAR(disc_mass, 0.5, 1e-12) << where << " disc " << d;
        }
        EXPECT_EQ(own_x.size(), left_count + alike_samples[1]) << where;
        // The samples behind it: the union of both discs' (rows shared are counted once).
        const bool same_rows = c.left.rpm != 500.0 || c.right.rpm != 700.0;
        EXPECT_EQ(own_samples, same_rows ? std::max(alike_samples[0], alike_samples[1])
                                         : alike_samples[0] + alike_samples[1])
            << where;
        EXPECT_TRUE(std::isfinite(own.throw_width_se_m)) << where;
      }
    }
  }
}

TEST(Predictor, PerDiscSettingsAlikeGiveTheBothDiscsPrediction) {
  Predictor predictor(testing::synthetic_contents());
  PredictionRequest both = request("urea", 620.0);
  both.drop_point_turn_rad = 0.25;
  Prediction expected;
  ASSERT_EQ(predictor.predict(both, expected), PredictStatus::kOk);
  const std::vector<double> expected_trays = copy(expected.tray_mass_fraction);
  PredictionRequest each = request("urea", 0.0);
  each.disc_rpm = {620.0, 620.0};
  each.disc_drop_point_turn_rad = {0.25, 0.25};
  Prediction got;
  ASSERT_EQ(predictor.predict(each, got), PredictStatus::kOk);
  EXPECT_EQ(copy(got.tray_mass_fraction), expected_trays);
  EXPECT_EQ(got.working_width_to_and_fro_m, expected.working_width_to_and_fro_m);
  EXPECT_EQ(got.cv_to_and_fro_se, expected.cv_to_and_fro_se);
}

TEST(Predictor, RefusesPerDiscSettingsOutsideTheTable) {
  Predictor predictor(testing::synthetic_contents());
  Prediction out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  PredictionRequest r = request("can", 600.0);
  r.disc_rpm = {nan, 900.0};
  EXPECT_EQ(predictor.predict(r, out), PredictStatus::kRpmOutsideTable);
  r.disc_rpm = {450.0, nan};
  EXPECT_EQ(predictor.predict(r, out), PredictStatus::kRpmOutsideTable);
  r.disc_rpm = {nan, std::numeric_limits<double>::infinity()};
  EXPECT_EQ(predictor.predict(r, out), PredictStatus::kNotFinite);
  r.disc_rpm = {650.0, 700.0};  // both given: the both-discs rpm would be dropped
  EXPECT_EQ(predictor.predict(r, out), PredictStatus::kOutOfRange);
  r.rpm = 0.0;
  EXPECT_EQ(predictor.predict(r, out), PredictStatus::kOk);
  r.disc_drop_point_turn_rad = {nan, 3.5};
  EXPECT_EQ(predictor.predict(r, out), PredictStatus::kOutOfRange);
  r.disc_drop_point_turn_rad = {0.1, -0.1};
  r.drop_point_turn_rad = 0.2;
  EXPECT_EQ(predictor.predict(r, out), PredictStatus::kOutOfRange);
  // A one-disc machine has no right disc to set.
  Predictor single(testing::synthetic_contents(testing::default_synthetic_materials(), 1));
  PredictionRequest one = request("can", 600.0);
  one.disc_rpm = {nan, 650.0};
  EXPECT_EQ(single.predict(one, out), PredictStatus::kOutOfRange);
  one.disc_rpm = {650.0, nan};
  one.rpm = 0.0;
  EXPECT_EQ(single.predict(one, out), PredictStatus::kOk);
}

TEST(Predictor, DropPointTurnIsTheTableTurnedAboutTheDiscAxis) {
  constexpr double kTurn_rad = 0.35;
  tables::TableContents turned_contents = testing::synthetic_contents();
  const auto turn = [](float& x, float& y) {
    const double r = std::hypot(double{x}, double{y}), phi = std::atan2(double{y}, double{x}) + kTurn_rad;
    x = static_cast<float>(r * std::cos(phi));
    y = static_cast<float>(r * std::sin(phi));
  };
  for (tables::Run& run : turned_contents.runs) {
    for (tables::LaunchSample& s : run.samples) {
      turn(s.x_m, s.y_m);
      turn(s.vx_norm, s.vy_norm);
      turn(s.wx_norm, s.wy_norm);
    }
  }
  Predictor turned_table(std::move(turned_contents));
  Predictor predictor(testing::synthetic_contents());
  for (const bool cached : {true, false}) {
    predictor.set_landing_grid_enabled(cached);
    turned_table.set_landing_grid_enabled(cached);
    for (const double rpm : {700.0, 640.0}) {
      for (const double wind_x_m_s : {0.0, 3.0}) {
        PredictionRequest r = request("can", rpm);
        r.wind_x_m_s = wind_x_m_s;
        Prediction expected;
        ASSERT_EQ(turned_table.predict(r, expected), PredictStatus::kOk);
        const std::vector<double> expected_trays = copy(expected.tray_mass_fraction);
        r.drop_point_turn_rad = kTurn_rad;
        Prediction got;
        ASSERT_EQ(predictor.predict(r, got), PredictStatus::kOk);
        const std::string where = std::string(cached ? "cached" : "flown") + " at " + std::to_string(rpm) +
                                  " rpm, wind " + std::to_string(wind_x_m_s);
        ASSERT_EQ(got.tray_mass_fraction.size(), expected_trays.size()) << where;
        for (std::size_t k = 0; k < expected_trays.size(); ++k) {
          EXPECT_NEAR(got.tray_mass_fraction[k], expected_trays[k], 1e-5) << where << " tray " << k;
        }
        EXPECT_NEAR(got.throw_width_m, expected.throw_width_m, 1e-3) << where;
        EXPECT_NEAR(got.working_width_to_and_fro_m, expected.working_width_to_and_fro_m, 1e-3) << where;
        // And the turn changes the pattern (the check has power): the fan of a twin-disc machine turned
        // towards the rear or the front throws differently across the driving direction.
        r.drop_point_turn_rad = 0.0;
        Prediction unturned;
        ASSERT_EQ(predictor.predict(r, unturned), PredictStatus::kOk);
        EXPECT_GT(std::abs(unturned.throw_width_m - expected.throw_width_m), 0.05) << where;
      }
    }
  }
  PredictionRequest bad = request("can", 700.0);
  bad.drop_point_turn_rad = 3.2;
  Prediction out;
  EXPECT_EQ(predictor.predict(bad, out), PredictStatus::kOutOfRange);
  bad.drop_point_turn_rad = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(predictor.predict(bad, out), PredictStatus::kNotFinite);
}

}  // namespace
}  // namespace spread::predict

namespace spread::predict {
namespace {

// One reading of a run's flight effects for every reader: the recorded ones, or for a run that records none
// the four there were when runs began to record them (such tables flew all of them); an unknown one is
// refused.
TEST(RunFlightEffects, RecordedOrElseEveryFlightEffect) {
  tables::Run run;
  run.stats_json = "{\"speed_mean\":1.0}";
  EXPECT_EQ(run_flight_effects(run), flight::kDrag | flight::kMagnus | flight::kSpinDecay | flight::kWind);
  run.stats_json = "{\"flight_effects\":\"drag\"}";
  EXPECT_EQ(run_flight_effects(run), flight::EffectSet{flight::kDrag});
  run.stats_json = "{\"flight_effects\":\"\"}";
  EXPECT_EQ(run_flight_effects(run), flight::EffectSet{0});
  run.stats_json = "{\"flight_effects\":\"drag,levitation\"}";
  EXPECT_THROW(run_flight_effects(run), std::invalid_argument);
}

}  // namespace
}  // namespace spread::predict
