// The ECU on a network: silent until its ISO 11783-5 address claim stands, fail-safe when the address is lost,
// NACK for unsupported requests, two units with one NAME on one bus, and a loop that idles when its bus closes.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "firmware_sim/can/can_ecu_link.hpp"
#include "isobus/can/can_bus_relay.hpp"
#include "isobus/can/unix_can_bus.hpp"
#include "isobus/iso_name.hpp"
#include "isobus/isobus_id.hpp"
#include "isobus/process_data.hpp"
#include "isobus/tc_messages.hpp"

namespace spread::firmware::can {
namespace {

using namespace isobus;
using namespace isobus::can;

using namespace std::chrono_literals;

class RecordingSink final : public CanFrameSink {
 public:
  bool send(const can_frame& frame) override {
    frames.push_back(frame);
    return true;
  }
  std::vector<can_frame> take() { return std::exchange(frames, {}); }
  std::vector<can_frame> frames;
};

// The ECU's processor on a live bus (claim started), driven frame by frame on a manual clock.
class NetworkedEcu : public ::testing::Test {
 protected:
  NetworkedEcu() : ecu_(clock_, parameters(), nullptr), processor_(ecu_, clock_, sink_, CanEcuSettings{}) {}
  static EcuParameters parameters() {
    EcuParameters p;
    p.command_timeout = 0s;
    return p;
  }
  void deliver(std::uint32_t pgn, std::uint8_t destination, std::uint8_t source, const std::vector<std::uint8_t>& data) {
    processor_.handle_frame(make_frame(encode_id({6, pgn, destination, source}), data.data(),
                                       static_cast<std::uint8_t>(data.size())));
  }
  void request(std::uint32_t pgn, std::uint8_t destination, std::uint8_t source = 0x81) {
    deliver(kRequestPgn, destination, source,
            {static_cast<std::uint8_t>(pgn), static_cast<std::uint8_t>(pgn >> 8), static_cast<std::uint8_t>(pgn >> 16)});
  }
  void request_rate(std::uint8_t destination = 0x80) {
    const ProcessDataBytes b = encode_process_data({static_cast<std::uint8_t>(ProcessDataCommand::kRequestValue), 0, 6, 0});
    processor_.handle_frame(make_frame(encode_id({3, kProcessDataPgn, destination, 0x81}), b.data(), 8));
  }
  void advance(std::chrono::milliseconds by) {
    clock_.advance(by);
    processor_.service();
  }
  // 0x81 claims its address with a task controller's NAME and sends its status: the ECU's partner TC, whose
  // process data it takes (ISO 11783-10).
  void become_partner() {
    isobus::IsoName tc;
    tc.self_configurable = true;
    tc.device_class = isobus::kDeviceClassNonSpecific;
    tc.function = isobus::kFunctionTaskController;
    const auto name = isobus::name_to_bytes(isobus::encode_name(tc));
    deliver(kAddressClaimedPgn, kGlobalAddress, 0x81, {name.begin(), name.end()});
    const auto status = isobus::encode_tc_status(true);
    processor_.handle_frame(make_frame(encode_id({3, kProcessDataPgn, kGlobalAddress, 0x81}), status.data(), 8));
  }

  ManualClock clock_;
  RecordingSink sink_;
  Ecu ecu_;
  CanEcuProcessor processor_;
};

TEST_F(NetworkedEcu, SendsNothingButItsClaimUntilTheClaimStands) {
  processor_.start_address_claim();
  auto sent = sink_.take();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].can_id, 0x18EEFF80u | CAN_EFF_FLAG);
  EXPECT_FALSE(processor_.has_address());
  request_rate();
  advance(100ms);
  EXPECT_TRUE(sink_.take().empty()) << "process data answered before the claim stood";
  advance(150ms);
  EXPECT_TRUE(processor_.has_address());
  sent = sink_.take();
  // Once the claim stands the ECU also broadcasts its DM1 (once a second): not part of this check.
  std::erase_if(sent, [](const can_frame& f) { return decode_id(f.can_id & CAN_EFF_MASK).pgn == 0xFECAu; });
  // ... and asks every node for its address claim, to learn who holds which address (a TC that claimed
  // before the ECU joined). The request asks the ECU too: its claim follows at once, or a node that drops
  // whoever does not answer a global request would drop the ECU.
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].can_id, 0x18EAFF80u | CAN_EFF_FLAG);
  ASSERT_EQ(sent[0].len, 3);
  EXPECT_EQ(sent[0].data[0] | (sent[0].data[1] << 8) | (sent[0].data[2] << 16), 0xEE00);
  EXPECT_EQ(sent[1].can_id, 0x18EEFF80u | CAN_EFF_FLAG) << "the ECU answers its own global request";
  EXPECT_EQ(isobus::name_from_bytes(sent[1].data), CanEcuSettings{}.name);
  become_partner();
  sink_.take();  // the TC client's connection start
  request_rate();
  sent = sink_.take();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(decode_id(sent[0].can_id & CAN_EFF_MASK).pgn, kProcessDataPgn);
}

