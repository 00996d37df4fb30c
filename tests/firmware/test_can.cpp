// The ECU over the virtual CAN bus: end-to-end process data and speed, every bad-frame class, and the replay of
// candump logs against recorded answers. (The codecs and candump logs on their own are tests/isobus.)
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <fstream>
#include <sstream>

#include "firmware_sim/can/can_ecu_link.hpp"
#include "isobus/can/candump_log.hpp"
#include "isobus/can/virtual_can_bus.hpp"
#include "isobus/ddi.hpp"
#include "isobus/ddop.hpp"
#include "isobus/dm1.hpp"
#include "isobus/frame_description.hpp"
#include "isobus/iso_name.hpp"
#include "isobus/isobus_id.hpp"
#include "isobus/process_data.hpp"
#include "isobus/speed_messages.hpp"
#include "isobus/tc_messages.hpp"
#include "isobus/tc_partner.hpp"
#include "isobus/transport_protocol.hpp"

namespace spread::firmware::can {
namespace {

using namespace isobus;
using namespace isobus::can;

using namespace std::chrono_literals;

constexpr std::uint8_t kEcu = 0x80;
constexpr std::uint8_t kTractor = 0x81;

// The ECU on one end of the virtual bus, the test as the tractor / task controller on the other.
class VirtualBus : public ::testing::Test {
 protected:
  VirtualBus()
      : pair_(make_virtual_can_pair()),
        ecu_(clock_, parameters(), nullptr),
        ecu_io_(pair_.first, ecu_, clock_, CanEcuSettings{}),
        loop_(clock_, 20.0) {}

  static EcuParameters parameters() {
    EcuParameters p;
    p.command_timeout = 0s;
    return p;
  }

  // The test is the ECU's partner task controller: its address claimed with a TC's NAME (ISO 11783-5),
  // then its status (ISO 11783-10). Processed with the first tick, before what a test sends.
  void SetUp() override {
    claim_address(kTractor, task_controller_name());
    send_tc_status();
  }

  static std::uint64_t task_controller_name(std::uint32_t identity = 0x81) {
    isobus::IsoName n;
    n.self_configurable = true;
    n.device_class = isobus::kDeviceClassNonSpecific;
    n.function = isobus::kFunctionTaskController;
    n.identity_number = identity;
    return isobus::encode_name(n);
  }

  void claim_address(std::uint8_t source, std::uint64_t name) {
    const auto bytes = isobus::name_to_bytes(name);
    ASSERT_TRUE(tractor().send(
        make_frame(encode_id({6, isobus::kAddressClaimedPgn, kGlobalAddress, source}), bytes.data(), 8)));
  }

  void send_pd(ProcessDataCommand command, std::uint16_t ddi, std::int32_t value, std::uint16_t element = 0,
               std::uint8_t destination = kEcu) {
    const ProcessDataBytes b = encode_process_data({static_cast<std::uint8_t>(command), element, ddi, value});
    ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kProcessDataPgn, destination, kTractor}), b.data(), 8)));
  }

  // A live tractor and task controller from now on: every loop tick of run() is preceded by a ground-based
  // speed every 100 ms (ISO 11783-7) and the TC status every 2 s (ISO 11783-10).
  void go_live(double speed_m_s = 12.0 / 3.6) { live_speed_m_s_ = speed_m_s; }
  void stop_speed() { live_speed_m_s_ = -1.0; }
  void stop_tc_status() { live_tc_status_ = false; }

  // Rate 250 kg/ha, 24 m, manual disc speed, all sections, work state on: a spreader asked to spread.
  void set_spreading(std::int32_t rpm_raw = 7500000) {
    send_pd(ProcessDataCommand::kValue, 6, 25000);
    send_pd(ProcessDataCommand::kValue, 66, 24000);
    send_pd(ProcessDataCommand::kValue, 389, rpm_raw);
    send_pd(ProcessDataCommand::kValue, 290, 0x5555);
    send_pd(ProcessDataCommand::kValue, 289, 1);
  }

  std::int32_t request(std::uint16_t ddi) {
    send_pd(ProcessDataCommand::kRequestValue, ddi, 0);
    return single_answer(ddi).value;
  }

  bool fault_active(Fault fault) { return (ecu_.status().fault_codes & fault_bit(fault)) != 0; }

  void send_speed(std::uint32_t pgn, double speed_m_s, Direction direction) {
    const auto bytes = encode_speed(speed_m_s, 0, direction);
    ASSERT_TRUE(tractor().send(make_frame(encode_id({3, pgn, kGlobalAddress, 0xF0}), bytes.data(), 8)));
  }

  void send_tc_status() {
    // Process data command 0xE (TC status) to the global address.
    const auto status = isobus::encode_tc_status(true);
    ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kProcessDataPgn, kGlobalAddress, kTractor}), status.data(), 8)));
  }

  // Runs loop ticks, then returns every frame the ECU sent.
  std::vector<can_frame> run(int ticks) {
    for (int i = 0; i < ticks; ++i) {
      if (live_speed_m_s_) {
        if (live_ticks_ % 2 == 0 && *live_speed_m_s_ >= 0.0) {
          send_speed(kGroundBasedSpeedPgn, *live_speed_m_s_, Direction::kForward);
        }
        if (live_ticks_ % 40 == 0 && live_tc_status_) send_tc_status();
        ++live_ticks_;
      }
      loop_.tick(ecu_, ecu_io_);
    }
    std::vector<can_frame> out;
    can_frame f{};
    while (tractor().read(f) == ReadOutcome::kFrame) {
      // The ECU's task-controller client answers the TC status with its connection handshake (this
      // fixture's TC never answers it): kept apart from the answers the tests look at.
      const IsobusId id = decode_id(f.can_id & CAN_EFF_MASK);
      const bool handshake = id.pgn == isobus::kWorkingSetMasterPgn ||
                             (id.pgn == kProcessDataPgn && isobus::tc_message_kind({f.data, 8}).has_value());
      if (id.pgn == isobus::kDm1Pgn) {
        dm1_frames_.push_back(f);  // the once-a-second diagnostics, looked at by their own test
      } else {
        (handshake ? connection_frames_ : out).push_back(f);
      }
    }
    return out;
  }

  ProcessData single_answer(std::uint16_t expected_ddi) {
    const auto frames = run(1);
    EXPECT_EQ(frames.size(), 1u);
    if (frames.empty()) return {};
    const IsobusId id = decode_id(frames[0].can_id & CAN_EFF_MASK);
    EXPECT_EQ(id.pgn, kProcessDataPgn);
    EXPECT_EQ(id.source, kEcu);
    EXPECT_EQ(id.destination, kTractor);
    ProcessDataBytes b{};
    std::copy(frames[0].data, frames[0].data + 8, b.begin());
    const ProcessData m = decode_process_data(b);
    EXPECT_EQ(m.ddi, expected_ddi);
    return m;
  }

  std::uint8_t pdack_errors(std::uint16_t expected_ddi) {
    const auto frames = run(1);
    EXPECT_EQ(frames.size(), 1u);
    if (frames.empty()) return 0xFF;
    ProcessDataBytes b{};
    std::copy(frames[0].data, frames[0].data + 8, b.begin());
    const auto ack = decode_pdack(b);
    EXPECT_TRUE(ack.has_value()) << describe_frame(frames[0]);
    if (!ack) return 0xFF;
    EXPECT_EQ(ack->ddi, expected_ddi);
    return ack->error_bits;
  }

  CanFramePort& tractor() { return pair_.second; }

  std::vector<can_frame> connection_frames_;  // the ECU's TC-client handshake frames
  std::vector<can_frame> dm1_frames_;         // DM1 single frames
  std::optional<double> live_speed_m_s_;  // < 0: the tractor's speed broadcasts have stopped
  bool live_tc_status_ = true;
  int live_ticks_ = 0;
  ManualClock clock_;
  std::pair<CanFramePort, CanFramePort> pair_;
  Ecu ecu_;
  CanPortIo ecu_io_;
  FixedRateLoop loop_;
};

