// The advice on the main job's table (the DEM table of scenes/default.toml, built by the ctest fixture
// capi.fixture.default_scene), judged on the ground beyond the window each search optimises:
// - border and edge settings, the ground rebuilt here from the passes' own predictions over every bout the
//   last pass reaches: no bout more than 10 % over-applied (> 120 %), the last bout's shortfall stated;
// - no search turns a drop point outside the turns the table validates (the scene's, written by
//   lookup_builder);
// - wind compensation against a brute force of each disc's own drop point, and on launch samples it did
//   not choose on;
// - the headline working width under bootstrap resamples of the launch samples.
// Run through ctest (the fixture builds the file).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/edge_spreading.hpp"
#include "libspread/analysis/predict/setting_chart.hpp"
#include "libspread/analysis/predict/width_stability.hpp"
#include "libspread/analysis/predict/wind_compensation.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace {

namespace pr = spread::predict;
namespace metrics = spread::metrics;
constexpr double kDeg = spread::kPi / 180.0;

#define REQUIRE_DEFAULT_TABLE()                                                                                    \
  if (!std::filesystem::exists(SPREAD_DEFAULT_TABLE)) {                                                            \
    GTEST_SKIP() << SPREAD_DEFAULT_TABLE << " missing: run through ctest (fixture capi.fixture.default_scene)";    \
  }

pr::PredictionRequest urea(double bout_width_m) {
  pr::PredictionRequest r;
  r.material = "Urea";
  r.rpm = 600.0;
  r.bout_width_m = bout_width_m;
  r.cv_target = 0.10;
  return r;
}

// The ground across the last bouts with the edge on the right, rebuilt from predictions: the passes before
// at the field's setting (pass k at −kW, mirrored for odd k), the last pass at `setting` (the edge-side
// disc's landings times its flow). Rates as a share of one pass's landed mass per bout width.
struct Ground {
  metrics::TrayLayout trays;
  std::vector<double> rate;
};

// `interior`: the passes continued past the edge instead (what the field's interior gets at each place).
Ground ground(pr::Predictor& predictor, const pr::PredictionRequest& field, const pr::EdgeSetting& setting,
              bool interior = false) {
  pr::PredictionRequest normal = field;
  normal.standard_errors = false;
  pr::Prediction p0;
  EXPECT_EQ(predictor.predict(normal, p0), pr::PredictStatus::kOk);
  std::vector<double> x0(p0.landing_x_m.begin(), p0.landing_x_m.end());
  std::vector<double> m0(p0.landing_mass_fraction.begin(), p0.landing_mass_fraction.end());
  const double kernel_m = p0.kernel_half_width_m;
  pr::PredictionRequest last = normal;
  last.rpm = 0.0;
  last.disc_rpm = {field.rpm, setting.disc.rpm};
  last.disc_drop_point_turn_rad = {
      std::isnan(setting.field_side_drop_point_turn_rad) ? 0.0 : setting.field_side_drop_point_turn_rad,
      setting.disc.drop_point_turn_rad};
  last.kernel_half_width_m = kernel_m;
  pr::Prediction p1;
  EXPECT_EQ(predictor.predict(last, p1), pr::PredictStatus::kOk);
  std::vector<double> x1(p1.landing_x_m.begin(), p1.landing_x_m.end());
  std::vector<double> m1(p1.landing_mass_fraction.begin(), p1.landing_mass_fraction.end());
  for (std::size_t i = p1.left_landing_count; i < m1.size(); ++i) m1[i] *= setting.flow_fraction;

  Ground g;
  g.trays = metrics::tray_layout_covering(80.0, 0.5);
  g.rate.assign(static_cast<std::size_t>(g.trays.tray_count), 0.0);
  std::vector<double> x(x0.size());
  for (int k = interior ? -20 : 1; k <= 20; ++k) {
    for (std::size_t i = 0; i < x0.size(); ++i) x[i] = (k % 2 != 0 ? -x0[i] : x0[i]) - k * field.bout_width_m;
    metrics::accumulate_transverse_kernel(x, m0, g.trays, kernel_m, g.rate);
  }
  if (!interior) metrics::accumulate_transverse_kernel(x1, m1, g.trays, kernel_m, g.rate);
  double landed = 0.0;
  for (std::size_t i = 0; i < x0.size(); ++i) landed += std::isfinite(x0[i]) ? m0[i] : 0.0;
  for (double& r : g.rate) r /= landed * g.trays.tray_width_m / field.bout_width_m;
  return g;
}