TEST_F(NetworkedEcu, LosingTheAddressSwitchesTheWorkStateOffAndSilencesTheEcu) {
  processor_.start_address_claim();
  advance(300ms);
  ASSERT_TRUE(processor_.has_address());
  ASSERT_FALSE(ecu_.set_work_state(true));
  sink_.take();
  const auto stronger = isobus::name_to_bytes(0x0000000000000001ull);
  deliver(kAddressClaimedPgn, kGlobalAddress, 0x80, {stronger.begin(), stronger.end()});
  EXPECT_FALSE(processor_.has_address());
  advance(200ms);
  EXPECT_FALSE(ecu_.status().work_state_setpoint) << "metering must not go on without a bus address";
  EXPECT_EQ(processor_.network().counters().address_losses, 1u);
  auto sent = sink_.take();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].can_id, 0x18EEFFFEu | CAN_EFF_FLAG) << "cannot-claim comes from the null address";
  request_rate();
  request_rate(kGlobalAddress);
  request(0xFEE6, 0x80);
  advance(100ms);
  EXPECT_TRUE(sink_.take().empty());
  request(kAddressClaimedPgn, kGlobalAddress);
  advance(200ms);
  sent = sink_.take();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].can_id, 0x18EEFFFEu | CAN_EFF_FLAG);
}

TEST_F(NetworkedEcu, AFrameFromOurAddressMakesTheEcuClaimAgain) {
  processor_.start_address_claim();
  advance(300ms);
  become_partner();
  sink_.take();
  // Another node sends process data from 0x80, our address: not acted on, our claim goes out again.
  const ProcessDataBytes b = encode_process_data({static_cast<std::uint8_t>(ProcessDataCommand::kValue), 0, 289, 1});
  processor_.handle_frame(make_frame(encode_id({3, kProcessDataPgn, kGlobalAddress, 0x80}), b.data(), 8));
  const auto sent = sink_.take();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].can_id, 0x18EEFF80u | CAN_EFF_FLAG);
  EXPECT_FALSE(ecu_.status().work_state_setpoint);
  EXPECT_EQ(processor_.network().claim().counters().address_violations, 1u);
  EXPECT_TRUE(processor_.has_address());
}

TEST_F(NetworkedEcu, ARequestToUsForAnUnsupportedPgnIsNackedAGlobalOneIsNot) {
  processor_.start_address_claim();
  advance(300ms);
  sink_.take();
  request(0xFEE6, 0x80, 0x81);  // time/date: not provided by this ECU
  auto sent = sink_.take();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].can_id, 0x18E8FF80u | CAN_EFF_FLAG) << "acknowledgement, to global, from 0x80";
  const std::uint8_t nack[8] = {0x01, 0xFF, 0xFF, 0xFF, 0x81, 0xE6, 0xFE, 0x00};
  EXPECT_EQ(std::vector<std::uint8_t>(sent[0].data, sent[0].data + 8), std::vector<std::uint8_t>(nack, nack + 8));
  request(0xFEE6, kGlobalAddress);
  request(0xFEE6, 0x90);  // to another node
  EXPECT_TRUE(sink_.take().empty());
  EXPECT_EQ(processor_.network().counters().requests_nacked, 1u);
  EXPECT_EQ(processor_.network().counters().requests_ignored, 1u);
  request(kAddressClaimedPgn, 0x80);
  sent = sink_.take();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].can_id, 0x18EEFF80u | CAN_EFF_FLAG);
  deliver(kRequestPgn, 0x80, 0x81, {0x00, 0xEE});  // two bytes: not a request
  EXPECT_EQ(ecu_.faults().count(Fault::kCanMalformedFrame), 1u);
  EXPECT_TRUE(sink_.take().empty());
}

// Two ECUs on one bus (spread-canbus's relay, real sockets): with one NAME they never hold an address at
// the same time, whether they prefer one address or two (each gives up for a hold-off and claims again:
// they may take turns, neither goes silent for good); with their own serial numbers both hold one.
struct TwoUnits {
  bool both_at_1_5_s = false;     // both held an address 1 s after B joined
  bool both_at_once_later = false;  // both held an address at any step from then on
  bool a_again = false;           // A held an address again after the first second
  bool b_again = false;
  std::uint64_t a_holds = 0;      // duplicate-NAME hold-offs
  std::uint64_t b_holds = 0;
  std::string report;