TEST_F(VirtualBus, SetValuesRequestsAndSpeedEndToEnd) {
  send_pd(ProcessDataCommand::kSetValueAndAcknowledge, 6, 20000);  // 200 kg/ha
  EXPECT_EQ(pdack_errors(6), kPdackNoError);
  send_pd(ProcessDataCommand::kValue, 66, 24000);  // 24 m, no acknowledge expected
  send_pd(ProcessDataCommand::kValue, 389, 7500000);  // 750 r/min
  send_pd(ProcessDataCommand::kValue, 289, 1);  // work state on
  send_pd(ProcessDataCommand::kValue, 290, 0x5555);  // sections 1-8 on
  go_live();
  EXPECT_TRUE(run(1).empty()) << "set-values without acknowledge are answered only on error";

  // Wheel-based speed is ignored while the ground-based one is fresh.
  send_speed(kWheelBasedSpeedPgn, 5.0, Direction::kForward);
  EXPECT_TRUE(run(200).empty());  // 10 s: the disc settles (tau 0.8 s)

  send_pd(ProcessDataCommand::kRequestValue, 6, 0);
  EXPECT_EQ(single_answer(6).value, 20000);
  send_pd(ProcessDataCommand::kRequestValue, 390, 0);
  EXPECT_NEAR(single_answer(390).value, 7500000, 100);
  send_pd(ProcessDataCommand::kRequestValue, 397, 0);
  EXPECT_EQ(single_answer(397).value, 3333);
  send_pd(ProcessDataCommand::kRequestValue, 141, 0);
  EXPECT_EQ(single_answer(141).value, 1);
  send_pd(ProcessDataCommand::kRequestValue, 161, 0);
  EXPECT_EQ(static_cast<std::uint32_t>(single_answer(161).value), 0xFFFF5555u) << "sections 9-16 not installed";
  send_pd(ProcessDataCommand::kRequestValue, 7, 0);
  EXPECT_EQ(single_answer(7).value, 20000);

  send_pd(ProcessDataCommand::kRequestValue, 70, 0);
  EXPECT_EQ(single_answer(70).value, 54000);
  EXPECT_NEAR(ecu_.status().mass_flow_kg_s, 200.0 * 24.0 * 12.0 / 36000.0, 1e-3);

  // Close sections 7 and 8 (state 00), leave the rest (11 = unchanged). Without tables the right disc
  // cannot be narrowed: the command is refused (not acknowledged and then spread anyway), the sections
  // stay as they were.
  send_pd(ProcessDataCommand::kSetValueAndAcknowledge, 290, static_cast<std::int32_t>(0xFFFF0FFFu));
  EXPECT_EQ(pdack_errors(290), kPdackValueOutOfRange);
  run(1);
  send_pd(ProcessDataCommand::kRequestValue, 290, 0);
  EXPECT_EQ(static_cast<std::uint32_t>(single_answer(290).value), 0xFFFF5555u);
  send_pd(ProcessDataCommand::kRequestValue, 161, 0);
  EXPECT_EQ(static_cast<std::uint32_t>(single_answer(161).value), 0xFFFF5555u);
  send_pd(ProcessDataCommand::kRequestValue, 67, 0);
  EXPECT_EQ(single_answer(67).value, 24000);
  // Sections 5-8 off: the right disc's flow closes, half the machine spreads.
  send_pd(ProcessDataCommand::kSetValueAndAcknowledge, 290, static_cast<std::int32_t>(0xFFFF00FFu));
  EXPECT_EQ(pdack_errors(290), kPdackNoError);
  EXPECT_TRUE(run(1).empty());
  send_pd(ProcessDataCommand::kRequestValue, 161, 0);
  EXPECT_EQ(static_cast<std::uint32_t>(single_answer(161).value), 0xFFFF0055u);
  send_pd(ProcessDataCommand::kRequestValue, 67, 0);
  EXPECT_EQ(single_answer(67).value, 12000);
  EXPECT_NEAR(ecu_.status().mass_flow_kg_s, 0.5 * 200.0 * 24.0 * 12.0 / 36000.0, 1e-3);
  // The faults: metering waited while the disc spun up, and the narrowing refused.
  EXPECT_EQ(ecu_.faults().count(Fault::kDiscNotAtSpeed), 1u);
  EXPECT_EQ(ecu_.faults().count(Fault::kAutomaticUnavailable), 1u);
  EXPECT_EQ(ecu_.faults().total(), 2u);
}

