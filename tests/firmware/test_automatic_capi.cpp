// Automatic mode against real launch tables through the C API: the table file is built by the ctest
// fixture `capi.fixture.default_scene` (lookup_builder scenes/default.toml, the main job's DEM table). Run
// through ctest, or by hand after building the file: test_firmware --gtest_filter=AutomaticModeCapi.*
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <thread>

#include "capi/cpp/capi_spread_predictor.hpp"
#include "libspread/control/ecu.hpp"
#include "firmware_sim/ecu/fixed_rate_loop.hpp"

namespace spread::firmware {
namespace {

using namespace std::chrono_literals;

class NoIo final : public LoopIo {
 public:
  void pump(Nanoseconds) override {}
  void after_step(const EcuStatus&) override {}
};

class AutomaticModeCapi : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(SPREAD_FIRMWARE_TEST_TABLES)) {
      GTEST_SKIP() << "table file " << SPREAD_FIRMWARE_TEST_TABLES
                   << " missing: run through ctest (fixture capi.fixture.default_scene runs lookup_builder)";
    }
    predictor_ = std::make_unique<CapiSpreadPredictor>(SPREAD_FIRMWARE_TEST_TABLES, 15.0);
    ASSERT_FALSE(predictor_->materials().empty());
    material_ = predictor_->materials().front();
  }

  EcuCommand automatic(std::int64_t sequence, double width_m) const {
    EcuCommand c;
    c.sequence = sequence;
    c.mode = static_cast<std::int32_t>(Mode::kAutomatic);
    c.rate_setpoint_kg_ha = 200.0;
    c.width_setpoint_m = width_m;
    c.ground_speed_m_s = 3.0;
    c.material = material_;
    c.section_count = 8;
    c.section_on.fill(true);
    c.work_state = true;
    return c;
  }

  // Manual mode at `rpm` on bouts of `width_m`, every section on.
  EcuCommand manual(std::int64_t sequence, double width_m, double rpm) const {
    EcuCommand c = automatic(sequence, width_m);
    c.mode = static_cast<std::int32_t>(Mode::kManual);
    c.rpm_setpoint = rpm;
    return c;
  }

  // An ECU on the table with a planner that plans inline (deterministic) over a C API handle of its own,
  // that handle's CV target `planning_cv_percent`.
  struct PlannedEcu {
    PlannedEcu(SpreadPredictor& predictor, const EcuParameters& p, double planning_cv_percent)
        : planning(SPREAD_FIRMWARE_TEST_TABLES, planning_cv_percent),
          planner(planning, p.section_max_beyond_percent, SectionPlanner::Threading::kInline),
          ecu(clock, p, &predictor, &planner),
          loop(clock, 20.0) {}
    void run(Nanoseconds duration) {
      NoIo io;
      loop.run(ecu, io, duration);
    }
    CapiSpreadPredictor planning;
    SectionPlanner planner;
    ManualClock clock;
    Ecu ecu;
    FixedRateLoop loop;
  };

  double first_band_width_at(double rpm) {
    SpreadPrediction p;
    EXPECT_EQ(predictor_->predict(material_, rpm, 24.0, p), PredictionOutcome::kOk);
    return p.first_band_width_m;  // what automatic mode aims at (rpm_for_width_solver.hpp)
  }

  std::unique_ptr<CapiSpreadPredictor> predictor_;
  std::string material_;
};

