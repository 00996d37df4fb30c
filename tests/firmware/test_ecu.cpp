// ECU core without I/O: dynamics, metering, sections, validation of every bad-input class, automatic
// mode against an analytic predictor, and the fixed-rate loop on a manual clock.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <iostream>
#include <limits>

#include "libspread/control/ecu.hpp"
#include "firmware_sim/ecu/fixed_rate_loop.hpp"
#include "libspread/control/metering.hpp"
#include "libspread/control/section_planner.hpp"
#include "tests/firmware/analytic_predictor.hpp"

namespace spread::firmware {
namespace {

using namespace std::chrono_literals;
using testing::AnalyticPredictor;

EcuCommand manual_command(std::int64_t sequence) {
  EcuCommand c;
  c.sequence = sequence;
  c.mode = 0;
  c.rate_setpoint_kg_ha = 200.0;
  c.width_setpoint_m = 24.0;
  c.ground_speed_m_s = 12.0 / 3.6;
  c.rpm_setpoint = 750.0;
  c.material = "urea";
  c.section_count = 8;
  for (int i = 0; i < 8; ++i) c.section_on[static_cast<std::size_t>(i)] = true;
  c.work_state = true;
  return c;
}

// Steps the ECU for `duration` at 20 Hz on the manual clock.
void run_for(Ecu& ecu, ManualClock& clock, Nanoseconds duration) {
  for (Nanoseconds t{}; t < duration; t += 50ms) {
    clock.advance(50ms);
    ecu.step(0.05);
  }
}

bool fault_active(const Ecu& ecu, Fault fault) { return (ecu.status().fault_codes & fault_bit(fault)) != 0; }

class NullIo final : public LoopIo {
 public:
  void pump(Nanoseconds) override { ++pumps; }
  void after_step(const EcuStatus&) override { ++publishes; }
  int pumps = 0;
  int publishes = 0;
};

TEST(Metering, MassFlowFollowsRateWidthSpeed) {
  // 200 kg/ha over 24 m at 12 km/h: 200 * 24 * 12 / 36000 = 1.6 kg/s.
  EXPECT_NEAR(mass_flow_kg_s(200.0, 24.0, 12.0 / 3.6), 1.6, 1e-12);
  EXPECT_EQ(mass_flow_kg_s(200.0, 24.0, 0.0), 0.0);
  EXPECT_EQ(mass_flow_kg_s(-5.0, 24.0, 3.0), 0.0);
}

TEST(DiscSpeed, FirstOrderLagReaches63PercentAfterOneTimeConstant) {
  DiscSpeedModel disc(0.8);
  for (int i = 0; i < 16; ++i) disc.step(1000.0, 0.05);  // 16 * 50 ms = 0.8 s = tau
  EXPECT_NEAR(disc.rpm(), 1000.0 * (1.0 - std::exp(-1.0)), 1e-9);
  EXPECT_THROW(DiscSpeedModel(0.0), std::invalid_argument);
  EXPECT_THROW(DiscSpeedModel(std::nan("")), std::invalid_argument);
}

TEST(Ecu, ManualCommandMetersAndSpinsUp) {
  ManualClock clock;
  EcuParameters p;
  p.command_timeout = 0s;  // 10 s without a new command
  Ecu ecu(clock, p);
  ASSERT_FALSE(ecu.apply_command(manual_command(1)).has_value());
  for (int i = 0; i < 200; ++i) {
    clock.advance(50ms);
    ecu.step(0.05);
  }
  const EcuStatus s = ecu.status();
  EXPECT_NEAR(s.rpm_actual, 750.0, 0.01);
  EXPECT_NEAR(s.mass_flow_kg_s, 1.6, 1e-9);
  EXPECT_TRUE(s.work_state_actual);
  EXPECT_EQ(s.section_mask, 0xFF);
  EXPECT_TRUE(std::isnan(s.throw_width_m)) << "no predictor: no pattern";
}

TEST(Ecu, SectionsOffScaleTheFlow) {
  ManualClock clock;
  EcuParameters p;
  p.command_timeout = 0s;
  Ecu ecu(clock, p);
  EcuCommand c = manual_command(1);
  for (int i = 4; i < 8; ++i) c.section_on[static_cast<std::size_t>(i)] = false;
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  run_for(ecu, clock, 5s);  // the disc reaches its speed
  EXPECT_NEAR(ecu.status().mass_flow_kg_s, 0.8, 1e-9);
  EXPECT_NEAR(ecu.status().width_actual_m, 12.0, 1e-12);
  ASSERT_FALSE(ecu.set_work_state(false).has_value());
  ecu.step(0.05);
  EXPECT_EQ(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_FALSE(ecu.status().work_state_actual);
}

// Two discs, no tables to narrow a side with: a side with every section off closes its disc's flow; a
// side with only some off keeps throwing out to the bout's edge, and the actual state says so; sections
// off between sections on cannot be skipped. One disc: any section on spreads them all.
TEST(Ecu, SectionsActuallySpreadFollowTheDiscs) {
  struct Case {
    const char* what;
    int discs;
    std::uint32_t mask;
    std::uint16_t actual;
    double flow_share;  // of the whole machine's flow
  };
  for (const Case& c : {Case{"right side off", 2, 0x0F, 0x0F, 0.5}, Case{"left side off", 2, 0xF0, 0xF0, 0.5},
                        Case{"outer right off, no tables", 2, 0x3F, 0xFF, 1.0},
                        Case{"inner left off", 2, 0xF3, 0xFF, 1.0}, Case{"all on", 2, 0xFF, 0xFF, 1.0},
                        Case{"one disc, half off", 1, 0x0F, 0xFF, 1.0}}) {
    ManualClock clock;
    EcuParameters p;
    p.command_timeout = 0s;
    p.disc_count = c.discs;
    Ecu ecu(clock, p);
    EcuCommand command = manual_command(1);
    for (int i = 0; i < 8; ++i) command.section_on[static_cast<std::size_t>(i)] = ((c.mask >> i) & 1u) != 0;
    ASSERT_FALSE(ecu.apply_command(command).has_value());
    run_for(ecu, clock, 5s);
    const EcuStatus s = ecu.status();
    EXPECT_EQ(s.section_mask, c.mask) << c.what;
    EXPECT_EQ(s.section_actual_mask, c.actual) << c.what;
    EXPECT_NEAR(s.mass_flow_kg_s, 1.6 * c.flow_share, 1e-9) << c.what;
    EXPECT_NEAR(s.width_actual_m, 24.0 * std::popcount(c.actual) / 8.0, 1e-12) << c.what;
  }
}

// Every rejected command: counted under its own fault, bit shown, state unchanged.
struct BadCommandCase {
  const char* name;
  void (*spoil)(EcuCommand&);
  Fault expected;
};

class EcuBadCommand : public ::testing::TestWithParam<BadCommandCase> {};

TEST_P(EcuBadCommand, IsCountedReportedAndChangesNothing) {
  ManualClock clock;
  AnalyticPredictor predictor;
  Ecu ecu(clock, EcuParameters{}, &predictor);
  ASSERT_FALSE(ecu.apply_command(manual_command(10)).has_value());
  ecu.step(0.05);
  const EcuStatus before = ecu.status();

  EcuCommand bad = manual_command(11);
  bad.rate_setpoint_kg_ha = 999.0;  // would change state if accepted
  GetParam().spoil(bad);
  const Rejection rejection = ecu.apply_command(bad);
  ASSERT_TRUE(rejection.has_value());
  EXPECT_EQ(*rejection, GetParam().expected) << fault_name(*rejection);

  const EcuStatus after = ecu.status();
  EXPECT_EQ(after.rate_setpoint_kg_ha, before.rate_setpoint_kg_ha);
  EXPECT_EQ(after.last_command_sequence, 10);
  EXPECT_EQ(after.fault_counts[static_cast<std::size_t>(GetParam().expected)], 1u);
  EXPECT_NE(after.fault_codes & fault_bit(GetParam().expected), 0u);
  // Event faults stay visible for the hold time (2 s), then clear; the count stays.
  clock.advance(2500ms);
  ecu.step(0.05);
  EXPECT_EQ(ecu.status().fault_codes & fault_bit(GetParam().expected), 0u);
  EXPECT_EQ(ecu.status().fault_counts[static_cast<std::size_t>(GetParam().expected)], 1u);
}

INSTANTIATE_TEST_SUITE_P(
    AllClasses, EcuBadCommand,
    ::testing::Values(
        BadCommandCase{"nan_rate", [](EcuCommand& c) { c.rate_setpoint_kg_ha = std::nan(""); }, Fault::kNotANumber},
        BadCommandCase{"inf_speed", [](EcuCommand& c) { c.ground_speed_m_s = INFINITY; }, Fault::kNotANumber},
        BadCommandCase{"nan_rpm", [](EcuCommand& c) { c.rpm_setpoint = std::nan(""); }, Fault::kNotANumber},
        BadCommandCase{"negative_rate", [](EcuCommand& c) { c.rate_setpoint_kg_ha = -1.0; },
                       Fault::kSetpointOutOfRange},
        BadCommandCase{"width_too_wide", [](EcuCommand& c) { c.width_setpoint_m = 100.0; },
                       Fault::kSetpointOutOfRange},
        BadCommandCase{"rpm_too_fast", [](EcuCommand& c) { c.rpm_setpoint = 5000.0; }, Fault::kSetpointOutOfRange},
        BadCommandCase{"speed_negative", [](EcuCommand& c) { c.ground_speed_m_s = -0.1; },
                       Fault::kSetpointOutOfRange},
        BadCommandCase{"seventeen_sections", [](EcuCommand& c) { c.section_count = 17; },
                       Fault::kSetpointOutOfRange},
 BadCommandCase{"more_sections_than_installed", [](EcuCommand& c) { c.section_count = 12; },
                       Fault::kSetpointOutOfRange},
        BadCommandCase{"zero_sections", [](EcuCommand& c) { c.section_count = 0; }, Fault::kSetpointOutOfRange},
        BadCommandCase{"unknown_mode", [](EcuCommand& c) { c.mode = 7; }, Fault::kUnknownMode},
        BadCommandCase{"unknown_material", [](EcuCommand& c) { c.material = "sand"; }, Fault::kUnknownMaterial},
        BadCommandCase{"duplicate_sequence", [](EcuCommand& c) { c.sequence = 10; }, Fault::kStaleSequence},
        BadCommandCase{"older_sequence", [](EcuCommand& c) { c.sequence = 3; }, Fault::kStaleSequence},
        BadCommandCase{"automatic_without_width",
                       [](EcuCommand& c) {
                         c.mode = 1;
                         c.width_setpoint_m = 0.0;
                       },
                       Fault::kSetpointOutOfRange}),
    [](const ::testing::TestParamInfo<BadCommandCase>& param_info) { return std::string(param_info.param.name); });

TEST(Ecu, BadSingleSetValuesAreRejected) {
  ManualClock clock;
  Ecu ecu(clock, EcuParameters{});
  ASSERT_FALSE(ecu.apply_command(manual_command(1)).has_value());
  EXPECT_EQ(ecu.set_rate_setpoint(std::nan("")), Fault::kNotANumber);
  EXPECT_EQ(ecu.set_width_setpoint(-3.0), Fault::kSetpointOutOfRange);
  EXPECT_EQ(ecu.set_ground_speed(21.0, TravelDirection::kForward, 1s), Fault::kSetpointOutOfRange);
  EXPECT_EQ(ecu.set_section_mask(0x100), Fault::kSetpointOutOfRange) << "section 9 is not installed";
  EXPECT_EQ(ecu.status().rate_setpoint_kg_ha, 200.0);
  EXPECT_EQ(ecu.status().section_mask, 0xFF);
  EXPECT_EQ(ecu.faults().total(), 4u);
}

// With tables but no material known (a CAN-only machine whose product was never chosen), a command that
// needs a plan from the material's launch samples — a narrowed side, a border — is refused (fault
// unknown_material: a PDACK error and a DM1 on the bus), never accepted to do nothing. Commands that need
// no plan still go through: every section on, or a whole side off (that disc's flow closes).
TEST(Ecu, CommandsThatNeedTheMaterialAreRefusedUntilOneIsKnown) {
  ManualClock clock;
  AnalyticPredictor predictor;
  Ecu ecu(clock, EcuParameters{}, &predictor);
  ASSERT_FALSE(ecu.set_width_setpoint(12.0));
  EXPECT_EQ(ecu.set_section_mask(0x7F), Fault::kUnknownMaterial) << "section 8 off narrows the right side";
  EXPECT_EQ(ecu.set_section_mask(0xFE), Fault::kUnknownMaterial) << "section 1 off narrows the left side";
  EXPECT_EQ(ecu.set_border(1, 0.0), Fault::kUnknownMaterial);
  EXPECT_EQ(ecu.status().section_mask, 0xFF);
  EXPECT_EQ(ecu.status().border_mode, BorderMode::kOff);
  EXPECT_EQ(ecu.faults().count(Fault::kUnknownMaterial), 3u);
  EXPECT_FALSE(ecu.set_section_mask(0x0F)) << "the right side off: its disc closes, no plan needed";
  EXPECT_FALSE(ecu.set_section_mask(0xFF));
  EXPECT_FALSE(ecu.set_section_mask(0x99)) << "inner sections off between sections on: nothing narrows";
  EXPECT_FALSE(ecu.set_border(0, 0.0)) << "border off needs nothing";
  ASSERT_FALSE(ecu.set_material("urea"));
  EXPECT_FALSE(ecu.set_section_mask(0x7F));
  EXPECT_FALSE(ecu.set_border(1, 0.0));
  // Without tables no side can be narrowed at all: a mask that would narrow one is refused (not
  // acknowledged and then spread anyway); a whole side off closes its disc and needs no plan.
  Ecu no_tables(clock, EcuParameters{});
  EXPECT_EQ(no_tables.set_section_mask(0x7F), Fault::kAutomaticUnavailable);
  EXPECT_EQ(no_tables.status().section_mask, 0xFF);
  EXPECT_FALSE(no_tables.set_section_mask(0x0F));
}

TEST(Ecu, AutomaticModeNeedsTables) {
  ManualClock clock;
  Ecu ecu(clock, EcuParameters{});
  EcuCommand c = manual_command(1);
  c.mode = 1;
  EXPECT_EQ(ecu.apply_command(c), Fault::kAutomaticUnavailable);
  EXPECT_EQ(ecu.status().mode, Mode::kManual);
}

TEST(Ecu, CommandTimeoutSwitchesTheWorkStateOffAndReportsIt) {
  ManualClock clock;
  EcuParameters p;  // command timeout 2 s
  p.disc_time_constant_s = 0.1;
  Ecu ecu(clock, p);
  ASSERT_FALSE(ecu.apply_command(manual_command(1)).has_value());
  run_for(ecu, clock, 1s);
  EXPECT_GT(ecu.status().mass_flow_kg_s, 0.0);
  run_for(ecu, clock, 1500ms);
  EXPECT_EQ(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_FALSE(ecu.status().work_state_setpoint) << "the silent controller's work state is switched off";
  EXPECT_TRUE(fault_active(ecu, Fault::kCommandTimeout));
  // The sender's next command is a fresh request: its work state applies again.
  ASSERT_FALSE(ecu.apply_command(manual_command(2)).has_value());
  run_for(ecu, clock, 50ms);
  EXPECT_GT(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_FALSE(fault_active(ecu, Fault::kCommandTimeout));
  EXPECT_EQ(ecu.status().fault_counts[static_cast<std::size_t>(Fault::kCommandTimeout)], 1u);
}

// --- Safety rules: each case below spread, or kept spreading, on the ECU before these rules. ---

TEST(EcuSafety, NoMeteringWhileTheDiscStandsOrSpinsUp) {
  ManualClock clock;
  EcuParameters p;
  p.command_timeout = 0s;
  Ecu ecu(clock, p);
  EcuCommand c = manual_command(1);
  c.rpm_setpoint = 0.0;  // disc stopped, rate and speed set
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  run_for(ecu, clock, 5s);
  EXPECT_EQ(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_FALSE(ecu.status().work_state_actual);
  EXPECT_EQ(ecu.status().rate_actual_kg_ha, 0.0);
  EXPECT_TRUE(fault_active(ecu, Fault::kDiscNotAtSpeed));

  // Spin-up to 750 r/min: metering opens only once the disc is within 5 % of its target.
  c = manual_command(2);
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  double rpm_at_opening = -1.0;
  for (int i = 0; i < 200 && rpm_at_opening < 0.0; ++i) {
    run_for(ecu, clock, 50ms);
    if (ecu.status().work_state_actual) rpm_at_opening = ecu.status().rpm_actual;
    if (rpm_at_opening < 0.0) {
      EXPECT_EQ(ecu.status().mass_flow_kg_s, 0.0) << "at " << ecu.status().rpm_actual << " r/min";
    }
  }
  EXPECT_GE(rpm_at_opening, 0.95 * 750.0);
  EXPECT_FALSE(fault_active(ecu, Fault::kDiscNotAtSpeed));
  // A set-point below the spreading speed never meters, however well the disc follows it.
  c = manual_command(3);
  c.rpm_setpoint = 100.0;
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  run_for(ecu, clock, 10s);
  EXPECT_EQ(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_TRUE(fault_active(ecu, Fault::kDiscNotAtSpeed));
}

TEST(EcuSafety, ALostOrUnavailableSpeedClosesMetering) {
  ManualClock clock;
  EcuParameters p;
  p.disc_time_constant_s = 0.1;
  Ecu ecu(clock, p);
  ASSERT_TRUE(!ecu.set_rate_setpoint(250.0) && !ecu.set_width_setpoint(24.0) && !ecu.set_rpm_setpoint(750.0));
  ecu.note_task_controller_alive();
  ASSERT_FALSE(ecu.set_work_state(true).has_value());
  for (int i = 0; i < 20; ++i) {  // 1 s of speed broadcasts every 100 ms, valid 300 ms each
    ASSERT_FALSE(ecu.set_ground_speed(3.0, TravelDirection::kForward, 300ms).has_value());
    run_for(ecu, clock, 100ms);
  }
  EXPECT_GT(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_NEAR(ecu.status().ground_speed_m_s, 3.0, 1e-12);
  run_for(ecu, clock, 400ms);  // the broadcasts stop
  EXPECT_EQ(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_EQ(ecu.status().ground_speed_m_s, 0.0) << "a lost speed is not reported as the last value";
  EXPECT_TRUE(fault_active(ecu, Fault::kSpeedUnavailable));
  // Back: metering resumes by itself (the work state was never switched off).
  ASSERT_FALSE(ecu.set_ground_speed(3.0, TravelDirection::kForward, 300ms).has_value());
  run_for(ecu, clock, 50ms);
  EXPECT_GT(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_FALSE(fault_active(ecu, Fault::kSpeedUnavailable));
  // The source says "error / not available": closed at once, not after its timeout.
  ecu.set_ground_speed_unavailable();
  run_for(ecu, clock, 50ms);
  EXPECT_EQ(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_TRUE(fault_active(ecu, Fault::kSpeedUnavailable));
  // Reverse: no spreading.
  ASSERT_FALSE(ecu.set_ground_speed(2.0, TravelDirection::kReverse, 300ms).has_value());
  run_for(ecu, clock, 50ms);
  EXPECT_EQ(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_TRUE(fault_active(ecu, Fault::kDrivingReverse));
  EXPECT_FALSE(fault_active(ecu, Fault::kSpeedUnavailable));
}

TEST(EcuSafety, SpeedInputsDoNotKeepASilentTaskControllerAlive) {
  ManualClock clock;
  EcuParameters p;
  p.disc_time_constant_s = 0.1;
  Ecu ecu(clock, p);  // task controller timeout 6 s
  ASSERT_TRUE(!ecu.set_rate_setpoint(250.0) && !ecu.set_width_setpoint(24.0) && !ecu.set_rpm_setpoint(750.0));
  ecu.note_task_controller_alive();
  ASSERT_FALSE(ecu.set_work_state(true).has_value());
  // TC status at 0 and 2 s, then only the tractor's speed broadcasts.
  for (int i = 0; i < 100; ++i) {
    if (i % 20 == 0 && i <= 20) ecu.note_task_controller_alive();
    ASSERT_FALSE(ecu.set_ground_speed(3.0, TravelDirection::kForward, 300ms).has_value());
    run_for(ecu, clock, 100ms);
    if (i == 75) {
      EXPECT_GT(ecu.status().mass_flow_kg_s, 0.0) << "5.6 s after the last TC status: still alive";
    }
  }
  // 10 s: 8 s since the last status.
  EXPECT_EQ(ecu.status().mass_flow_kg_s, 0.0);
  EXPECT_FALSE(ecu.status().work_state_setpoint);
  EXPECT_TRUE(fault_active(ecu, Fault::kTaskControllerLost));
  // The TC comes back: the fault clears, but the work state stays off until it is switched on again.
  ecu.note_task_controller_alive();
  ASSERT_FALSE(ecu.set_ground_speed(3.0, TravelDirection::kForward, 300ms).has_value());
  run_for(ecu, clock, 50ms);
  EXPECT_FALSE(fault_active(ecu, Fault::kTaskControllerLost));
  EXPECT_EQ(ecu.status().mass_flow_kg_s, 0.0);
  ASSERT_FALSE(ecu.set_work_state(true).has_value());
  run_for(ecu, clock, 50ms);
  EXPECT_GT(ecu.status().mass_flow_kg_s, 0.0);
}

TEST(EcuSafety, RepeatedCommandsDoNotUndoATaskControllersSwitchOff) {
  ManualClock clock;
  EcuParameters p;
  p.command_timeout = 0s;
  p.disc_time_constant_s = 0.1;
  Ecu ecu(clock, p);
  ASSERT_FALSE(ecu.apply_command(manual_command(1)).has_value());
  run_for(ecu, clock, 1s);
  EXPECT_TRUE(ecu.status().work_state_actual);
  ecu.note_task_controller_alive();
  ASSERT_FALSE(ecu.set_work_state(false).has_value());  // DDI 289 = 0
  for (int i = 2; i < 12; ++i) {
    ASSERT_FALSE(ecu.apply_command(manual_command(i)).has_value());
    run_for(ecu, clock, 100ms);
  }
  EXPECT_FALSE(ecu.status().work_state_setpoint);
  EXPECT_FALSE(ecu.status().work_state_actual);
  // The LCM operator switches off and on again: that change is applied.
  EcuCommand off = manual_command(12);
  off.work_state = false;
  ASSERT_FALSE(ecu.apply_command(off).has_value());
  ASSERT_FALSE(ecu.apply_command(manual_command(13)).has_value());
  run_for(ecu, clock, 50ms);
  EXPECT_TRUE(ecu.status().work_state_actual);
}

TEST(EcuSafety, OneSequenceNumberFarAheadCannotStallTheRealSender) {
  ManualClock clock;
  EcuParameters p;
  p.command_timeout = 0s;
  Ecu ecu(clock, p);
  ASSERT_FALSE(ecu.apply_command(manual_command(100)).has_value());
  EcuCommand rogue = manual_command(1000);
  rogue.rate_setpoint_kg_ha = 999.0;
  EXPECT_EQ(ecu.apply_command(rogue), Fault::kSequenceJump);
  EXPECT_EQ(ecu.status().rate_setpoint_kg_ha, 200.0);
  for (int i = 101; i < 110; ++i) EXPECT_FALSE(ecu.apply_command(manual_command(i)).has_value()) << i;
  EXPECT_EQ(ecu.status().last_command_sequence, 109);
  EXPECT_EQ(ecu.faults().count(Fault::kStaleSequence), 0u);
  // A sender that really jumped (or restarted at 0) continues from its new number: believed on the second.
  EXPECT_EQ(ecu.apply_command(manual_command(5000)), Fault::kSequenceJump);
  EXPECT_FALSE(ecu.apply_command(manual_command(5001)).has_value());
  EXPECT_EQ(ecu.apply_command(manual_command(0)), Fault::kSequenceJump);
  EXPECT_FALSE(ecu.apply_command(manual_command(1)).has_value());
  EXPECT_EQ(ecu.status().last_command_sequence, 1);
  // Extreme values do not overflow the distance arithmetic.
  EXPECT_EQ(ecu.apply_command(manual_command(std::numeric_limits<std::int64_t>::max())), Fault::kSequenceJump);
  EXPECT_EQ(ecu.apply_command(manual_command(std::numeric_limits<std::int64_t>::min())), Fault::kSequenceJump);
}

TEST(EcuSafety, NoBusAddressNoMetering) {
  ManualClock clock;
  EcuParameters p;
  p.command_timeout = 0s;
  p.disc_time_constant_s = 0.1;
  Ecu ecu(clock, p);
  ASSERT_FALSE(ecu.apply_command(manual_command(1)).has_value());
  run_for(ecu, clock, 1s);
  ASSERT_TRUE(ecu.status().work_state_actual);
  ecu.set_bus_address(false);  // another node won the address claim
  run_for(ecu, clock, 50ms);
  EXPECT_FALSE(ecu.status().work_state_actual);
  EXPECT_FALSE(ecu.status().work_state_setpoint) << "losing the address switches the work state off";
  EXPECT_TRUE(fault_active(ecu, Fault::kNoBusAddress));
  ecu.set_bus_address(true);
  run_for(ecu, clock, 50ms);
  EXPECT_FALSE(fault_active(ecu, Fault::kNoBusAddress));
  EXPECT_FALSE(ecu.status().work_state_actual) << "back on the bus, off until switched on again";
}

TEST(EcuSafety, ZeroWidthIsNotSpreading) {
  ManualClock clock;
  EcuParameters p;
  p.command_timeout = 0s;
  Ecu ecu(clock, p);
  EcuCommand c = manual_command(1);
  c.width_setpoint_m = 0.0;
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  run_for(ecu, clock, 5s);
  EXPECT_FALSE(ecu.status().work_state_actual);
  EXPECT_EQ(ecu.status().rate_actual_kg_ha, 0.0);
}

TEST(Ecu, AutomaticModeReachesRequestedWidth) {
  ManualClock clock;
  AnalyticPredictor predictor;
  EcuParameters p;
  p.command_timeout = 0s;
  Ecu ecu(clock, p, &predictor);
  EcuCommand c = manual_command(1);
  c.mode = 1;
  c.width_setpoint_m = 18.0;
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  for (int i = 0; i < 200; ++i) {  // 10 s at 20 Hz, > 10 time constants
    clock.advance(50ms);
    ecu.step(0.05);
  }
  const EcuStatus s = ecu.status();
  // The solver aims at the set-point plus its margin (0.5 m): the settled pattern reaches the set-point.
  const double margin_rpm = AnalyticPredictor::urea_rpm_for_effective_width(18.5);
  EXPECT_NEAR(s.rpm_target, margin_rpm, 1.0);
  EXPECT_NEAR(s.rpm_actual, margin_rpm, 1.0);
  EXPECT_GE(s.effective_width_m, 18.0);
  EXPECT_NEAR(s.effective_width_m, 18.5, 0.1);
  EXPECT_GE(s.rpm_target, margin_rpm) << "the solver picks the slowest speed known to reach the width";
  EXPECT_TRUE(s.width_reachable);
  EXPECT_EQ(s.fault_codes, 0u);
}

TEST(Ecu, AutomaticModeReportsWidthOutOfReach) {
  ManualClock clock;
  AnalyticPredictor predictor;
  EcuParameters p;
  p.command_timeout = 0s;
  Ecu ecu(clock, p, &predictor);
  EcuCommand c = manual_command(1);
  c.mode = 1;
  c.width_setpoint_m = 40.0;  // E(1100 r/min) = 32.7 m
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  ecu.step(0.05);
  EcuStatus s = ecu.status();
  EXPECT_FALSE(s.width_reachable);
  EXPECT_NEAR(s.rpm_target, 1100.0, 1e-9) << "out of reach: the widest speed in range";
  EXPECT_NE(s.fault_codes & fault_bit(Fault::kWidthOutOfReach), 0u);
  // Back within reach: the state fault clears at once.
  ASSERT_FALSE(ecu.set_width_setpoint(24.0).has_value());
  ecu.step(0.05);
  s = ecu.status();
  EXPECT_TRUE(s.width_reachable);
  EXPECT_EQ(s.fault_codes & fault_bit(Fault::kWidthOutOfReach), 0u);
  // Too narrow: E(300 r/min) = 2.4 m.
  ASSERT_FALSE(ecu.set_width_setpoint(1.0).has_value());
  ecu.step(0.05);
  EXPECT_FALSE(ecu.status().width_reachable);
  EXPECT_NEAR(ecu.status().rpm_target, 300.0, 1e-9);
}

TEST(Ecu, AutomaticModeRefusesManualRpm) {
  ManualClock clock;
  AnalyticPredictor predictor;
  Ecu ecu(clock, EcuParameters{}, &predictor);
  EcuCommand c = manual_command(1);
  c.mode = 1;
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  EXPECT_EQ(ecu.set_rpm_setpoint(500.0), Fault::kCanNotSettable);
}

// A predictor that narrows a side as the C API's border search would answer it, with known numbers: the
// side's disc at 3/4 of the field's speed (a narrowing or a border throws shorter), its drop point turned
// and 60 % of the flow; strips inside the edge line spread, the others not.
class NarrowingPredictor final : public SpreadPredictor {
 public:
  std::size_t material_count() const override { return analytic.material_count(); }
  std::string_view material_name(std::size_t index) const override { return analytic.material_name(index); }
  bool has_material(std::string_view material) const override { return analytic.has_material(material); }
  double cv_target_percent() const override { return analytic.cv_target_percent(); }
  RpmRange rpm_range(std::string_view material) const override { return analytic.rpm_range(material); }
  PredictionOutcome predict(std::string_view material, double rpm, double bout_width_m,
                            SpreadPrediction& out) override {
    return analytic.predict(material, rpm, bout_width_m, out);
  }
  PredictionOutcome narrow_side(const NarrowingRequest& request, std::span<const SideStrip> strips,
                                std::span<double> strip_rate_percent, SideNarrowing& out) override {
    out = SideNarrowing{};
    out.rpm = 0.75 * request.rpm;
    out.drop_point_turn_rad = 0.1;
    out.flow_fraction = 0.6;
    out.meets = true;
    for (std::size_t j = 0; j < strips.size(); ++j) {
      strip_rate_percent[j] = strips[j].to_m <= request.edge_line_m + 1e-9 ? 100.0 : 0.0;
    }
    return PredictionOutcome::kOk;
  }
  AnalyticPredictor analytic;
};

// Travel [m] while each disc is closed although its side still has sections on, over `duration`.
struct Unspread {
  std::array<double, 2> metres{};
  bool disc_not_at_speed = false;
};
Unspread run_and_count_unspread(Ecu& ecu, ManualClock& clock, Nanoseconds duration, double speed_m_s) {
  Unspread u;
  for (Nanoseconds t{}; t < duration; t += 50ms) {
    clock.advance(50ms);
    ecu.step(0.05);
    const EcuStatus s = ecu.status();
    for (std::size_t d = 0; d < 2; ++d) {
      const std::uint16_t side_bits = d == kLeftDisc ? 0x0F : 0xF0;  // 8 sections: 1-4 left, 5-8 right
      if ((s.section_mask & side_bits) != 0 && !(s.disc_flow_fraction[d] > 0.0)) u.metres[d] += speed_m_s * 0.05;
    }
    u.disc_not_at_speed = u.disc_not_at_speed || (s.fault_codes & fault_bit(Fault::kDiscNotAtSpeed)) != 0;
  }
  return u;
}

// The narrowed side moves from right to left (the TC switches sections 7-8 on and 1-2 off), then a border
// is engaged on the left and left again, at 3 m/s on 12 m bouts at 600 r/min. Each disc changes speed by a
// quarter (600 <-> 450 r/min, 1.3-1.5 s with the drive's 0.8 s lag): a disc that stays in use keeps
// spreading through it, except one slowing down to a border, which must throw nothing beyond it.
TEST(Ecu, ADiscThatStaysInUseKeepsSpreadingThroughASideChange) {
  ManualClock clock;
  EcuParameters p;
  p.command_timeout = 0s;
  NarrowingPredictor predictor;
  SectionPlanner planner(predictor, p.section_max_beyond_percent, SectionPlanner::Threading::kInline);
  Ecu ecu(clock, p, &predictor, &planner);
  constexpr double kSpeed = 3.0;
  EcuCommand c = manual_command(1);
  c.width_setpoint_m = 12.0;
  c.rpm_setpoint = 600.0;
  c.ground_speed_m_s = kSpeed;
  c.section_on = {};
  for (int i = 0; i < 6; ++i) c.section_on[static_cast<std::size_t>(i)] = true;  // 11111100: right narrowed
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  run_for(ecu, clock, 8s);
  EcuStatus s = ecu.status();
  ASSERT_EQ(s.disc_rpm_target[kRightDisc], 450.0);
  ASSERT_EQ(s.disc_rpm_target[kLeftDisc], 600.0);
  ASSERT_GT(s.disc_flow_fraction[kLeftDisc], 0.0);
  ASSERT_GT(s.disc_flow_fraction[kRightDisc], 0.0);

  c.sequence = 2;
  c.section_on = {};
  for (int i = 2; i < 8; ++i) c.section_on[static_cast<std::size_t>(i)] = true;  // 00111111: left narrowed
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  const Unspread side_change = run_and_count_unspread(ecu, clock, 4s, kSpeed);
  s = ecu.status();
  EXPECT_EQ(s.disc_rpm_target[kLeftDisc], 450.0);
  EXPECT_EQ(s.disc_rpm_target[kRightDisc], 600.0);
  std::cout << "side change right -> left at 3 m/s: unspread " << side_change.metres[kLeftDisc] << " m behind the left disc, "
            << side_change.metres[kRightDisc] << " m behind the right disc\n";
  EXPECT_EQ(side_change.metres[kLeftDisc], 0.0);
  EXPECT_EQ(side_change.metres[kRightDisc], 0.0);
  EXPECT_FALSE(side_change.disc_not_at_speed);
  // Each disc meters its share of the field's flow: the narrowed left 60 %, the right all of it.
  EXPECT_NEAR(s.mass_flow_kg_s, mass_flow_kg_s(200.0, 12.0 * (1.0 + 0.6) / 2.0, kSpeed), 1e-9);

  // Every section on, then a border on the left: the left disc slows to the border's speed and stays
  // closed until it is there (nothing over the border); the right disc spreads on.
  c.sequence = 3;
  c.section_on = {};
  for (int i = 0; i < 8; ++i) c.section_on[static_cast<std::size_t>(i)] = true;
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  const Unspread widen = run_and_count_unspread(ecu, clock, 4s, kSpeed);
  std::cout << "narrowing ended (left 450 -> 600 r/min): unspread " << widen.metres[kLeftDisc] << " m left, "
            << widen.metres[kRightDisc] << " m right\n";
  EXPECT_EQ(widen.metres[kLeftDisc], 0.0);
  EXPECT_EQ(widen.metres[kRightDisc], 0.0);
  c.sequence = 4;
  c.border_mode = static_cast<std::int32_t>(BorderMode::kLeftBorder);
  c.border_gap_m = 1.0;
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  bool left_metered_above_border_speed = false;
  Unspread border{};
  for (int k = 0; k < 80; ++k) {
    const Unspread step = run_and_count_unspread(ecu, clock, 50ms, kSpeed);
    border.metres[0] += step.metres[0];
    border.metres[1] += step.metres[1];
    s = ecu.status();
    if (s.disc_flow_fraction[kLeftDisc] > 0.0 && s.disc_rpm_actual[kLeftDisc] > 450.0 * (1.0 + p.disc_speed_tolerance)) {
      left_metered_above_border_speed = true;
    }
  }
  std::cout << "left border engaged: unspread " << border.metres[kLeftDisc] << " m left (closed while above the border's speed), "
            << border.metres[kRightDisc] << " m right\n";
  EXPECT_TRUE(s.border_applied);
  EXPECT_FALSE(left_metered_above_border_speed) << "thrown over the border while slowing down to its speed";
  EXPECT_GT(border.metres[kLeftDisc], 0.0);
  EXPECT_EQ(border.metres[kRightDisc], 0.0);
  // Leaving the border: the left disc comes back up to the field's speed and spreads on meanwhile.
  c.sequence = 5;
  c.border_mode = static_cast<std::int32_t>(BorderMode::kOff);
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  const Unspread leave = run_and_count_unspread(ecu, clock, 4s, kSpeed);
  EXPECT_EQ(leave.metres[kLeftDisc], 0.0);
  EXPECT_EQ(leave.metres[kRightDisc], 0.0);

  // A disc that was not metering still waits for its speed: the work state off and on again from rest.
  c.sequence = 6;
  c.work_state = false;
  c.rpm_setpoint = 0.0;
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  run_for(ecu, clock, 10s);
  c.sequence = 7;
  c.work_state = true;
  c.rpm_setpoint = 600.0;
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  run_for(ecu, clock, 1s);
  s = ecu.status();
  EXPECT_EQ(s.mass_flow_kg_s, 0.0) << "metering from a disc still spinning up";
}

TEST(Ecu, PredictionFailureIsCountedAndFallsBackToTheCurve) {
  ManualClock clock;
  AnalyticPredictor predictor;
  Ecu ecu(clock, EcuParameters{}, &predictor);
  EcuCommand c = manual_command(1);
  c.mode = 1;
  ASSERT_FALSE(ecu.apply_command(c).has_value());
  ecu.step(0.05);
  predictor.fail_next = true;  // every refinement prediction fails from now on
  ASSERT_FALSE(ecu.set_width_setpoint(20.0).has_value());
  ecu.step(0.05);
  EXPECT_GE(ecu.faults().count(Fault::kPredictionFailed), 1u);
  // The curve sample that reaches 20 m + margin is used: within one curve step (5 r/min) above the exact speed.
  const double exact_rpm = AnalyticPredictor::urea_rpm_for_effective_width(20.5);
  EXPECT_GE(ecu.status().rpm_target, exact_rpm);
  EXPECT_LE(ecu.status().rpm_target, exact_rpm + 5.0);
}

TEST(RpmForWidthSolver, CostIsBoundedPerSolve) {
  AnalyticPredictor predictor;
  const WidthCurve curve = sample_width_curve(predictor, "urea", {300.0, 1100.0}, 5.0);
  EXPECT_EQ(curve.rpm.size(), 161u);
  RpmForWidthSolver solver;
  const RpmSolution s = solver.solve(predictor, curve, 18.0);
  EXPECT_TRUE(s.reachable);
  EXPECT_LE(s.predictions, solver.settings().max_bisections);
  EXPECT_NEAR(s.rpm, AnalyticPredictor::urea_rpm_for_effective_width(18.0), 5.0 / 8.0);
  // A noisy, non-monotonic curve: the first sample reaching the set-point wins.
  WidthCurve noisy{"urea", {400, 450, 500, 550, 600}, {3.0, 5.0, 2.5, 6.0, 4.0}};
  RpmSolverSettings no_refinement;
  no_refinement.max_bisections = 0;
  EXPECT_EQ(RpmForWidthSolver(no_refinement).solve(predictor, noisy, 5.5).rpm, 550.0);
  EXPECT_EQ(RpmForWidthSolver(no_refinement).solve(predictor, noisy, 4.5).rpm, 450.0);
  EXPECT_FALSE(RpmForWidthSolver(no_refinement).solve(predictor, noisy, 8.0).reachable);
  EXPECT_EQ(RpmForWidthSolver(no_refinement).solve(predictor, noisy, 8.0).rpm, 550.0);
}

TEST(FixedRateLoop, TwentyHertzOnManualClockIsDeterministic) {
  auto run = [] {
    ManualClock clock;
    AnalyticPredictor predictor;
    Ecu ecu(clock, EcuParameters{}, &predictor);
    FixedRateLoop loop(clock, 20.0);
    NullIo io;
    EXPECT_FALSE(ecu.apply_command(manual_command(1)).has_value());
    loop.run(ecu, io, 1s);
    EXPECT_EQ(loop.statistics().ticks, 20);
    EXPECT_EQ(io.publishes, 20);
    EXPECT_EQ(loop.statistics().overruns, 0);
    EXPECT_EQ(clock.now(), Nanoseconds(1s));
    return ecu.status();
  };
  const EcuStatus a = run();
  const EcuStatus b = run();
  EXPECT_EQ(a.rpm_actual, b.rpm_actual);  // bit-identical
  EXPECT_EQ(a.throw_width_m, b.throw_width_m);
  EXPECT_NEAR(a.rpm_actual, 750.0 * (1.0 - std::exp(-1.0 / 0.8)), 1e-6);
}

TEST(FixedRateLoop, OverrunIsCountedAsFault) {
  ManualClock clock;
  Ecu ecu(clock, EcuParameters{});
  FixedRateLoop loop(clock, 20.0);
  class SlowIo final : public LoopIo {
   public:
    explicit SlowIo(ManualClock& c) : clock(c) {}
    void pump(Nanoseconds) override {}
    void after_step(const EcuStatus&) override { clock.advance(70ms); }  // longer than 50 ms
    ManualClock& clock;
  } io(clock);
  loop.tick(ecu, io);
  EXPECT_EQ(loop.statistics().overruns, 1);
  EXPECT_EQ(ecu.faults().count(Fault::kLoopOverrun), 1u);
  EXPECT_THROW(FixedRateLoop(clock, 0.0), std::invalid_argument);
  EXPECT_THROW(loop.run(ecu, io, std::nullopt, nullptr), std::invalid_argument);
}

TEST(EcuParameters, BadParametersNameTheField) {
  EcuParameters p;
  p.section_count = 20;
  try {
    validate(p);
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("section_count"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace spread::firmware