// Border spreading and wind compensation over ISOBUS: the manufacturer-proprietary DDIs of ddi.hpp are
// set by the TC and read back; a value out of their range, or wind compensation on an ECU without its
// tables, is refused with PDACK "outside the operational range" and changes nothing.
TEST_F(VirtualBus, BorderAndWindModesAreSetThroughProprietaryDdis) {
  send_pd(ProcessDataCommand::kSetValueAndAcknowledge, 57344, 2);  // right border
  EXPECT_EQ(pdack_errors(57344), kPdackNoError);
  send_pd(ProcessDataCommand::kSetValueAndAcknowledge, 57345, 3000);  // 3 m inside the bout's edge
  EXPECT_EQ(pdack_errors(57345), kPdackNoError);
  send_pd(ProcessDataCommand::kSetValueAndAcknowledge, 57347, -2500);  // wind from the right, 2.5 m/s
  EXPECT_EQ(pdack_errors(57347), kPdackNoError);
  send_pd(ProcessDataCommand::kSetValueAndAcknowledge, 57348, 400);
  EXPECT_EQ(pdack_errors(57348), kPdackNoError);
  EXPECT_EQ(request(57344), 2);
  EXPECT_EQ(request(57345), 3000);
  EXPECT_EQ(request(57347), -2500);
  EXPECT_EQ(request(57348), 400);
  EXPECT_EQ(ecu_.status().border_mode, BorderMode::kRightBorder);
  EXPECT_DOUBLE_EQ(ecu_.status().border_gap_m, 3.0);
  EXPECT_DOUBLE_EQ(ecu_.status().wind_x_m_s, -2.5);

  send_pd(ProcessDataCommand::kSetValueAndAcknowledge, 57344, 5);  // no such mode
  EXPECT_EQ(pdack_errors(57344), kPdackValueOutOfRange);
  send_pd(ProcessDataCommand::kSetValueAndAcknowledge, 57346, 1);  // no tables here to compensate with
  EXPECT_EQ(pdack_errors(57346), kPdackValueOutOfRange);
  send_pd(ProcessDataCommand::kSetValueAndAcknowledge, 57347, 31000);  // beyond the 30 m/s accepted
  EXPECT_EQ(pdack_errors(57347), kPdackValueOutOfRange);
  EXPECT_EQ(request(57344), 2);
  EXPECT_EQ(request(57346), 0);
  EXPECT_EQ(request(57347), -2500);
}

// --- Fail-safe rules over the bus: each of these spread, or kept spreading, before the rules. ---

TEST_F(VirtualBus, DiscAtZeroRpmNeverMeters) {
  set_spreading(0);  // DDI 389 = 0 r/min with a rate and the work state on
  go_live();
  run(100);
  EXPECT_EQ(request(141), 0) << "actual work state";
  EXPECT_EQ(request(7), 0) << "actual rate";
  EXPECT_EQ(ecu_.status().mass_flow_kg_s, 0.0);
  EXPECT_TRUE(fault_active(Fault::kDiscNotAtSpeed));
}

TEST_F(VirtualBus, SpeedBroadcastsThatStopCloseMetering) {
  set_spreading();
  go_live(3.0);
  run(100);  // 5 s: spreading
  ASSERT_EQ(request(141), 1);
  stop_speed();
  run(172);  // the speed frames stopped 8.6 s ago
  EXPECT_EQ(request(397), 0) << "no stale 3 m/s";
  EXPECT_EQ(request(7), 0);
  EXPECT_EQ(request(141), 0);
  EXPECT_TRUE(fault_active(Fault::kSpeedUnavailable));
}

TEST_F(VirtualBus, ErrorAndNotAvailableSpeedsCloseMeteringAtOnce) {
  set_spreading();
  go_live(3.0);
  run(100);
  ASSERT_EQ(request(141), 1);
  stop_speed();
  for (const std::uint16_t raw : {std::uint16_t{0xFE00}, std::uint16_t{0xFFFF}}) {  // error, not available
    std::uint8_t bytes[8] = {static_cast<std::uint8_t>(raw & 0xFF), static_cast<std::uint8_t>(raw >> 8), 0, 0, 0, 0,
                             0xFF, 0xFD};
    ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kGroundBasedSpeedPgn, kGlobalAddress, 0xF0}), bytes, 8)));
    run(1);  // the next loop step, not the source's 300 ms timeout
    EXPECT_EQ(request(141), 0) << std::hex << raw;
    EXPECT_TRUE(fault_active(Fault::kSpeedUnavailable));
    go_live(3.0);
    run(2);
    ASSERT_EQ(request(141), 1);
    stop_speed();
  }
  EXPECT_EQ(ecu_io_.processor().counters().speed_not_available, 2u);
}