TEST_F(AutomaticModeCapi, ReachesARequestedWidth) {
  const RpmRange range = predictor_->rpm_range(material_);
  ASSERT_LT(range.min_rpm, range.max_rpm);
  // A width the tables can deliver: the effective width a little above the lowest usable speed.
  EcuParameters p;
  p.command_timeout = 0s;
  p.auto_rpm_min = std::max(range.min_rpm, p.auto_rpm_min);
  p.auto_rpm_max = std::min(range.max_rpm, p.auto_rpm_max);
  const double probe_rpm = p.auto_rpm_min + 0.6 * (p.auto_rpm_max - p.auto_rpm_min);
  const double requested_m = first_band_width_at(probe_rpm);
  ASSERT_GT(requested_m, 0.0) << "no usable working width at " << probe_rpm << " r/min";

  ManualClock clock;
  Ecu ecu(clock, p, predictor_.get());
  FixedRateLoop loop(clock, 20.0);
  NoIo io;
  ASSERT_FALSE(ecu.apply_command(automatic(1, requested_m)).has_value());
  loop.run(ecu, io, 10s);
  const EcuStatus s = ecu.status();
  EXPECT_TRUE(s.width_reachable);
  EXPECT_EQ(s.fault_codes, 0u) << "faults 0x" << std::hex << s.fault_codes;
  EXPECT_GE(s.rpm_target, p.auto_rpm_min);
  EXPECT_LE(s.rpm_target, p.auto_rpm_max);
  EXPECT_NEAR(s.rpm_actual, s.rpm_target, 0.5) << "disc settled after 10 s (tau 0.8 s)";
  // The solved speed reaches the width. (Table-based widths are quantised by the 0.5 m trays and not
  // monotonic in rpm, so the check is on the prediction at the chosen speed.)
  EXPECT_GE(first_band_width_at(s.rpm_target), requested_m);
  EXPECT_TRUE(std::isfinite(s.throw_width_m));
  EXPECT_TRUE(std::isfinite(s.effective_width_m));
  // Every predicted width carries its Monte Carlo standard error from the C API.
  EXPECT_GT(s.effective_width_se_m, 0.0);
  EXPECT_GT(s.throw_width_se_m, 0.0);
  EXPECT_GT(s.cv_se_percent, 0.0);
  // Not "throw >= effective": the throw width leaves out 0.5 % of the mass on each side, the working
  // width is a CV criterion on the 0.5 m tray grid, and a box-shaped pattern meets the CV target at a bout
  // width up to its full extent (docs/messages.md, status_t). It never exceeds the throw width by more than
  // a tray or two.
  EXPECT_LE(s.effective_width_m, s.throw_width_m + 1.0);
}

// Settled on its chosen speed, the ECU's own status must deliver what it reports as reachable: the
// effective width at least the set-point and the CV at the set-point within the target. Choosing the
// speed exactly at the edge of what reaches the width, and judging only the solver's curve, broke this
// for set-points between the 0.5 m tray widths: on the default DEM table (Urea, set-points 6.0-10.0 m
// every 0.1 m) 12 of 41 were reported reachable with a settled CV of 16.3-18.0 %. The solver's margin
// and the check of the settled prediction keep it true (41 of 41 then deliver).
TEST_F(AutomaticModeCapi, ReachableMeansTheSettledPatternDelivers) {
  EcuParameters p;
  p.command_timeout = 0s;
  const RpmRange range = predictor_->rpm_range(material_);
  p.auto_rpm_min = std::max(range.min_rpm, p.auto_rpm_min);
  p.auto_rpm_max = std::min(range.max_rpm, p.auto_rpm_max);
  const double narrowest = first_band_width_at(p.auto_rpm_min);
  const double widest = first_band_width_at(p.auto_rpm_max);
  ASSERT_LT(narrowest, widest);
  int reachable = 0;
  // Every 0.3 m: over 3 m the set-points fall on every tenth of a metre between the 0.5 m trays.
  for (double width_m = std::ceil(narrowest); width_m <= std::floor(widest); width_m += 0.3) {
    ManualClock clock;
    Ecu ecu(clock, p, predictor_.get());
    FixedRateLoop loop(clock, 20.0);
    NoIo io;
    ASSERT_FALSE(ecu.apply_command(automatic(1, width_m)).has_value());
    loop.run(ecu, io, 15s);
    const EcuStatus s = ecu.status();
    if (s.width_reachable) {
      ++reachable;
      EXPECT_GE(s.effective_width_m, width_m) << "set-point " << width_m << " m at " << s.rpm_actual << " r/min";
      EXPECT_LE(s.cv_percent, 15.0) << "set-point " << width_m << " m at " << s.rpm_actual << " r/min";
      EXPECT_EQ(s.fault_codes & fault_bit(Fault::kWidthOutOfReach), 0u);
    } else {
      EXPECT_NE(s.fault_codes & fault_bit(Fault::kWidthOutOfReach), 0u) << "unreachable is a fault";
    }
  }
  EXPECT_GT(reachable, 0);
}