// Length (m) of [from, to] over the trays k where `where(k)` holds (trays counted by their overlap).
template <typename Where>
double length_where(const Ground& g, double from_m, double to_m, Where where) {
  double length = 0.0;
  for (int k = 0; k < g.trays.tray_count; ++k) {
    const double a = std::max(from_m, g.trays.left_edge_m() + k * g.trays.tray_width_m);
    const double b = std::min(to_m, g.trays.left_edge_m() + (k + 1) * g.trays.tray_width_m);
    if (b > a && where(static_cast<std::size_t>(k))) length += b - a;
  }
  return length;
}

// At 11 m and 12 m bouts, border (at the field edge and 3 m inside it, water without a border device) and
// edge spreading, whether or not a setting meets the thresholds: judged on the whole ground the last pass
// reaches, no bout
// gets more than 10 % of its width above 120 % of the field's rate where the field's interior gets less (the
// search once turned the field-side disc −90° and put 122–244 % on the bout before while reporting none;
// at 12 m the interior itself reaches 127 %), the last bout's under-applied length is stated and agrees with
// the ground, and edge spreading's rate is read over the strip ending at the line.
TEST(DefaultEdge, NoBoutTheLastPassReachesIsFlooded) {
  REQUIRE_DEFAULT_TABLE();
  pr::Predictor predictor(spread::tables::read_table_file(SPREAD_DEFAULT_TABLE));
  struct Case {
    pr::EdgeKind kind;
    double gap_m;
  };
  for (const double bout_width_m : {11.0, 12.0}) {
    const pr::PredictionRequest field = urea(bout_width_m);
    for (const Case c : {Case{pr::EdgeKind::kBorder, 0.0}, Case{pr::EdgeKind::kBorder, 3.0}, Case{pr::EdgeKind::kEdge, 0.0}}) {
      pr::EdgeRequest edge;
      edge.kind = c.kind;
      edge.gap_m = c.gap_m;
      const pr::EdgeKind kind = c.kind;
      const pr::EdgeResult r = pr::find_edge_setting(predictor, field, edge);
      ASSERT_EQ(r.status, pr::PredictStatus::kOk);
      const std::string what = std::string(pr::to_string(kind)) + " at " + std::to_string(bout_width_m) + " m, gap " +
                               std::to_string(c.gap_m) + " m";
      const Ground g = ground(predictor, field, r.setting), inside = ground(predictor, field, r.setting, true);
      const double line_m = r.profile.edge_line_m;
      for (int bout = 0; bout < 4; ++bout) {
        const double from = bout == 0 ? -0.5 * bout_width_m : -(bout + 0.5) * bout_width_m;
        const double to = bout == 0 ? line_m : -(bout - 0.5) * bout_width_m;
        const double flooded_m =
            length_where(g, from, to, [&](std::size_t k) { return g.rate[k] > std::max(1.20, inside.rate[k]); });
        EXPECT_LE(flooded_m, 0.10 * bout_width_m) << what << ", bout " << bout << " before the last";
      }
      // The under-applied length of the last bout as the ground has it (within one tray).
      const double under_m = length_where(g, -0.5 * bout_width_m, line_m, [&](std::size_t k) {
        return g.rate[k] < std::min(r.profile.under_limit, inside.rate[k]);
      });
      EXPECT_NEAR(r.profile.under_applied_last_bout_m, under_m, 0.5) << what;
      if (kind == pr::EdgeKind::kEdge && r.profile.meets) {
        // The strip of one tray ending at the line.
        double strip = 0.0;
        for (int k = 0; k < g.trays.tray_count; ++k) {
          const double a = std::max(line_m - 0.5, g.trays.left_edge_m() + k * 0.5);
          const double b = std::min(line_m, g.trays.left_edge_m() + (k + 1) * 0.5);
          if (b > a) strip += g.rate[static_cast<std::size_t>(k)] * (b - a) / 0.5;
        }
        EXPECT_GE(strip, 0.8 - 0.01) << what;
      }
    }
  }
}