TEST_F(VirtualBus, ReverseStopsSpreading) {
  set_spreading();
  go_live(3.0);
  run(100);
  ASSERT_EQ(request(141), 1);
  stop_speed();
  send_speed(kGroundBasedSpeedPgn, 1.5, Direction::kReverse);
  run(1);
  EXPECT_EQ(request(141), 0);
  EXPECT_TRUE(fault_active(Fault::kDrivingReverse));
}

TEST_F(VirtualBus, MachineSelectedSpeedWinsAndEachSourceTimesOut) {
  send_speed(kWheelBasedSpeedPgn, 2.0, Direction::kForward);
  send_speed(kGroundBasedSpeedPgn, 2.5, Direction::kForward);
  send_speed(kMachineSelectedSpeedPgn, 2.2, Direction::kForward);
  run(1);
  EXPECT_NEAR(ecu_.status().ground_speed_m_s, 2.2, 1e-9);
  run(6);  // 350 ms: the machine selected speed is stale; the others were sent at the same time
  send_speed(kWheelBasedSpeedPgn, 2.1, Direction::kForward);
  run(1);
  EXPECT_NEAR(ecu_.status().ground_speed_m_s, 2.1, 1e-9) << "only the wheels are alive";
}

TEST_F(VirtualBus, SilentTaskControllerSwitchesTheWorkStateOff) {
  set_spreading();
  go_live(3.0);
  run(100);
  ASSERT_EQ(request(141), 1);
  stop_tc_status();  // the TC's status stops (last at 4 s); the tractor's speed keeps coming
  run(80);           // 9 s: within the 6 s the TC is given
  EXPECT_EQ(request(141), 1);
  run(40);
  EXPECT_FALSE(ecu_.status().work_state_setpoint) << "work state set-point switched off";
  EXPECT_FALSE(ecu_.status().work_state_actual);
  EXPECT_TRUE(fault_active(Fault::kTaskControllerLost));
  // A TC silent for 6 s is no longer the partner: its requests go unanswered until its status returns.
  send_pd(ProcessDataCommand::kRequestValue, 141, 0);
  EXPECT_TRUE(run(1).empty());
  EXPECT_EQ(ecu_io_.processor().task_controller_partner().counters().partners_lost, 1u);
  // The TC returns: the fault clears, the work state stays off until the TC switches it on again.
  send_tc_status();
  EXPECT_EQ(request(141), 0);
  EXPECT_FALSE(fault_active(Fault::kTaskControllerLost));
  send_pd(ProcessDataCommand::kValue, 289, 1);
  run(1);
  EXPECT_EQ(request(141), 1);
}

// Partner-only control (ISO 11783-10): another node's set-values and TC status are ignored and counted;
// the partner's address taken by another NAME stops metering at once, as a silent TC does after 6 s.
TEST_F(VirtualBus, OnlyThePartnerTaskControllerIsObeyed) {
  set_spreading();
  go_live(3.0);
  run(100);
  ASSERT_EQ(request(141), 1);
  // An unclaimed node at 0x90 switches the work state off, and a claimed non-TC node asks a value.
  const ProcessDataBytes off = encode_process_data({static_cast<std::uint8_t>(ProcessDataCommand::kValue), 0, 289, 0});
  ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kProcessDataPgn, kEcu, 0x90}), off.data(), 8)));
  claim_address(0x91, isobus::encode_name(isobus::IsoName{}));
  const ProcessDataBytes ask =
      encode_process_data({static_cast<std::uint8_t>(ProcessDataCommand::kRequestValue), 0, 7, 0});
  ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kProcessDataPgn, kEcu, 0x91}), ask.data(), 8)));
  EXPECT_TRUE(run(1).empty()) << "no answer, no PDACK to a node that is not the partner";
  EXPECT_TRUE(ecu_.status().work_state_actual);
  EXPECT_EQ(ecu_io_.processor().counters().not_from_partner, 2u);
  EXPECT_EQ(ecu_.faults().count(Fault::kCanNotFromTaskController), 2u);

  // Another NAME claims the partner's address: the partner is gone now, not 6 s later.
  claim_address(kTractor, task_controller_name(0x99));
  run(1);
  EXPECT_FALSE(ecu_.status().work_state_actual);
  EXPECT_FALSE(ecu_.status().work_state_setpoint);
  EXPECT_TRUE(fault_active(Fault::kTaskControllerLost));
  EXPECT_EQ(ecu_io_.processor().task_controller_partner().last_loss(), "its address was claimed by another NAME");
}