// Section control through the discs on the main job's table, planned inline (deterministic): with the
// right side's outer section off, the right disc takes the border search's setting for an edge line at
// the end of section 7, the left disc keeps the field's speed, the metered flow follows the discs'
// shares, and the right side's sections reported spread are those whose strips the narrowed pass still
// gives the section-on share of the field's rate.
TEST_F(AutomaticModeCapi, SectionsOffNarrowTheirSideThroughItsDisc) {
  EcuParameters p;
  p.command_timeout = 0s;
  PlannedEcu machine(*predictor_, p, 15.0);
  EcuCommand c = manual(1, 12.0, 600.0);
  c.section_on[7] = false;
  ASSERT_FALSE(machine.ecu.apply_command(c).has_value());
  machine.run(10s);
  const EcuStatus s = machine.ecu.status();
  EXPECT_EQ(machine.planner.searches(), 1) << "one narrowing, planned once and then answered from the cache";
  CapiSpreadPredictor& planning = machine.planning;

  // The same search through the C API by hand: the edge line at 12/2 - 1.5 m on the right; sections 5-8
  // are 1.5 m strips outward from the centre line.
  SideNarrowing expected;
  const std::array<SideStrip, 4> strips{SideStrip{0.0, 1.5}, SideStrip{1.5, 3.0}, SideStrip{3.0, 4.5}, SideStrip{4.5, 6.0}};
  std::array<double, 4> rate{};
  NarrowingRequest request;
  request.material = material_;
  request.rpm = 600.0;
  request.bout_width_m = 12.0;
  request.side = kRightDisc;
  request.edge_line_m = 4.5;
  request.max_beyond_percent = p.section_max_beyond_percent;
  ASSERT_EQ(planning.narrow_side(request, strips, rate, expected), PredictionOutcome::kOk);
  EXPECT_EQ(s.disc_rpm_target[kRightDisc], expected.rpm);
  EXPECT_EQ(s.disc_drop_point_turn_rad[kRightDisc], expected.drop_point_turn_rad);
  EXPECT_NEAR(s.disc_rpm_actual[kRightDisc], expected.rpm, 0.5);
  EXPECT_EQ(s.disc_rpm_target[kLeftDisc], 600.0);
  EXPECT_NEAR(s.disc_rpm_actual[kLeftDisc], 600.0, 0.5);
  EXPECT_EQ(s.disc_drop_point_turn_rad[kLeftDisc],
            std::isnan(expected.other_drop_point_turn_rad) ? 0.0 : expected.other_drop_point_turn_rad);
  EXPECT_EQ(s.disc_flow_fraction[kLeftDisc], 1.0);
  EXPECT_EQ(s.disc_flow_fraction[kRightDisc], expected.flow_fraction);
  EXPECT_TRUE(expected.flow_fraction < 1.0 || expected.rpm != 600.0 || expected.drop_point_turn_rad != 0.0)
      << "the right disc is set apart from the field";
  const double field_flow_kg_s = 200.0 * 12.0 * 3.0 / 10000.0;  // kg/ha × m × m/s → kg/s
  EXPECT_NEAR(s.mass_flow_kg_s, field_flow_kg_s * (1.0 + expected.flow_fraction) / 2.0, 1e-9);
  EXPECT_EQ(s.section_mask, 0x7F);
  std::uint16_t right = 0;
  for (std::size_t j = 0; j < 4; ++j) {
    if (rate[j] >= p.section_on_rate_percent) right |= static_cast<std::uint16_t>(1u << (4 + j));
  }
  EXPECT_EQ(s.section_actual_mask, 0x0F | right)
      << "the right side's strips get " << rate[0] << ", " << rate[1] << ", " << rate[2] << ", " << rate[3]
      << " % of the field's rate";
  EXPECT_EQ(right & 0x80, 0) << "section 8, switched off, is not spread";
  EXPECT_EQ(s.sides_pending, 0);
  EXPECT_EQ(s.fault_codes, 0u) << "faults 0x" << std::hex << s.fault_codes;
}