// The table states the turns the scene's DEM comparison validated, and no search leaves them.
TEST(DefaultAdvice, NoSearchTurnsADropPointOutsideTheValidatedRange) {
  REQUIRE_DEFAULT_TABLE();
  spread::tables::TableContents contents = spread::tables::read_table_file(SPREAD_DEFAULT_TABLE);
  ASSERT_TRUE(contents.drop_point_turn_validated_rad.has_value());
  pr::Predictor predictor(std::move(contents));
  const pr::TurnRange valid = predictor.drop_point_turn_range();
  EXPECT_LT(valid.low_rad, 0.0);
  EXPECT_GT(valid.high_rad, 0.0);
  EXPECT_LT(valid.high_rad - valid.low_rad, spread::kPi);  // not the whole circle: the DEM comparison bounds it
  const std::vector<double> widths{8, 11, 12, 18, 24};
  pr::SettingChartOptions options;
  options.cv_target = 0.10;
  const pr::SettingChart chart = pr::setting_chart(predictor, "Urea", widths, options);
  for (const pr::SettingChartRow& row : chart.rows) EXPECT_TRUE(valid.contains(row.drop_point_turn_rad)) << row.width_m;
  for (const double bout_width_m : {11.0, 12.0}) {
    for (const pr::EdgeKind kind : {pr::EdgeKind::kBorder, pr::EdgeKind::kEdge}) {
      pr::EdgeRequest edge;
      edge.kind = kind;
      const pr::EdgeResult r = pr::find_edge_setting(predictor, urea(bout_width_m), edge);
      EXPECT_TRUE(valid.contains(r.setting.disc.drop_point_turn_rad)) << bout_width_m;
      if (!std::isnan(r.setting.field_side_drop_point_turn_rad)) {
        EXPECT_TRUE(valid.contains(r.setting.field_side_drop_point_turn_rad)) << bout_width_m;
      }
    }
  }
  pr::PredictionRequest windy = urea(11.0);
  windy.wind_x_m_s = 3.0;
  pr::Prediction out;
  pr::PredictorWorkspace workspace(predictor);
  const pr::WindCompensation found = pr::compensate_wind(predictor, windy, out, workspace);
  for (const pr::DiscSetting& d : found.discs) EXPECT_TRUE(valid.contains(d.drop_point_turn_rad));
}

// The lowest field CV at the bout (the setting swapped on the return pass) over each disc's own drop
// point on a 5° grid within the validated turns, both discs at 600 rpm (the brute force the search must
// reach): from one prediction per turn (the discs fly apart), each disc's landings binned on one layout
// with one kernel.
double brute_force_cv(pr::Predictor& predictor, const pr::PredictionRequest& request) {
  const pr::TurnRange valid = predictor.drop_point_turn_range();
  std::vector<double> turns;
  for (int k = -36; k <= 36; ++k) {
    if (valid.contains(k * 5.0 * kDeg)) turns.push_back(k * 5.0 * kDeg);
  }
  const metrics::TrayLayout trays = metrics::tray_layout_covering(40.0, request.tray_width_m);
  const auto t = static_cast<std::size_t>(trays.tray_count);
  std::vector<std::vector<double>> left(turns.size(), std::vector<double>(t)), right = left;
  double kernel_m = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < turns.size(); ++i) {
    pr::PredictionRequest r = request;
    r.rpm = 0.0;
    r.disc_rpm = {request.rpm, request.rpm};
    r.disc_drop_point_turn_rad = {turns[i], turns[i]};
    r.standard_errors = false;
    r.kernel_half_width_m = kernel_m;
    pr::Prediction p;
    EXPECT_EQ(predictor.predict(r, p), pr::PredictStatus::kOk);
    kernel_m = p.kernel_half_width_m;
    const std::vector<double> x(p.landing_x_m.begin(), p.landing_x_m.end());
    const std::vector<double> m(p.landing_mass_fraction.begin(), p.landing_mass_fraction.end());
    const std::size_t split = p.left_landing_count;
    metrics::accumulate_transverse_kernel(std::span(x).first(split), std::span(m).first(split), trays, kernel_m, left[i]);
    metrics::accumulate_transverse_kernel(std::span(x).subspan(split), std::span(m).subspan(split), trays, kernel_m,
                                          right[i]);
  }
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> pattern(t);
  for (std::size_t i = 0; i < turns.size(); ++i) {
    for (std::size_t j = 0; j < turns.size(); ++j) {
      for (std::size_t k = 0; k < t; ++k) pattern[k] = left[i][k] + right[j][k];
      // The field's CV with the setting swapped on the return pass (which meets the wind from the other
      // side): in a lateral wind the return pass lands as the outgoing one, the racetrack overlap.
      best = std::min(best, metrics::cv_at_width(pattern, trays, request.bout_width_m, metrics::Overlap::kRacetrack));
    }
  }
  return best;
}

// In a 3 m/s crosswind at 11 m and 8 m: the compensation reaches the brute force over each disc's own drop
// point within half a point (it searches each disc's speed too, so it may do better).
TEST(DefaultWind, CompensationReachesTheBruteForce) {
  REQUIRE_DEFAULT_TABLE();
  pr::Predictor predictor(spread::tables::read_table_file(SPREAD_DEFAULT_TABLE));
  pr::PredictorWorkspace workspace(predictor);
  for (const double bout_width_m : {11.0, 8.0}) {
    pr::PredictionRequest request = urea(bout_width_m);
    request.wind_x_m_s = 3.0;
    const double brute = brute_force_cv(predictor, request);
    pr::Prediction out;
    const pr::WindCompensation found = pr::compensate_wind(predictor, request, out, workspace);
    ASSERT_EQ(found.status, pr::PredictStatus::kOk);
    EXPECT_LE(found.cv, brute + 0.005) << bout_width_m << " m: brute force " << brute;
    EXPECT_LT(found.cv, found.present_cv) << bout_width_m;
  }
}