// The ISO 11783-10 connection, with this test as the task controller: the ECU hands over its device
// descriptor object pool by TP, activates it, and then takes set-points on the pool's elements.
TEST_F(VirtualBus, TaskControllerReceivesActivatesAndDrivesThePool) {
  isobus::TransportProtocol tp(kTractor);
  auto tc_send = [&](const isobus::TcFrame& f) {
    ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kProcessDataPgn, kEcu, kTractor}), f.data(), 8)));
  };
  auto last_connection_frame = [&]() -> std::array<std::uint8_t, 8> {
    EXPECT_FALSE(connection_frames_.empty());
    std::array<std::uint8_t, 8> b{};
    if (!connection_frames_.empty()) std::copy(connection_frames_.back().data, connection_frames_.back().data + 8, b.begin());
    return b;
  };
  send_tc_status();
  run(1);
  ASSERT_EQ(connection_frames_.size(), 2u);
  EXPECT_EQ(decode_id(connection_frames_[0].can_id & CAN_EFF_MASK).pgn, isobus::kWorkingSetMasterPgn);
  EXPECT_EQ(last_connection_frame()[0], 0x00) << "request version";
  tc_send(isobus::encode_version({}));
  run(1);
  EXPECT_EQ(last_connection_frame()[0], 0x01) << "request structure label";
  tc_send(isobus::encode_label(isobus::TcMessage::kStructureLabel, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}));
  run(1);
  EXPECT_EQ(last_connection_frame()[0], 0x21) << "request localisation label";
  tc_send(isobus::encode_label(isobus::TcMessage::kLocalizationLabel, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}));
  run(1);
  const auto transfer_request = last_connection_frame();
  ASSERT_EQ(transfer_request[0], 0x41) << "request object-pool transfer";
  const std::uint32_t size = transfer_request[1] | (transfer_request[2] << 8) | (transfer_request[3] << 16) |
                             (std::uint32_t{transfer_request[4]} << 24);
  tc_send(isobus::encode_error_answer(isobus::TcMessage::kRequestPoolTransferResponse, 0));
  // The pool by TP: the TC's side of the protocol answers the ECU's RTS and data packets.
  std::vector<isobus::TransportMessage> received;
  for (int tick = 0; tick < 200 && received.empty(); ++tick) {
    for (const can_frame& f : run(1)) {
      const IsobusId id = decode_id(f.can_id & CAN_EFF_MASK);
      isobus::TransportFrame t{id.priority, id.pgn, id.source, id.destination, {}};
      std::copy(f.data, f.data + 8, t.data.begin());
      tp.handle_frame(t, clock_.now());
    }
    tp.update(clock_.now());
    for (const auto& t : tp.take_frames()) {
      ASSERT_TRUE(tractor().send(make_frame(encode_id({t.priority, t.pgn, t.destination, kTractor}), t.data.data(), 8)));
    }
    received = tp.take_received();
  }
  ASSERT_EQ(received.size(), 1u) << "the pool arrived";
  ASSERT_EQ(received[0].data.size(), size + 1);
  EXPECT_EQ(received[0].data[0], 0x61);
  const isobus::DdopParseResult pool =
      isobus::parse_ddop(std::span<const std::uint8_t>(received[0].data).subspan(1));
  ASSERT_TRUE(pool.pool.has_value()) << pool.error;
  int sections = 0;
  for (const auto& o : pool.pool->objects) {
    if (const auto* e = std::get_if<isobus::DeviceElement>(&o); e && e->type == isobus::ElementType::kSection) ++sections;
  }
  EXPECT_EQ(sections, 8);
  tc_send(isobus::encode_error_answer(isobus::TcMessage::kPoolTransferResponse, 0));
  run(1);
  EXPECT_EQ(last_connection_frame()[0], 0x81) << "activate";
  tc_send(isobus::encode_error_answer(isobus::TcMessage::kActivatePoolResponse, 0));
  run(2);
  EXPECT_TRUE(ecu_io_.processor().task_controller_client().connected());
  EXPECT_EQ(last_connection_frame()[0], 0xFF) << "client task message";

  // Set-points on the pool's elements: rate on the bin (2), sections 1-4 on the boom (1).
  go_live(3.0);
  send_pd(ProcessDataCommand::kValue, 6, 25000, 2);
  send_pd(ProcessDataCommand::kValue, 66, 24000, 1);
  send_pd(ProcessDataCommand::kValue, 389, 7500000, 3);
  send_pd(ProcessDataCommand::kValue, 290, static_cast<std::int32_t>(0xFFFF0055u), 1);
  send_pd(ProcessDataCommand::kValue, 289, 1, 0);
  run(100);
  send_pd(ProcessDataCommand::kRequestValue, 161, 0, 1);
  EXPECT_EQ(static_cast<std::uint32_t>(single_answer(161).value), 0xFFFF0055u) << "sections 1-4 on, 5-8 off";
  EXPECT_EQ(request(141), 1);
  // A DDI on an element that does not carry it is refused (the boom has no rate).
  send_pd(ProcessDataCommand::kRequestValue, 6, 0, 1);
  EXPECT_EQ(pdack_errors(6), kPdackDdiNotSupported);
}

// DM1 (ISO 11783-12): once a second the active faults, each as its proprietary SPN with a failure mode;
// none active is the all-zero DTC; several go by BAM.
TEST_F(VirtualBus, ActiveFaultsAreBroadcastInDm1) {
  auto latest_dm1 = [&]() -> std::optional<isobus::Dm1> {
    if (dm1_frames_.empty()) return std::nullopt;
    return isobus::decode_dm1(std::span<const std::uint8_t>(dm1_frames_.back().data, 6));
  };
  run(1);
  ASSERT_FALSE(dm1_frames_.empty());
  EXPECT_EQ(decode_id(dm1_frames_.back().can_id & CAN_EFF_MASK).priority, 6);
  ASSERT_TRUE(latest_dm1().has_value());
  EXPECT_TRUE(latest_dm1()->active.empty()) << "no active fault";
  EXPECT_FALSE(latest_dm1()->lamps.amber_warning);
  // One refused set-point: one DTC, SPN 520192 + 5, FMI 2 (data erratic), occurrence 1, lamp off (an event).
  send_pd(ProcessDataCommand::kValue, 66, 100000);
  run(20);
  auto dm1 = latest_dm1();
  ASSERT_TRUE(dm1.has_value());
  ASSERT_EQ(dm1->active.size(), 1u);
  EXPECT_EQ(dm1->active[0].spn, isobus::kProprietarySpnBase + 5);
  EXPECT_EQ(dm1->active[0].fmi, isobus::Fmi::kDataErratic);
  EXPECT_EQ(dm1->active[0].occurrences, 1);
  EXPECT_FALSE(dm1->lamps.amber_warning);
  // Spreading asked for without a speed and with the disc at rest: two held conditions and the event,
  // more than 8 bytes: a BAM announcing PGN 0xFECA.
  set_spreading(0);
  const auto frames = run(20);
  const bool bam = std::any_of(frames.begin(), frames.end(), [](const can_frame& f) {
    const IsobusId id = decode_id(f.can_id & CAN_EFF_MASK);
    return id.pgn == isobus::kTpConnectionManagementPgn && f.data[0] == 32 && f.data[5] == 0xCA && f.data[6] == 0xFE;
  });
  EXPECT_TRUE(bam) << "DM1 with several DTCs by BAM";
}