// Border spreading and wind compensation as ECU modes on the main job's table, planned inline: the
// border side's disc takes the border search's setting for the edge line `gap` inside the bout's edge,
// its sections stay on; with wind compensation each disc takes spread_compensate_wind's setting.
TEST_F(AutomaticModeCapi, BorderAndWindModesSetTheDiscsApart) {
  EcuParameters p;
  p.command_timeout = 0s;
  // Compensating for a CV target of 10 % on 11 m bouts (docs/c-api.md "Wind compensation").
  PlannedEcu machine(*predictor_, p, 10.0);
  CapiSpreadPredictor& planning = machine.planning;
  EcuCommand c = manual(1, 12.0, 600.0);
  c.border_mode = static_cast<std::int32_t>(BorderMode::kLeftBorder);
  c.border_gap_m = 1.0;
  ASSERT_FALSE(machine.ecu.apply_command(c).has_value());
  machine.run(8s);
  EcuStatus s = machine.ecu.status();
  NarrowingRequest request;
  request.material = material_;
  request.rpm = 600.0;
  request.bout_width_m = 12.0;
  request.side = kLeftDisc;
  request.edge_line_m = 5.0;
  request.max_beyond_percent = p.section_max_beyond_percent;
  SideNarrowing border;
  const std::array<SideStrip, 4> strips{SideStrip{0.0, 1.5}, SideStrip{1.5, 3.0}, SideStrip{3.0, 4.5}, SideStrip{4.5, 6.0}};
  std::array<double, 4> rate{};
  ASSERT_EQ(planning.narrow_side(request, strips, rate, border), PredictionOutcome::kOk);
  EXPECT_TRUE(s.border_applied);
  EXPECT_EQ(s.disc_rpm_target[kLeftDisc], border.rpm);
  EXPECT_EQ(s.disc_drop_point_turn_rad[kLeftDisc], border.drop_point_turn_rad);
  EXPECT_EQ(s.disc_flow_fraction[kLeftDisc], border.flow_fraction);
  EXPECT_EQ(s.disc_rpm_target[kRightDisc], 600.0);
  // The left side's sections (4, 3, 2, 1 from the centre) as the border pass spreads them.
  std::uint16_t left = 0;
  for (std::size_t j = 0; j < 4; ++j) {
    if (rate[j] >= p.section_on_rate_percent) left |= static_cast<std::uint16_t>(1u << (3 - j));
  }
  EXPECT_EQ(s.section_actual_mask, 0xF0 | left);

  // Wind compensation in a 3 m/s crosswind, no border.
  c = manual(2, 11.0, 600.0);
  c.wind_compensation = true;
  c.wind_x_m_s = 3.0;
  ASSERT_FALSE(machine.ecu.apply_command(c).has_value());
  machine.run(8s);
  s = machine.ecu.status();
  std::array<SideNarrowing, 2> wind{};
  ASSERT_EQ(planning.compensate_wind(material_, 600.0, 11.0, 3.0, 0.0, wind), PredictionOutcome::kOk);
  EXPECT_TRUE(s.wind_compensated);
  EXPECT_FALSE(s.border_applied);
  for (const int d : {kLeftDisc, kRightDisc}) {
    EXPECT_EQ(s.disc_rpm_target[static_cast<std::size_t>(d)], wind[static_cast<std::size_t>(d)].rpm);
    EXPECT_EQ(s.disc_drop_point_turn_rad[static_cast<std::size_t>(d)],
              wind[static_cast<std::size_t>(d)].drop_point_turn_rad);
    EXPECT_NEAR(s.disc_rpm_actual[static_cast<std::size_t>(d)], wind[static_cast<std::size_t>(d)].rpm, 0.5);
  }
  EXPECT_TRUE(s.work_state_actual);
}