// Chosen on half of the launch samples (every other sample of each row), judged on the other half, the
// answer applied as the compensation applies it (swapped on the return pass): where the present setting
// misses the target the compensation keeps a point or more of CV and at least 40 % of the gain it saw — it
// does not merely fit the noise of the samples it chose on (a CV from half a row's samples has a standard
// error of about 3 points).
TEST(DefaultWind, CompensationKeepsItsGainOnHeldOutSamples) {
  REQUIRE_DEFAULT_TABLE();
  const spread::tables::TableContents all = spread::tables::read_table_file(SPREAD_DEFAULT_TABLE);
  spread::tables::TableContents halves[2] = {all, all};
  for (int h = 0; h < 2; ++h) {
    halves[h].landing_data.clear();
    for (spread::tables::Run& run : halves[h].runs) {
      std::vector<spread::tables::LaunchSample> kept;
      for (std::size_t i = static_cast<std::size_t>(h); i < run.samples.size(); i += 2) kept.push_back(run.samples[i]);
      run.samples = std::move(kept);
    }
  }
  pr::Predictor choose(std::move(halves[0])), judge(std::move(halves[1]));
  pr::PredictorWorkspace workspace(choose);
  for (const double bout_width_m : {11.0, 8.0}) {
    pr::PredictionRequest request = urea(bout_width_m);
    request.wind_x_m_s = 3.0;
    pr::Prediction out;
    const pr::WindCompensation found = pr::compensate_wind(choose, request, out, workspace);
    ASSERT_EQ(found.status, pr::PredictStatus::kOk);
    pr::Prediction present, compensated;
    pr::PredictionRequest at = request;
    ASSERT_EQ(judge.predict(at, present), pr::PredictStatus::kOk);
    at.rpm = 0.0;
    at.disc_rpm = {found.discs[0].rpm, found.discs[1].rpm};
    at.disc_drop_point_turn_rad = {found.discs[0].drop_point_turn_rad, found.discs[1].drop_point_turn_rad};
    at.return_pass = pr::ReturnPassSettings::kSwapped;  // as the compensation applies it on the way back
    ASSERT_EQ(judge.predict(at, compensated), pr::PredictStatus::kOk);
    const double gain_chosen = found.present_cv - found.cv;
    const double gain_held_out = present.cv_to_and_fro - compensated.cv_to_and_fro;
    // Where the present setting misses the target (11 m) the gain must hold. At 8 m it already meets it
    // (7.7 % on the held-out half): of the 5.1 points the choosing half sees there only about 1.3 hold —
    // the rest is that half's noise — so there the compensation must only do no harm.
    const double kept = present.cv_to_and_fro > request.cv_target ? std::max(0.01, 0.4 * gain_chosen) : 0.0;
    EXPECT_GT(gain_held_out, kept) << bout_width_m << " m: chosen " << found.present_cv << " -> " << found.cv
                                   << ", held out " << present.cv_to_and_fro << " -> " << compensated.cv_to_and_fro;
  }
}

// Urea at 600 rpm against CV <= 10 % (the stated setting): over bootstrap resamples of the launch samples
// the headline stays where its ± says. A band that splits near 9 m in some resamples once took the headline
// from 11.3 m to about 8 m in a quarter of them (the upper part no longer established on its own); joined
// across a gap the samples do not show above the target, it stays.
TEST(DefaultWidth, HeadlineHoldsUnderResampling) {
  REQUIRE_DEFAULT_TABLE();
  pr::PredictionRequest request;
  request.material = "Urea";
  request.rpm = 600.0;
  request.cv_target = 0.10;
  const pr::WidthStability s =
      pr::width_stability(spread::tables::read_table_file(SPREAD_DEFAULT_TABLE), request, 40, 7);
  ASSERT_GT(s.headline_m, 10.0);
  ASSERT_TRUE(std::isfinite(s.interval_m));
  EXPECT_LE(s.beyond_1m_fraction, 0.05) << "2.5-97.5 %: " << s.quantile_025_m << "-" << s.quantile_975_m << " m";
  EXPECT_GE(s.quantile_025_m, s.headline_m - 2.0 * s.interval_m);
  EXPECT_LE(s.quantile_975_m, s.headline_m + 2.0 * s.interval_m);
}

}  // namespace