// ISO 11783-10 measurement commands: the ECU sends values by itself on a time or distance interval, on a
// change threshold, and within minimum/maximum thresholds, to the TC that asked, on the element asked.
TEST_F(VirtualBus, MeasurementCommandsMakeTheEcuSendValuesByItself) {
  auto values_of = [&](const std::vector<can_frame>& frames, std::uint16_t ddi) {
    std::vector<std::int32_t> v;
    for (const can_frame& f : frames) {
      ProcessDataBytes b{};
      std::copy(f.data, f.data + 8, b.begin());
      const ProcessData m = decode_process_data(b);
      const IsobusId id = decode_id(f.can_id & CAN_EFF_MASK);
      if (id.pgn == kProcessDataPgn && m.command == 3 && m.ddi == ddi && id.destination == kTractor) {
        v.push_back(m.value);
      }
    }
    return v;
  };
  set_spreading();
  go_live(3.0);
  send_pd(static_cast<ProcessDataCommand>(0x4), 7, 1000, 2);       // rate every 1 s, on the bin element
  send_pd(static_cast<ProcessDataCommand>(0x8), 390, 1000000, 3);  // disc speed on every 100 r/min change
  send_pd(static_cast<ProcessDataCommand>(0x5), 397, 6000, 0);     // speed every 6 m driven
  const auto frames = run(200);                                     // 10 s
  const auto rate = values_of(frames, 7);
  EXPECT_GE(rate.size(), 10u);
  EXPECT_LE(rate.size(), 11u);
  EXPECT_EQ(rate.back(), 25000) << "spreading at 250 kg/ha";
  const auto rpm = values_of(frames, 390);
  EXPECT_GE(rpm.size(), 6u) << "the spin-up to 750 r/min crosses 100 r/min steps";
  EXPECT_LE(rpm.size(), 9u) << "a settled disc sends nothing more";
  const auto speed = values_of(frames, 397);
  EXPECT_NEAR(static_cast<double>(speed.size()), 5.0, 1.0) << "30 m driven, every 6 m";
  EXPECT_EQ(ecu_io_.processor().measurement_triggers().active(), 3u);
  // Cancelled: no more rate values.
  send_pd(static_cast<ProcessDataCommand>(0x4), 7, 0, 2);
  run(1);
  EXPECT_TRUE(values_of(run(60), 7).empty());
  // A trigger on an element that does not carry the DDI is refused.
  send_pd(static_cast<ProcessDataCommand>(0x4), 7, 1000, 1);
  EXPECT_EQ(pdack_errors(7), kPdackDdiNotSupported);
}

// Threshold triggers report once per crossing, not on every change while the value is past the threshold
// (the disc speed changes every loop step while it spins up or down).
TEST_F(VirtualBus, ThresholdTriggersReportOnceOnCrossing) {
  auto rpm_values = [](const std::vector<can_frame>& frames) {
    std::vector<std::int32_t> v;
    for (const can_frame& f : frames) {
      ProcessDataBytes b{};
      std::copy(f.data, f.data + 8, b.begin());
      const ProcessData m = decode_process_data(b);
      if (m.command == 3 && m.ddi == 390) v.push_back(m.value);
    }
    return v;
  };
  go_live();  // the TC's status keeps it the partner through the 30 s below
  send_pd(static_cast<ProcessDataCommand>(0x7), 390, 3000000, 3);  // at or below 300 r/min
  auto values = rpm_values(run(2));
  ASSERT_EQ(values.size(), 1u) << "the resting disc is inside at once: reported once";
  EXPECT_EQ(values[0], 0);
  send_pd(ProcessDataCommand::kValue, 389, 7500000);  // spin up to 750 r/min: leaves the window
  EXPECT_TRUE(rpm_values(run(200)).empty());
  send_pd(static_cast<ProcessDataCommand>(0x6), 390, 6000000, 3);  // and at or above 600 r/min
  EXPECT_TRUE(rpm_values(run(2)).empty()) << "750 r/min is outside the window 600-300";
  send_pd(static_cast<ProcessDataCommand>(0x7), 390, 8000000, 3);  // the window is now 600-800 r/min
  values = rpm_values(run(2));
  ASSERT_EQ(values.size(), 1u) << "inside the new window: once";
  send_pd(ProcessDataCommand::kValue, 389, 0);  // spin down through 600 r/min
  EXPECT_TRUE(rpm_values(run(200)).empty()) << "leaving the window sends nothing";
  send_pd(ProcessDataCommand::kValue, 389, 7000000);  // up again: enters 600-800 once
  values = rpm_values(run(200));
  ASSERT_EQ(values.size(), 1u);
  EXPECT_GE(values[0], 6000000);
  EXPECT_LE(values[0], 8000000);
}