  TwoUnits(std::uint32_t identity_a, std::uint8_t address_a, std::uint32_t identity_b, std::uint8_t address_b,
           std::chrono::milliseconds watch) {
    char pattern[] = "/tmp/canbus-XXXXXX";
    const std::string dir = ::mkdtemp(pattern);
    {
      CanBusRelay bus(dir + "/bus");
      ManualClock clock;
      EcuParameters p;
      p.command_timeout = 0s;
      Ecu ecu_a(clock, p);
      Ecu ecu_b(clock, p);
      CanFramePort port_a = connect_unix_can_bus(bus.path());
      CanFramePort port_b = connect_unix_can_bus(bus.path());
      auto settings = [](std::uint32_t identity, std::uint8_t address) {
        isobus::IsoName n;
        n.identity_number = identity;
        CanEcuSettings s;
        s.name = isobus::encode_name(n);
        s.address = address;
        return s;
      };
      CanPortIo a(port_a, ecu_a, clock, settings(identity_a, address_a));
      CanPortIo b(port_b, ecu_b, clock, settings(identity_b, address_b));
      auto run = [&](std::chrono::milliseconds span, bool watching) {
        for (auto t = 0ms; t < span; t += 10ms) {
          bus.run_once(1ms);
          a.pump(Nanoseconds::zero());
          b.pump(Nanoseconds::zero());
          clock.advance(10ms);
          if (!watching) continue;
          const bool a_has = a.processor().has_address();
          const bool b_has = b.processor().has_address();
          both_at_once_later = both_at_once_later || (a_has && b_has);
          a_again = a_again || a_has;
          b_again = b_again || b_has;
        }
      };
      a.processor().start_address_claim();
      run(500ms, false);  // A's claim stands before B joins, as with a unit switched on later
      b.processor().start_address_claim();
      run(1000ms, false);
      both_at_1_5_s = a.processor().has_address() && b.processor().has_address();
      run(watch, true);
      const auto& ca = a.processor().network().claim().counters();
      const auto& cb = b.processor().network().claim().counters();
      a_holds = ca.duplicate_name_holds;
      b_holds = cb.duplicate_name_holds;
      report = "A hold-offs " + std::to_string(a_holds) + ", B hold-offs " + std::to_string(b_holds);
    }
    std::filesystem::remove_all(dir);
  }
};

TEST(TwoUnitsOnOneBus, OneNameNeverHoldsTwoAddressesAtOnce) {
  for (const std::uint8_t address_b : {std::uint8_t{0x80}, std::uint8_t{0x81}}) {
    const TwoUnits units(0x1234, 0x80, 0x1234, address_b, 14000ms);
    EXPECT_FALSE(units.both_at_1_5_s) << units.report;
    EXPECT_FALSE(units.both_at_once_later) << units.report;
    EXPECT_GE(units.a_holds, 1u) << units.report;
    EXPECT_GE(units.b_holds, 1u) << units.report;
    // The hold-offs end: at least one unit is back on the bus by itself, without a restart.
    EXPECT_TRUE(units.a_again || units.b_again) << units.report;
  }
  const TwoUnits distinct(1001, 0x80, 1002, 0x81, 0ms);
  EXPECT_TRUE(distinct.both_at_1_5_s) << distinct.report;
  EXPECT_EQ(distinct.report, "A hold-offs 0, B hold-offs 0");
}

// An ECU whose bus goes away keeps running without spinning on the hung-up socket.
TEST(UnixCanBus, TheEcuLoopIdlesWhenTheBusCloses) {
  char pattern[] = "/tmp/canbus-XXXXXX";
  const std::string dir = ::mkdtemp(pattern);
  SteadyClock clock;
  Ecu ecu(clock, EcuParameters{}, nullptr);
  std::optional<CanBusRelay> bus(std::in_place, dir + "/bus");
  CanFramePort port = connect_unix_can_bus(bus->path());
  CanPortIo io(port, ecu, clock);
  for (int i = 0; i < 4; ++i) bus->run_once(5ms);  // the relay accepts the ECU's connection
  bus.reset();  // the bus stops
  io.pump(20ms);
  EXPECT_TRUE(io.bus_closed());
  EXPECT_EQ(io.wait_fd(), -1);
  const auto start = std::chrono::steady_clock::now();
  io.pump(30ms);
  EXPECT_GE(std::chrono::steady_clock::now() - start, 30ms) << "returned at once: the loop would spin";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace spread::firmware::can
