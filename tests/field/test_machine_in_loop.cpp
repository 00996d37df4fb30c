// The field with the ECU in the loop (machine_in_loop.hpp): the mass the gates deliver is the mass the
// grid holds, whatever the gates' travel; runs repeat bit for bit; section control and border mode, run by
// the ECU's own logic over the C API, take mass off the boundary and overlap off the field; the discs pass
// through the states the ECU sets; bad settings are named. On the synthetic launch table written as a file
// (the ECU reads it through the C API, the stamps through the predictor).
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "capi/cpp/capi_spread_predictor.hpp"
#include "libspread/analysis/field/field_summary.hpp"
#include "libspread/analysis/field/machine_in_loop.hpp"
#include "libspread/analysis/field/plan.hpp"
#include "libspread/control/gate_response.hpp"
#include "libspread/core/error.hpp"
#include "tests/predict/synthetic_table.hpp"
#include "tests/support/error_message.hpp"

namespace spread::field {
namespace {

constexpr double kBout_m = 18.0;
constexpr double kRate_kg_ha = 200.0;

struct Tables {
  std::string path = (std::filesystem::temp_directory_path() / "spread_test_field_machine.sqlite").string();
  predict::Predictor predictor{testing::synthetic_contents()};
  std::unique_ptr<firmware::CapiSpreadPredictor> ecu;
  Tables() {
    testing::write_synthetic_table(path);
    ecu = std::make_unique<firmware::CapiSpreadPredictor>(path);
  }
};
Tables& tables() {
  static Tables t;
  return t;
}

predict::PredictionRequest field_request() {
  predict::PredictionRequest r;
  r.material = "can";
  r.rpm = 650.0;
  r.bout_width_m = kBout_m;
  r.tray_width_m = 0.5;
  return r;
}

MachineSettings settings(bool section_control, bool border) {
  MachineSettings s;
  s.target_rate_kg_ha = kRate_kg_ha;
  s.bout_width_m = kBout_m;
  s.rpm = 650.0;
  s.section_control = section_control;
  s.border = border;
  s.section_count = 4;  // two per side: one narrowing per side for the ECU's planner to search, and the border
  return s;
}

// A pentagon of about 2.6 ha with a slanted edge: headland corners and tramline wedges.
const Boundary& pentagon() {
  static const Boundary b = make_boundary({{0, 0}, {200, 0}, {200, 120}, {120, 170}, {0, 150}}, "local", "test");
  return b;
}

MachineRun run(const MachineSettings& s) {
  PlanSettings plan;
  plan.bout_width_m = kBout_m;
  plan.headland_passes = 1;
  Tables& t = tables();
  return run_machine(pentagon(), plan_field(pentagon(), plan), *t.ecu, t.predictor, field_request(), s);
}

TEST(FieldMachine, GatesDeliverWhatTheGridHolds) {
  // Applied + beyond + not landed = what the gates delivered, and with an ideal gate and no section control
  // that is rate · W · the length driven: the feed opens and shuts at the pass ends. A gate of 1 s travel
  // delivers the same: what its opening misses at a pass start its closing adds after the end.
  for (const double travel_s : {0.0, 1.0}) {
    MachineSettings s = settings(false, false);
    s.gate_full_travel_s = travel_s;
    const MachineRun r = run(s);
    const FieldSummary sum = summarise(r.applied, pentagon(), kRate_kg_ha);
    EXPECT_NEAR(sum.applied_kg + sum.beyond_kg + sum.not_landed_kg, sum.metered_kg, 1e-3 * sum.metered_kg) << travel_s;
    double driven_m = 0.0;
    for (const Pass& p : r.passes) driven_m += path_length_m(p.path);
    const double expected_kg = kRate_kg_ha / 1e4 * kBout_m * driven_m;
    EXPECT_NEAR(sum.metered_kg, expected_kg, 1e-3 * expected_kg) << travel_s;
  }
}

TEST(FieldMachine, SameSettingsSameGrid) {
  const MachineRun a = run(settings(true, true)), b = run(settings(true, true));
  ASSERT_EQ(a.applied.grid.mass_kg.size(), b.applied.grid.mass_kg.size());
  EXPECT_TRUE(a.applied.grid.mass_kg == b.applied.grid.mass_kg);
  EXPECT_EQ(a.section_switches, b.section_switches);
}

TEST(FieldMachine, SectionControlAndBorderLowerOverlapAndMassBeyond) {
  const MachineRun neither = run(settings(false, false)), both = run(settings(true, true));
  const FieldSummary n = summarise(neither.applied, pentagon(), kRate_kg_ha);
  const FieldSummary b = summarise(both.applied, pentagon(), kRate_kg_ha);
  EXPECT_LT(b.over_area_m2, n.over_area_m2);
  EXPECT_LT(b.beyond_kg, 0.5 * n.beyond_kg);
  // The ECU switched sections and ran its border setting (its planner searched over the C API).
  EXPECT_GT(both.section_switches, 0u);
  EXPECT_EQ(neither.section_switches, 0u);
  EXPECT_TRUE(both.border_applied);
  EXPECT_FALSE(neither.border_applied);
  EXPECT_GT(both.planner_searches, 0);
  // The border disc changes speed on the turns: the discs pass through more states than the field's two.
  EXPECT_GT(both.stamps_built, 2u);
}

TEST(FieldMachine, AWindAcrossTheFieldMovesTheMassDownwind) {
  // Tramlines north–south in a square, a 4 m/s wind from the west and no compensation: the mass beyond the
  // east boundary grows; the gates deliver the same.
  const Boundary field = make_boundary({{0, 0}, {180, 0}, {180, 180}, {0, 180}}, "local", "test");
  PlanSettings plan;
  plan.bout_width_m = kBout_m;
  plan.headland_passes = 0;
  plan.reference_edge = 3;  // the west edge, from (0, 180) to (0, 0): tramlines run north–south
  const auto east_of = [&](const AsApplied& run) {
    double kg = 0.0;
    for (int iy = 0; iy < run.grid.ny; ++iy) {
      for (int ix = 0; ix < run.grid.nx; ++ix) {
        if (run.grid.centre(ix, iy).x_m > 180.0) kg += run.grid.mass_kg[static_cast<std::size_t>(iy) * run.grid.nx + ix];
      }
    }
    return kg;
  };
  MachineSettings calm = settings(false, false), westerly = calm;
  westerly.wind_east_m_s = 4.0;
  westerly.wind_compensation = false;
  Tables& t = tables();
  const MachineRun still = run_machine(field, plan_field(field, plan), *t.ecu, t.predictor, field_request(), calm);
  const MachineRun windy = run_machine(field, plan_field(field, plan), *t.ecu, t.predictor, field_request(), westerly);
  EXPECT_GT(east_of(windy.applied), 1.5 * east_of(still.applied));
  EXPECT_NEAR(windy.applied.metered_kg, still.applied.metered_kg, 1e-9 * still.applied.metered_kg);
}

TEST(FieldMachine, BadSettingsAreNamed) {
  MachineSettings s = settings(true, false);
  s.section_count = 0;
  EXPECT_NE(testing::error_of([&] { run(s); }).find("section_count must be 1..16, got 0"), std::string::npos);
  s = settings(true, false);
  s.speed_m_s = -1.0;
  EXPECT_NE(testing::error_of([&] { run(s); }).find("speed_m_s must be > 0"), std::string::npos);
  s = settings(true, false);
  s.gate_full_travel_s = -0.5;
  EXPECT_NE(testing::error_of([&] { run(s); }).find("gate travel"), std::string::npos);
}

TEST(GateResponse, TravelsAtItsRate) {
  firmware::GateResponse gate(1.0);
  gate.step(1.0, 0.25);
  EXPECT_DOUBLE_EQ(gate.opening(), 0.25);
  gate.step(1.0, 1.0);
  EXPECT_DOUBLE_EQ(gate.opening(), 1.0);
  gate.step(0.0, 0.5);
  EXPECT_DOUBLE_EQ(gate.opening(), 0.5);
  firmware::GateResponse ideal(0.0);
  ideal.step(0.8, 0.05);
  EXPECT_DOUBLE_EQ(ideal.opening(), 0.8);
  EXPECT_THROW(firmware::GateResponse(-1.0), std::invalid_argument);
}

}  // namespace
}  // namespace spread::field