// The planning thread: a lookup never waits for the search — it answers "not yet" and queues the key,
// the worker (its own C API handle) searches, and the same key then returns the plan an inline search
// finds. Prepared keys queue behind the one asked for.
TEST_F(AutomaticModeCapi, PlannerSearchesOnItsOwnThread) {
  CapiSpreadPredictor threaded(SPREAD_FIRMWARE_TEST_TABLES, 15.0);
  SectionPlanner worker(threaded, 0.1, SectionPlanner::Threading::kWorker);
  SidePlanKey key;
  std::copy(material_.begin(), material_.end(), key.material.begin());
  key.rpm = 600.0;
  key.bout_width_m = 12.0;
  key.section_count = 8;
  key.side = kRightDisc;
  key.sections_on = 2;
  worker.prepare(key);
  EXPECT_FALSE(worker.lookup(key).has_value()) << "searched on the worker, not in the caller";
  std::optional<SidePlan> plan;
  for (int i = 0; i < 1200 && !plan; ++i) {  // up to 2 min (a sanitizer build is slow)
    std::this_thread::sleep_for(100ms);
    plan = worker.lookup(key);
  }
  ASSERT_TRUE(plan.has_value()) << "no plan after 2 min";
  ASSERT_TRUE(plan->known);

  CapiSpreadPredictor inline_predictor(SPREAD_FIRMWARE_TEST_TABLES, 15.0);
  SectionPlanner in_line(inline_predictor, 0.1, SectionPlanner::Threading::kInline);
  const std::optional<SidePlan> expected = in_line.lookup(key);
  ASSERT_TRUE(expected.has_value() && expected->known);
  EXPECT_EQ(plan->narrowing.rpm, expected->narrowing.rpm);
  EXPECT_EQ(plan->narrowing.drop_point_turn_rad, expected->narrowing.drop_point_turn_rad);
  EXPECT_EQ(plan->narrowing.flow_fraction, expected->narrowing.flow_fraction);
  EXPECT_EQ(plan->section_rate_percent, expected->section_rate_percent);
  EXPECT_GE(worker.searches(), 1);
}

TEST_F(AutomaticModeCapi, ReportsAWidthOutOfReach) {
  EcuParameters p;
  p.command_timeout = 0s;
  const RpmRange range = predictor_->rpm_range(material_);
  p.auto_rpm_min = std::max(range.min_rpm, p.auto_rpm_min);
  p.auto_rpm_max = std::min(range.max_rpm, p.auto_rpm_max);
  const double widest = std::max(first_band_width_at(p.auto_rpm_max), first_band_width_at(p.auto_rpm_min));
  const double requested_m = std::min(widest + 10.0, p.width_max_m);
  ASSERT_GT(requested_m, widest + 1.0) << "the tables reach the machine's maximum width";
  ManualClock clock;
  Ecu ecu(clock, p, predictor_.get());
  ASSERT_FALSE(ecu.apply_command(automatic(1, requested_m)).has_value());
  ecu.step(0.05);
  EXPECT_FALSE(ecu.status().width_reachable);
  EXPECT_NE(ecu.status().fault_codes & fault_bit(Fault::kWidthOutOfReach), 0u);
}

TEST_F(AutomaticModeCapi, UnknownMaterialIsRejected) {
  ManualClock clock;
  Ecu ecu(clock, EcuParameters{}, predictor_.get());
  EcuCommand c = automatic(1, 20.0);
  c.material = "no such fertiliser";
  EXPECT_EQ(ecu.apply_command(c), Fault::kUnknownMaterial);
}

}  // namespace
}  // namespace spread::firmware
