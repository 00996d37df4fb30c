// ISO 11783-5 network management: the NAME layout, the address-claim state machine (start, 250 ms settle,
// contention won and lost, self-configurable re-claim, cannot-claim, requests), and the ECU on top of it:
// silent until its claim stands, fail-safe when the address is lost, NACK for unsupported requests.
#include <gtest/gtest.h>

#include <vector>

#include <cstdlib>
#include <filesystem>

#include "firmware_sim/can/can_bus_relay.hpp"
#include "firmware_sim/can/can_ecu_link.hpp"
#include "firmware_sim/can/unix_can_bus.hpp"
#include "firmware_sim/can/isobus_id.hpp"
#include "firmware_sim/can/process_data.hpp"
#include "firmware_sim/isobus/address_claim.hpp"
#include "firmware_sim/isobus/iso_name.hpp"
#include "firmware_sim/isobus/tc_messages.hpp"
#include "firmware_sim/isobus/tc_partner.hpp"

namespace spread::firmware::isobus {
namespace {

using namespace std::chrono_literals;

TEST(IsoName, FieldsSitWhereIso11783_5PutsThem) {
  const IsoName spreader;  // the ECU's default: agriculture, fertilisers, rate control
  EXPECT_EQ(encode_name(spreader), 0x200A800000001234ull);
  IsoName all;
  all.self_configurable = true;
  all.industry_group = 7;
  all.device_class_instance = 0xF;
  all.device_class = 0x7F;
  all.function = 0xFF;
  all.function_instance = 0x1F;
  all.ecu_instance = 7;
  all.manufacturer_code = 0x7FF;
  all.identity_number = 0x1FFFFF;
  EXPECT_EQ(encode_name(all), 0xFFFEFFFFFFFFFFFFull) << "only the reserved bit 48 stays 0";
  IsoName one;
  one = IsoName{false, 0, 0, 0, 0, 0, 0, 0, 0};
  one.manufacturer_code = 1;
  EXPECT_EQ(encode_name(one), 1ull << 21);
  one = IsoName{false, 0, 0, 0, 0, 0, 0, 0, 0};
  one.ecu_instance = 1;
  EXPECT_EQ(encode_name(one), 1ull << 32);
  one = IsoName{false, 0, 0, 0, 0, 0, 0, 0, 0};
  one.function_instance = 1;
  EXPECT_EQ(encode_name(one), 1ull << 35);
  one = IsoName{false, 0, 0, 0, 0, 0, 0, 0, 0};
  one.device_class_instance = 1;
  EXPECT_EQ(encode_name(one), 1ull << 56);
  const IsoName back = decode_name(encode_name(all));
  EXPECT_EQ(encode_name(back), encode_name(all));
  EXPECT_EQ(check_name(all), "");
}

TEST(IsoName, OutOfWidthFieldsBytesAndHex) {
  IsoName n;
  n.identity_number = 1u << 21;
  EXPECT_EQ(check_name(n), "identity number above 2097151");
  n = IsoName{};
  n.manufacturer_code = 2048;
  EXPECT_EQ(check_name(n), "manufacturer code above 2047");
  n = IsoName{};
  n.device_class = 128;
  EXPECT_NE(check_name(n), "");
  const auto bytes = name_to_bytes(0x200A800000001234ull);
  const std::array<std::uint8_t, 8> expected{0x34, 0x12, 0x00, 0x00, 0x00, 0x80, 0x0A, 0x20};
  EXPECT_EQ(bytes, expected);  // little-endian on the bus, as in the recorded replay answers
  EXPECT_EQ(name_from_bytes(bytes.data()), 0x200A800000001234ull);
  EXPECT_EQ(parse_name_hex("0x200A800000001234"), 0x200A800000001234ull);
  EXPECT_EQ(parse_name_hex("a00a800000001234"), 0xA00A800000001234ull);
  EXPECT_FALSE(parse_name_hex("0x"));
  EXPECT_FALSE(parse_name_hex("12345678901234567"));
  EXPECT_FALSE(parse_name_hex("12G4"));
  EXPECT_NE(describe_name(0x200A800000001234ull).find("function 128"), std::string::npos);
}

std::uint64_t name_with(bool self_configurable, std::uint32_t identity) {
  IsoName n;
  n.self_configurable = self_configurable;
  n.identity_number = identity;
  return encode_name(n);
}

TEST(AddressClaim, ClaimsAtStartAndMaySendAfter250Ms) {
  AddressClaim claim(name_with(false, 10), 0x80);
  EXPECT_EQ(claim.state(), ClaimState::kNotStarted);
  EXPECT_TRUE(claim.poll(0ms).empty());
  claim.start(0ms);
  const auto sent = claim.poll(0ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 0x80);
  EXPECT_EQ(sent[0].name, name_with(false, 10));
  EXPECT_FALSE(claim.has_address());
  EXPECT_TRUE(claim.poll(249ms).empty());
  EXPECT_FALSE(claim.has_address()) << "§4.4.2: no other message for 250 ms after the claim";
  claim.poll(250ms);
  EXPECT_TRUE(claim.has_address());
  EXPECT_EQ(claim.address(), 0x80);
}

TEST(AddressClaim, LowerNameWinsTheWinnerRepeatsItsClaim) {
  AddressClaim claim(name_with(false, 10), 0x80);
  claim.start(0ms);
  claim.poll(300ms);
  ASSERT_TRUE(claim.has_address());
  claim.on_address_claimed(0x80, name_with(false, 11), 400ms);  // higher NAME: it loses
  const auto sent = claim.poll(400ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 0x80);
  EXPECT_TRUE(claim.has_address());
  EXPECT_EQ(claim.counters().contentions_won, 1u);
}

// Our NAME from another node once (a stray or spoofed frame): we contend with our claim and keep the
// address. Twice within 2 s (a second unit with our NAME): neither can be told apart, so we give up for a
// hold-off and then claim again by ourselves, never going silent for good.
TEST(AddressClaim, OurNameFromAnotherNodeOnceIsContendedTwiceMakesUsHoldOff) {
  for (const std::uint8_t other_address : {std::uint8_t{0x80}, std::uint8_t{0x81}, kNullAddress}) {
    AddressClaim claim(name_with(true, 10), 0x80);  // even a self-configurable one: moving would not help
    claim.start(0ms);
    claim.poll(300ms);
    ASSERT_TRUE(claim.has_address());
    claim.on_address_claimed(other_address, name_with(true, 10), 400ms);
    auto sent = claim.poll(400ms);
    ASSERT_EQ(sent.size(), 1u) << int{other_address};
    EXPECT_EQ(sent[0].source, 0x80) << "one sighting: our claim again, the address stays ours";
    EXPECT_TRUE(claim.has_address());
    claim.on_address_claimed(other_address, name_with(true, 10), 500ms);
    EXPECT_EQ(claim.state(), ClaimState::kCannotClaim) << "a second sighting within 2 s: a second unit";
    EXPECT_FALSE(claim.has_address());
    sent = claim.poll(700ms);
    ASSERT_EQ(sent.size(), 1u);
    EXPECT_EQ(sent[0].source, kNullAddress) << "cannot-claim, which the other unit sees in turn";
    // The other unit's cannot-claim (our NAME again) starts the 3 s hold-off over, and sends nothing.
    claim.on_address_claimed(kNullAddress, name_with(true, 10), 800ms);
    EXPECT_TRUE(claim.poll(3799ms).empty());
    EXPECT_FALSE(claim.has_address());
    sent = claim.poll(3800ms);
    ASSERT_EQ(sent.size(), 1u) << "the hold-off is over: claim the preferred address again";
    EXPECT_EQ(sent[0].source, 0x80);
    claim.poll(4050ms);
    EXPECT_TRUE(claim.has_address());
    EXPECT_EQ(claim.counters().duplicate_names, 3u);
    EXPECT_EQ(claim.counters().duplicate_name_holds, 1u);
    // A second episode holds off twice as long (6 s).
    claim.on_address_claimed(other_address, name_with(true, 10), 10000ms);
    claim.on_address_claimed(other_address, name_with(true, 10), 10100ms);
    EXPECT_FALSE(claim.has_address());
    claim.poll(16099ms);
    EXPECT_EQ(claim.state(), ClaimState::kCannotClaim);
    EXPECT_EQ(claim.poll(16100ms).size(), 1u);
    EXPECT_EQ(claim.state(), ClaimState::kClaiming);
  }
}

TEST(AddressClaim, AddressViolationIsAnsweredWithOurClaimAtMostEvery250Ms) {
  AddressClaim claim(name_with(false, 10), 0x80);
  claim.on_address_violation(0ms);
  EXPECT_TRUE(claim.poll(0ms).empty()) << "nothing to defend before start";
  claim.start(0ms);
  claim.poll(300ms);
  claim.on_address_violation(400ms);
  auto sent = claim.poll(400ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 0x80);
  for (auto t = 401ms; t < 650ms; t += 10ms) claim.on_address_violation(t);  // a flood of spoofed frames
  EXPECT_TRUE(claim.poll(649ms).empty());
  claim.on_address_violation(650ms);
  EXPECT_EQ(claim.poll(650ms).size(), 1u);
  EXPECT_EQ(claim.counters().address_violations, 27u);
  EXPECT_EQ(claim.counters().violation_claims, 2u);
  EXPECT_TRUE(claim.has_address()) << "a violation is no contention: the address stays ours";
}

TEST(AddressClaim, NotSelfConfigurableLoserSendsCannotClaimAfterItsDelayAndFallsSilent) {
  AddressClaim claim(name_with(false, 10), 0x80);
  claim.start(0ms);
  claim.poll(300ms);
  claim.on_address_claimed(0x80, name_with(false, 9), 1000ms);  // lower NAME takes 0x80
  EXPECT_FALSE(claim.has_address());
  EXPECT_EQ(claim.state(), ClaimState::kCannotClaim);
  EXPECT_EQ(claim.address(), kNullAddress);
  std::vector<ClaimMessage> sent;
  for (auto t = 1000ms; t <= 1160ms && sent.empty(); t += 1ms) sent = claim.poll(t);
  ASSERT_EQ(sent.size(), 1u) << "cannot-claim within 0.6 ms × 255 = 153 ms";
  EXPECT_EQ(sent[0].source, kNullAddress);
  EXPECT_EQ(sent[0].name, name_with(false, 10));
  // A request for the claim is answered with cannot-claim again, after the same bounded delay.
  claim.on_request_for_claim(2000ms);
  EXPECT_EQ(claim.poll(2153ms).size(), 1u);
  EXPECT_EQ(claim.counters().cannot_claim_sent, 2u);
  EXPECT_FALSE(claim.has_address());
}

TEST(AddressClaim, SelfConfigurableLoserMovesToAFreeAddressAndWaitsAgain) {
  AddressClaim claim(name_with(true, 10), 128);
  claim.on_address_claimed(129, name_with(false, 1), 0ms);  // 129 is held by a stronger NAME
  claim.start(0ms);
  claim.poll(300ms);
  claim.on_address_claimed(128, name_with(false, 2), 400ms);
  const auto sent = claim.poll(400ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 130) << "129 is held by a lower NAME, 130 is free";
  EXPECT_FALSE(claim.has_address());
  claim.poll(649ms);
  EXPECT_FALSE(claim.has_address());
  claim.poll(650ms);
  EXPECT_TRUE(claim.has_address());
  EXPECT_EQ(claim.address(), 130);
}

TEST(AddressClaim, SelfConfigurableGivesUpWhenEveryAddressIsHeldByLowerNames) {
  const std::uint64_t ours = name_with(true, 1000);
  AddressClaim claim(ours, 128);
  for (int a = kSelfConfigurableFirst; a <= kSelfConfigurableLast; ++a) {
    claim.on_address_claimed(static_cast<std::uint8_t>(a), name_with(false, static_cast<std::uint32_t>(a)), 0ms);
  }
  claim.start(0ms);
  claim.poll(0ms);
  claim.on_address_claimed(128, name_with(false, 5), 10ms);
  EXPECT_EQ(claim.state(), ClaimState::kCannotClaim);
  const auto sent = claim.poll(200ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, kNullAddress);
}

TEST(AddressClaim, RequestIsAnsweredWithTheClaimAndStaleQueuedClaimsAreDropped) {
  AddressClaim claim(name_with(true, 10), 128);
  EXPECT_TRUE((claim.on_request_for_claim(0ms), claim.poll(0ms).empty())) << "nothing before start";
  claim.start(0ms);
  claim.poll(0ms);
  claim.on_request_for_claim(100ms);
  auto sent = claim.poll(100ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 128);
  // A request and then a lost contention before the next poll: the claim queued for 128 is stale.
  claim.on_request_for_claim(200ms);
  claim.on_address_claimed(128, name_with(false, 1), 200ms);
  sent = claim.poll(200ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 129);
}

}  // namespace
}  // namespace spread::firmware::isobus

namespace spread::firmware::can {
namespace {

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

}  // namespace
}  // namespace spread::firmware::can
