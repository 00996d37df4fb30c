// The as-applied map against what it must reproduce: the tray test's CV where the field is spread in
// straight passes without ends or edges, the metered mass (applied + beyond the boundary + not landed),
// and linearity (a pass spread twice doubles its cells). On the synthetic launch table (a real table
// written by tables::TableWriter, tests/predict/synthetic_table.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "libspread/analysis/field/as_applied.hpp"
#include "libspread/analysis/field/field_summary.hpp"
#include "libspread/analysis/field/field_wind.hpp"
#include "libspread/analysis/field/plan.hpp"
#include "libspread/analysis/field/rate_grid_csv.hpp"
#include "libspread/analysis/field/stamp_pattern.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace spread::field {
namespace {

constexpr double kBout_m = 18.0;
constexpr double kRate_kg_ha = 200.0;

struct Setting {
  predict::Predictor predictor{testing::synthetic_contents()};
  predict::Prediction prediction;
  StampPattern pattern;
  Setting() {
    predict::PredictionRequest r;
    r.material = "can";
    r.rpm = 650.0;
    r.bout_width_m = kBout_m;
    r.tray_width_m = 0.5;
    EXPECT_EQ(predictor.predict(r, prediction), predict::PredictStatus::kOk);
    pattern = stamp_pattern(prediction, 0.5);
  }
};
Setting& setting() {
  static Setting s;
  return s;
}

RunSettings run_settings() {
  RunSettings s;
  s.target_rate_kg_ha = kRate_kg_ha;
  s.bout_width_m = kBout_m;
  return s;
}

Pass straight(double x_m, double from_y_m, double to_y_m) {
  Pass p;
  p.path = {{x_m, from_y_m}, {x_m, to_y_m}};
  return p;
}

TEST(FieldAsApplied, StampPatternHoldsTheLandedMass) {
  const Setting& s = setting();
  double landed = 0.0;
  for (std::size_t i = 0; i < s.prediction.landing_mass_fraction.size(); ++i) {
    if (std::isfinite(s.prediction.landing_x_m[i])) landed += s.prediction.landing_mass_fraction[i];
  }
  EXPECT_NEAR(s.pattern.landed_fraction, landed, 1e-12);
  EXPECT_GT(s.pattern.size(), 100u);
}

TEST(FieldAsApplied, StraightPassesWithoutEndsGiveTheTrayTestCv) {
  // A 180 m × 200 m field, ten bouts; the passes run 80 m beyond both ends and four bouts beyond both
  // sides, to and fro, so every cell of the field sees the overlap of the tray test's to-and-fro passes.
  const Setting& s = setting();
  const Boundary field = make_boundary({{0, 0}, {180, 0}, {180, 200}, {0, 200}}, "local", "test");
  std::vector<Pass> passes;
  for (int k = -4; k < 14; ++k) {
    const double x = (k + 0.5) * kBout_m;
    passes.push_back(k % 2 == 0 ? straight(x, -80.0, 280.0) : straight(x, 280.0, -80.0));
  }
  const AsApplied run = spread_passes(field, passes, {&s.pattern, 1}, run_settings());
  const FieldSummary f = summarise(run, field, kRate_kg_ha);
  EXPECT_EQ(f.cells_inside, 360u * 400u);
  // Within two standard errors of the tray test's CV (its Monte Carlo error over the launch samples)...
  const double tray_cv = s.prediction.cv_to_and_fro;
  EXPECT_NEAR(f.cv, tray_cv, 2.0 * s.prediction.cv_to_and_fro_se) << "tray CV " << tray_cv << " ± "
                                                                   << s.prediction.cv_to_and_fro_se;
  // ...and in fact the same distribution: the cells repeat one bout's trays (the stamp's columns are the
  // trays' kernel estimate), whose CV takes the sample standard deviation over n = W / 0.5 m trays while
  // the field's is over ~10⁵ cells, so the two differ by √((n − 1)/n) alone.
  const double n = kBout_m / 0.5;
  EXPECT_NEAR(f.cv * std::sqrt(n / (n - 1.0)), tray_cv, 2e-3 * tray_cv);
  // Every kilogram inside lands at the target rate on average (each bout gets one pass's landed mass).
  EXPECT_NEAR(f.mean_rate_kg_ha, kRate_kg_ha * s.pattern.landed_fraction, 1e-6 * kRate_kg_ha);
}

TEST(FieldAsApplied, StraightPassesInWindGiveTheTrayTestCvWithItsReturnPass) {
  // The same field in wind, each pass stamped with the pattern of its own heading (the field's wind turned
  // into that heading's machine frame, wind_in_machine_frame). The tray test's to-and-fro CV must be
  // the field's with the return pass meeting the wind from the other side (return_pass.cpp) — not the
  // outgoing pattern mirrored, which lays the drift down towards the wind on every other pass.
  Setting& s = setting();
  const Boundary field = make_boundary({{0, 0}, {180, 0}, {180, 200}, {0, 200}}, "local", "test");
  std::vector<Pass> passes;
  for (int k = -4; k < 14; ++k) {
    const double x = (k + 0.5) * kBout_m;
    passes.push_back(k % 2 == 0 ? straight(x, -80.0, 280.0) : straight(x, 280.0, -80.0));
    passes.back().setting = k % 2 == 0 ? 0 : 1;  // stamps[0] heading north, stamps[1] heading south
  }
  struct Wind {
    double east_m_s, north_m_s;
    predict::ReturnPass read_as;
  };
  for (const Wind wind : {Wind{3.0, 0.0, predict::ReturnPass::kRacetrack}, Wind{2.5, 1.5, predict::ReturnPass::kFlown}}) {
    SCOPED_TRACE("wind east " + std::to_string(wind.east_m_s) + " north " + std::to_string(wind.north_m_s));
    predict::PredictionRequest r;
    r.material = "can";
    r.rpm = 650.0;
    r.bout_width_m = kBout_m;
    std::vector<StampPattern> stamps;
    for (const Point forward : {Point{0.0, 1.0}, Point{0.0, -1.0}}) {
      const Point machine_wind = wind_in_machine_frame(forward, wind.east_m_s, wind.north_m_s);
      predict::PredictionRequest heading = r;
      heading.wind_x_m_s = machine_wind.x_m;
      heading.wind_y_m_s = machine_wind.y_m;
      predict::Prediction p;
      ASSERT_EQ(s.predictor.predict(heading, p), predict::PredictStatus::kOk);
      stamps.push_back(stamp_pattern(p, 0.5));
    }
    const FieldSummary f = summarise(spread_passes(field, passes, stamps, run_settings()), field, kRate_kg_ha);
    // The pass heading north meets the wind as the tray test's outgoing pass: x east, y north.
    r.wind_x_m_s = wind.east_m_s;
    r.wind_y_m_s = wind.north_m_s;
    predict::Prediction tray_test;
    ASSERT_EQ(s.predictor.predict(r, tray_test), predict::PredictStatus::kOk);
    EXPECT_EQ(tray_test.return_pass, wind.read_as);
    const double n = kBout_m / 0.5;
    EXPECT_NEAR(f.cv * std::sqrt(n / (n - 1.0)), tray_test.cv_to_and_fro, 5e-3 * tray_test.cv_to_and_fro)
        << "field " << f.cv << ", tray test " << tray_test.cv_to_and_fro;
    // The outgoing pattern mirrored on every other pass is another field: over six times further off
    // (on this table's patterns 13 % and 5 % above the field's CV).
    const auto outgoing = tray_test.tray_mass_fraction;
    const double mirrored = metrics::cv_at_trays(outgoing, tray_test.trays, static_cast<int>(n), metrics::Overlap::kToAndFro);
    EXPECT_GT(std::abs(mirrored - f.cv * std::sqrt(n / (n - 1.0))), 0.03 * tray_test.cv_to_and_fro)
        << "mirrored outgoing pattern " << mirrored;
  }
}

TEST(FieldAsApplied, AppliedAndBeyondMakeTheMeteredMass) {
  // A pentagon with one headland round and tramlines: mass in the field, beyond it and not landed add up to
  // what the metering delivered, rate × W × the length driven.
  const Setting& s = setting();
  const Boundary field =
      make_boundary({{0, 0}, {210, -15}, {260, 120}, {120, 190}, {-20, 110}}, "local", "test");
  PlanSettings plan;
  plan.bout_width_m = kBout_m;
  plan.headland_passes = 1;
  const std::vector<Pass> passes = plan_field(field, plan);
  double driven_m = 0.0;
  for (const Pass& p : passes) driven_m += path_length_m(p.path);
  const AsApplied run = spread_passes(field, passes, {&s.pattern, 1}, run_settings());
  const FieldSummary f = summarise(run, field, kRate_kg_ha);
  const double metered_kg = kRate_kg_ha / 1e4 * kBout_m * driven_m;
  EXPECT_NEAR(run.metered_kg, metered_kg, 1e-9 * metered_kg);
  EXPECT_NEAR(f.applied_kg + f.beyond_kg + f.not_landed_kg, metered_kg, 1e-3 * metered_kg);
  EXPECT_GT(f.beyond_kg, 0.0);  // a normal setting on the outermost round throws over the boundary
  EXPECT_GT(f.applied_kg, 0.8 * metered_kg);
  EXPECT_GT(f.under_area_m2 + f.over_area_m2, 0.0);  // wedges and ends: a real field is not uniform
  EXPECT_NEAR(f.under_area_m2 + f.within_area_m2 + f.over_area_m2, f.field_area_m2, 1e-6);
  EXPECT_NEAR(f.field_area_m2, field.area_m2, 0.01 * field.area_m2);
}

TEST(FieldAsApplied, APassSpreadTwiceDoublesItsCells) {
  const Setting& s = setting();
  const Boundary field = make_boundary({{0, 0}, {100, 0}, {100, 150}, {0, 150}}, "local", "test");
  Pass pass;
  pass.path = {{30.0, 10.0}, {42.0, 80.0}, {45.0, 140.0}};  // not along the grid: bilinear shares everywhere
  const AsApplied once = spread_passes(field, {pass}, {&s.pattern, 1}, run_settings());
  const AsApplied twice = spread_passes(field, {pass, pass}, {&s.pattern, 1}, run_settings());
  ASSERT_EQ(once.grid.mass_kg.size(), twice.grid.mass_kg.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < once.grid.mass_kg.size(); ++i) {
    largest = std::max(largest, once.grid.mass_kg[i]);
    ASSERT_NEAR(twice.grid.mass_kg[i], 2.0 * once.grid.mass_kg[i], 1e-12 * (1.0 + once.grid.mass_kg[i])) << i;
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_NEAR(twice.metered_kg, 2.0 * once.metered_kg, 1e-12 * once.metered_kg);
}

TEST(FieldAsApplied, TheGridCsvHoldsTheAppliedMass) {
  // The CSV a GIS reads: its inside cells' rates times the cell area give back the applied mass (to the
  // file's 0.001 kg/ha), and the CRS is stated.
  const Setting& s = setting();
  const Boundary field = make_boundary({{0, 0}, {100, 0}, {120, 150}, {0, 130}}, "local", "test");
  PlanSettings plan;
  plan.bout_width_m = kBout_m;
  const AsApplied run = spread_passes(field, plan_field(field, plan), {&s.pattern, 1}, run_settings());
  const FieldSummary f = summarise(run, field, kRate_kg_ha);
  const std::string path = (std::filesystem::temp_directory_path() / "field_grid_test.csv").string();
  write_rate_grid_csv(path, run.grid, inside_mask(run.grid, field.ring), field.crs);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_NE(line.find("in local"), std::string::npos) << line;
  std::getline(in, line);
  EXPECT_EQ(line, "x_m,y_m,rate_kg_ha,inside");
  double applied_kg = 0.0;
  std::size_t inside = 0;
  double x = 0, y = 0, rate = 0;
  int flag = 0;
  while (std::getline(in, line)) {
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%d", &x, &y, &rate, &flag), 4) << line;
    if (flag) {
      applied_kg += rate * 0.25 / 1e4;
      ++inside;
    }
  }
  std::filesystem::remove(path);
  EXPECT_EQ(inside, f.cells_inside);
  EXPECT_NEAR(applied_kg, f.applied_kg, 1e-6 * f.applied_kg + 0.0005 * 0.25 / 1e4 * static_cast<double>(inside));
}

TEST(FieldAsApplied, SameInputsSameMap) {
  const Setting& s = setting();
  const Boundary field = make_boundary({{0, 0}, {100, 0}, {100, 150}, {0, 150}}, "local", "test");
  PlanSettings plan;
  plan.bout_width_m = kBout_m;
  const auto passes = plan_field(field, plan);
  const AsApplied a = spread_passes(field, passes, {&s.pattern, 1}, run_settings());
  const AsApplied b = spread_passes(field, passes, {&s.pattern, 1}, run_settings());
  EXPECT_EQ(a.grid.mass_kg, b.grid.mass_kg);
}

}  // namespace
}  // namespace spread::field