TEST_F(VirtualBus, StandardAndRemoteFramesOfOtherNodesAreNoFault) {
  can_frame standard{};
  standard.can_id = 0x123;
  standard.len = 8;
  ASSERT_TRUE(tractor().send(standard));
  can_frame remote = make_frame(encode_id({3, kProcessDataPgn, kEcu, kTractor}), nullptr, 0);
  remote.can_id |= CAN_RTR_FLAG;
  ASSERT_TRUE(tractor().send(remote));
  EXPECT_TRUE(run(1).empty());
  EXPECT_EQ(ecu_io_.processor().counters().frames_ignored, 2u);
  EXPECT_EQ(ecu_.faults().total(), 0u);
}

TEST_F(VirtualBus, WheelBasedSpeedAloneIsTheGroundSpeed) {
  // A tractor without a radar broadcasts only PGN 0xFE48: that speed must drive metering and DDI 397.
  const auto wheel = encode_speed(2.5, 0, Direction::kForward);
  ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kWheelBasedSpeedPgn, kGlobalAddress, 0xF0}), wheel.data(), 8)));
  EXPECT_TRUE(run(1).empty());
  EXPECT_NEAR(ecu_.status().ground_speed_m_s, 2.5, 1e-9);
  EXPECT_EQ(ecu_io_.processor().counters().speed_messages, 1u);
  send_pd(ProcessDataCommand::kRequestValue, 397, 0);
  EXPECT_EQ(single_answer(397).value, 2500);  // mm/s

  // A ground-based speed takes over while fresh (300 ms); after it goes quiet the wheels count again.
  const auto ground = encode_speed(4.0, 0, Direction::kForward);
  ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kGroundBasedSpeedPgn, kGlobalAddress, 0xF0}), ground.data(), 8)));
  run(1);
  const auto wheel_slipping = encode_speed(4.4, 0, Direction::kForward);
  ASSERT_TRUE(
      tractor().send(make_frame(encode_id({3, kWheelBasedSpeedPgn, kGlobalAddress, 0xF0}), wheel_slipping.data(), 8)));
  run(1);
  EXPECT_NEAR(ecu_.status().ground_speed_m_s, 4.0, 1e-9);
  run(20);  // 1 s without a ground-based speed
  ASSERT_TRUE(
      tractor().send(make_frame(encode_id({3, kWheelBasedSpeedPgn, kGlobalAddress, 0xF0}), wheel_slipping.data(), 8)));
  run(1);
  EXPECT_NEAR(ecu_.status().ground_speed_m_s, 4.4, 1e-9);
  EXPECT_EQ(ecu_.faults().total(), 0u);
}

TEST_F(VirtualBus, AnswersAddressClaimRequest) {
  const std::uint8_t request[3] = {0x00, 0xEE, 0x00};
  ASSERT_TRUE(tractor().send(make_frame(encode_id({6, kRequestPgn, kGlobalAddress, kTractor}), request, 3)));
  const auto frames = run(1);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(decode_id(frames[0].can_id & CAN_EFF_MASK).pgn, kAddressClaimedPgn);
}

struct BadProcessDataCase {
  const char* name;
  std::uint8_t command;
  std::uint16_t ddi;
  std::int32_t value;
  std::uint16_t element;
  std::uint8_t expected_pdack;
  Fault expected_fault;
};

class VirtualBusBadProcessData : public VirtualBus, public ::testing::WithParamInterface<BadProcessDataCase> {};

TEST_P(VirtualBusBadProcessData, IsNackedCountedAndChangesNothing) {
  const BadProcessDataCase& c = GetParam();
  send_pd(ProcessDataCommand::kValue, 6, 20000);
  run(1);
  const EcuStatus before = ecu_.status();
  send_pd(static_cast<ProcessDataCommand>(c.command), c.ddi, c.value, c.element);
  EXPECT_EQ(pdack_errors(c.ddi), c.expected_pdack);
  const EcuStatus after = ecu_.status();
  EXPECT_EQ(after.fault_counts[static_cast<std::size_t>(c.expected_fault)], 1u) << fault_name(c.expected_fault);
  EXPECT_NE(after.fault_codes & fault_bit(c.expected_fault), 0u);
  EXPECT_EQ(after.rate_setpoint_kg_ha, before.rate_setpoint_kg_ha);
  EXPECT_EQ(after.width_setpoint_m, before.width_setpoint_m);
  EXPECT_EQ(after.rpm_target, before.rpm_target);
  EXPECT_EQ(after.section_mask, before.section_mask);
  EXPECT_EQ(after.work_state_setpoint, before.work_state_setpoint);
}

INSTANTIATE_TEST_SUITE_P(
    AllClasses, VirtualBusBadProcessData,
    ::testing::Values(
        BadProcessDataCase{"unknown_ddi_request", 0x2, 999, 0, 0, kPdackDdiNotSupported, Fault::kCanUnknownDdi},
        BadProcessDataCase{"unknown_ddi_set", 0xA, 1234, 5, 0, kPdackDdiNotSupported, Fault::kCanUnknownDdi},
        // Element 5 (section 2) exists but does not carry DDI 6; element 100 does not exist; DDI 1 (volume
        // per area) is on no element of this spreader, the hopper (2) included.
        BadProcessDataCase{"ddi_not_on_that_element", 0x2, 6, 0, 5, kPdackDdiNotSupported, Fault::kCanUnknownDdi},
        BadProcessDataCase{"element_does_not_exist", 0x2, 6, 0, 100, kPdackInvalidElement, Fault::kCanUnknownDdi},
        BadProcessDataCase{"volume_rate_on_the_hopper", 0x3, 1, 20000, 2, kPdackDdiNotSupported,
                           Fault::kCanUnknownDdi},
        BadProcessDataCase{"unsupported_command", 0x9, 6, 1000, 0, kPdackCommandNotSupported,
                           Fault::kCanUnsupportedCommand},
        BadProcessDataCase{"negative_time_interval", 0x4, 7, -100, 0, kPdackInvalidInterval,
                           Fault::kSetpointOutOfRange},
        BadProcessDataCase{"read_only_ddi", 0xA, 7, 100, 0, kPdackNotSettable, Fault::kCanNotSettable},
        BadProcessDataCase{"negative_rate", 0xA, 6, -1, 0, kPdackValueOutOfRange, Fault::kSetpointOutOfRange},
        BadProcessDataCase{"width_too_wide", 0x3, 66, 100000, 0, kPdackValueOutOfRange, Fault::kSetpointOutOfRange},
        BadProcessDataCase{"rpm_too_fast", 0x3, 389, 2000000000, 0, kPdackValueOutOfRange,
                           Fault::kSetpointOutOfRange},
        BadProcessDataCase{"work_state_two", 0xA, 289, 2, 0, kPdackValueOutOfRange, Fault::kSetpointOutOfRange},
        BadProcessDataCase{"section_nine_on", 0xA, 290, 0x10000, 0, kPdackValueOutOfRange,
                           Fault::kSetpointOutOfRange},
        BadProcessDataCase{"section_error_state", 0xA, 290, 0x2, 0, kPdackValueOutOfRange,
                           Fault::kSetpointOutOfRange}),
    [](const ::testing::TestParamInfo<BadProcessDataCase>& param_info) { return std::string(param_info.param.name); });

TEST_F(VirtualBus, MalformedFramesAreCountedAndLoopGoesOn) {
  // Truncated record (5 bytes of a 16-byte can_frame).
  const std::uint8_t junk[5] = {1, 2, 3, 4, 5};
  ASSERT_TRUE(tractor().send_raw(junk, sizeof(junk)));
  // Oversized record (a CAN FD frame's size).
  std::uint8_t big[72] = {};
  ASSERT_TRUE(tractor().send_raw(big, sizeof(big)));
  // Process data with DLC 4.
  const std::uint8_t short_pd[4] = {0x02, 0x00, 0x06, 0x00};
  ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kProcessDataPgn, kEcu, kTractor}), short_pd, 4)));
  // Speed with DLC 2.
  const std::uint8_t short_speed[2] = {0x10, 0x00};
  ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kGroundBasedSpeedPgn, 0xFF, 0xF0}), short_speed, 2)));
  // NaN has no integer encoding on CAN; a speed beyond the ECU's range stands for an impossible value.
  const auto too_fast = encode_speed(30.0, 0, Direction::kForward);
  ASSERT_TRUE(tractor().send(make_frame(encode_id({3, kGroundBasedSpeedPgn, 0xFF, 0xF0}), too_fast.data(), 8)));

  EXPECT_TRUE(run(3).empty()) << "malformed frames get no answer";
  EXPECT_EQ(ecu_.faults().count(Fault::kCanMalformedFrame), 4u);
  EXPECT_EQ(ecu_.faults().count(Fault::kSetpointOutOfRange), 1u);
  EXPECT_EQ(ecu_.status().ground_speed_m_s, 0.0);
  EXPECT_EQ(loop_.statistics().ticks, 3) << "the loop kept running";
  // And the bus still works afterwards.
  send_pd(ProcessDataCommand::kRequestValue, 6, 0);
  EXPECT_EQ(single_answer(6).value, 0);
}

TEST_F(VirtualBus, BroadcastErrorsAreCountedButNotNacked) {
  send_pd(ProcessDataCommand::kValue, 999, 1, 0, kGlobalAddress);
  EXPECT_TRUE(run(1).empty());
  EXPECT_EQ(ecu_.faults().count(Fault::kCanUnknownDdi), 1u);
  // Frames for another ECU are not ours to judge.
  send_pd(ProcessDataCommand::kValue, 999, 1, 0, 0x90);
  EXPECT_TRUE(run(1).empty());
  EXPECT_EQ(ecu_.faults().count(Fault::kCanUnknownDdi), 1u);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Replays tests/firmware/data/process_data_session.log and returns the ECU's answers as a candump log.
std::string replay_answers(const CandumpLog& log) {
  ManualClock clock(log.records.front().time);
  EcuParameters p;
  p.command_timeout = 0s;
  Ecu ecu(clock, p);
  std::ostringstream answers;
  CandumpWriter writer(answers, clock, "can0");
  CanEcuProcessor processor(ecu, clock, writer);
  CandumpReplayIo replay(log, processor, clock);
  FixedRateLoop loop(clock, 20.0);
  loop.run(ecu, replay, replay.span() + 1s);
  EXPECT_TRUE(replay.finished());
  return answers.str();
}

TEST(CandumpReplay, ProducesTheRecordedAnswers) {
  const std::string dir = SPREAD_FIRMWARE_TEST_DATA;
  const CandumpLog log = read_candump_file(dir + "/process_data_session.log");
  ASSERT_TRUE(log.errors.empty()) << log.errors.front();
  ASSERT_FALSE(log.records.empty());
  const std::string answers = replay_answers(log);
  if (std::getenv("SPREAD_FIRMWARE_REGENERATE") != nullptr) {
    std::ofstream(dir + "/process_data_session.expected") << answers;
  }
  EXPECT_EQ(answers, read_text(dir + "/process_data_session.expected"));
  EXPECT_EQ(replay_answers(log), answers) << "replay is deterministic";
}

}  // namespace
}  // namespace spread::firmware::can
