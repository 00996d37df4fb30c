// ISOBUS sessions as a tractor maker runs them, replayed over spread-canbus's relay (real sockets, real
// frames) on one manual clock: the ECU (CanPortIo with its ISO 11783-10 client), the project's own task
// controller as spread-tractor tc runs it (NetworkLink + TcServer, with the ground-speed broadcast), and a
// probe node that records every frame on the bus and injects what a session needs (NACKs, a claim carrying
// the ECU's NAME, a contender for its address). Every node steps in one thread, 10 ms at a time, so a run
// is the same on a loaded machine as on an idle one.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "firmware_sim/can/can_ecu_link.hpp"
#include "libspread/control/ecu.hpp"
#include "isobus/can/can_bus_relay.hpp"
#include "isobus/can/unix_can_bus.hpp"
#include "isobus/dm1.hpp"
#include "isobus/iso_name.hpp"
#include "isobus/isobus_id.hpp"
#include "isobus/network_link.hpp"
#include "isobus/process_data.hpp"
#include "isobus/speed_messages.hpp"
#include "isobus/tc_partner.hpp"
#include "isobus/tc_server.hpp"
#include "tests/firmware/analytic_predictor.hpp"

namespace spread::firmware::can {
namespace {

using namespace isobus;
using namespace isobus::can;

using namespace std::chrono_literals;
namespace iso = isobus;

constexpr std::uint8_t kEcu = 0x80;
constexpr std::uint8_t kTcAddress = 0xF7;
constexpr std::uint8_t kProbe = 0x90;
constexpr Nanoseconds kTick = 10ms;

std::uint64_t tc_name() {
  iso::IsoName n;
  n.self_configurable = true;
  n.device_class = iso::kDeviceClassNonSpecific;
  n.function = iso::kFunctionTaskController;
  n.identity_number = 0x7C;
  return iso::encode_name(n);
}

std::uint32_t request_pgn(const can_frame& f) { return f.data[0] | (f.data[1] << 8) | (std::uint32_t{f.data[2]} << 16); }

// The task controller as spread-tractor tc runs it: address claim, TC server, speed every 100 ms, and on
// every activation the set-points (250 kg/ha, 24 m, 700 r/min, sections 1-4, work state on).
struct TcNode {
  CanFramePort port;
  NetworkLink network;
  iso::TcServer server;
  bool was_active = false;
  int activations = 0;
  std::int32_t width_mm = 24000;  // DDI 66 sent on activation (the operator's working width)
  Nanoseconds next_speed{};

  TcNode(const std::string& bus, const Clock& clock)
      : port(connect_unix_can_bus(bus)), network(clock, port, tc_name(), kTcAddress) {}

  void pump(Nanoseconds now) {
    can_frame frame{};
    while (port.read(frame) == ReadOutcome::kFrame) {
      const IsobusId id = decode_id(frame.can_id & CAN_EFF_MASK);
      if (id.pgn == iso::kAddressClaimedPgn && frame.len == 8) {
        server.on_address_claimed(id.source, iso::name_from_bytes(frame.data));
      }
      if (network.handle(id, frame) != NetworkLink::Verdict::kNotNetwork) continue;
      server.handle_frame(id.pgn, id.source, id.destination, std::span<const std::uint8_t>(frame.data, frame.len),
                          now);
    }
    network.service();
    if (!network.has_address()) return;
    if (!server.started()) server.start(network.address(), now);
    if (server.address() != network.address()) server.set_address(network.address());
    if (now >= next_speed) {
      const auto bytes = encode_speed(3.0, 0, Direction::kForward);
      port.send(make_frame(encode_id({3, kGroundBasedSpeedPgn, kGlobalAddress, network.address()}), bytes.data(), 8));
      next_speed = now + 100ms;
    }
    server.update(now);
    if (server.active() && !was_active) {
      ++activations;
      for (const auto& [ddi, value] : std::vector<std::pair<std::uint16_t, std::int32_t>>{
               {6, 25000}, {66, width_mm}, {389, 7000000}, {290, static_cast<std::int32_t>(0xFFFF0055u)}, {289, 1}}) {
        EXPECT_EQ(server.set_value(ddi, value), "");
      }
    }
    was_active = server.active();
    for (const iso::TransportFrame& f : server.take_frames()) {
      port.send(make_frame(encode_id({f.priority, f.pgn, f.destination, f.source}), f.data.data(), 8));
    }
  }
};

struct Seen {
  Nanoseconds time;
  IsobusId id;
  can_frame frame;
};

class IsobusSession : public ::testing::Test {
 protected:
  // `with_tables`: the ECU holds a launch table (an analytic one: materials "urea" and "can27").
  explicit IsobusSession(bool with_tables = false)
      : dir_(make_dir()),
        bus_(dir_ + "/bus"),
        ecu_(clock_, parameters(), with_tables ? &predictor_ : nullptr),
        probe_(connect_unix_can_bus(bus_.path())) {}
  ~IsobusSession() override {
    ecu_io_.reset();
    tc_.reset();
    std::filesystem::remove_all(dir_);
  }

  static std::string make_dir() {
    char pattern[] = "/tmp/isobus-session-XXXXXX";
    return ::mkdtemp(pattern);
  }
  static EcuParameters parameters() {
    EcuParameters p;
    p.command_timeout = 0s;
    return p;
  }

  void start_tc() {
    tc_.emplace(bus_.path(), clock_);
    tc_->network.start();
  }
  void start_ecu(CanEcuSettings settings = {}) {
    loop_start_ = clock_.now();
    ecu_port_ = connect_unix_can_bus(bus_.path());
    ecu_io_.emplace(ecu_port_, ecu_, clock_, settings);
    ecu_io_->processor().start_address_claim();
  }

  void run(Nanoseconds span) {
    for (Nanoseconds t{}; t < span; t += kTick) {
      bus_.run_once(0ms);
      const Nanoseconds now = clock_.now();
      if (ecu_io_) ecu_io_->pump(Nanoseconds::zero());
      if (tc_) tc_->pump(now);
      can_frame frame{};
      while (probe_.read(frame) == ReadOutcome::kFrame) {
        seen_.push_back({now, decode_id(frame.can_id & CAN_EFF_MASK), frame});
      }
      if (ecu_io_ && (now - loop_start_) % 50ms == Nanoseconds::zero()) {
        ecu_.step(0.05);
        ecu_io_->after_step(ecu_.status());
      }
      clock_.advance(kTick);
    }
  }

  void inject(std::uint32_t pgn, std::uint8_t destination, std::uint8_t source, const std::uint8_t* data,
              std::uint8_t length, std::uint8_t priority = 6) {
    ASSERT_TRUE(probe_.send(make_frame(encode_id({priority, pgn, destination, source}), data, length)));
  }
  // The TC's NACK of the ECU's process data (ISO 11783-3 acknowledgement, as an independent TC server sends
  // to a client whose working set it does not know).
  void tc_nacks_the_ecu() {
    const std::uint8_t nack[8] = {1, 0xFF, 0xFF, 0xFF, kEcu, 0x00, 0xCB, 0x00};
    // From the TC's own port: the TC is the partner, and the relay does not echo to the sender.
    ASSERT_TRUE(tc_->port.send(make_frame(encode_id({6, kAcknowledgementPgn, kEcu, kTcAddress}), nack, 8)));
  }

  double mass_flow() const { return ecu_.status().mass_flow_kg_s; }
  const CanEcuProcessor& processor() { return ecu_io_->processor(); }
  bool fault_active(Fault fault) const { return (ecu_.status().fault_codes & fault_bit(fault)) != 0; }

  // Frames from `source` with `pgn` seen at or after `from`.
  std::vector<Seen> seen(std::uint32_t pgn, std::uint8_t source, Nanoseconds from = Nanoseconds::zero()) const {
    std::vector<Seen> out;
    for (const Seen& s : seen_) {
      if (s.id.pgn == pgn && s.id.source == source && s.time >= from) out.push_back(s);
    }
    return out;
  }

  std::string dir_;
  CanBusRelay bus_;
  ManualClock clock_;
  Nanoseconds loop_start_{};
  testing::AnalyticPredictor predictor_;
  Ecu ecu_;
  CanFramePort probe_;
  CanFramePort ecu_port_;
  std::optional<CanPortIo> ecu_io_;
  std::optional<TcNode> tc_;
  std::vector<Seen> seen_;
};

// The ECU's claim after `from`, if any, and how long after `from` it came.
std::optional<Nanoseconds> claim_delay(const std::vector<Seen>& claims, Nanoseconds from) {
  for (const Seen& s : claims) {
    if (s.time >= from) return s.time - from;
  }
  return std::nullopt;
}

// ISO 11783-3 response time Tr: an answer to a request goes out within 200 ms.
constexpr Nanoseconds kResponseTime = 200ms;

// The task controller is on the bus first, as on a tractor whose terminal is powered before the implement
// is plugged in (0.5 to 5 s before the ECU). The ECU claims, asks everyone for their claim and answers its
// own global request at once (an independent TC server drops every node that has not claimed within 0.75 s
// of a global request, the requester included), answers a later request for the claim, global or to its
// address, connects, and meters on the TC's set-points.
class TaskControllerFirst : public IsobusSession, public ::testing::WithParamInterface<int> {};

TEST_P(TaskControllerFirst, TheEcuClaimsAnswersRequestsConnectsAndMeters) {
  start_tc();
  run(std::chrono::milliseconds(GetParam()));
  ASSERT_TRUE(tc_->network.has_address());
  const Nanoseconds ecu_start = clock_.now();
  start_ecu();
  run(1s);
  // The ECU's own global request for the address claim, once its claim stood, and its claim right after.
  std::optional<Nanoseconds> own_request;
  for (const Seen& s : seen(kRequestPgn, kEcu, ecu_start)) {
    if (request_pgn(s.frame) == iso::kAddressClaimedPgn && s.id.destination == kGlobalAddress) own_request = s.time;
  }
  ASSERT_TRUE(own_request) << "the ECU asked nobody for their claim";
  const auto answered = claim_delay(seen(iso::kAddressClaimedPgn, kEcu), *own_request);
  ASSERT_TRUE(answered) << "the ECU did not answer its own global request";
  EXPECT_LE(*answered, kResponseTime);
  // Another node's requests, global and to the ECU's address: each answered with the claim within Tr.
  for (const std::uint8_t destination : {kGlobalAddress, kEcu}) {
    const std::uint8_t request[3] = {0x00, 0xEE, 0x00};
    const Nanoseconds asked = clock_.now();
    inject(kRequestPgn, destination, kProbe, request, 3);
    run(300ms);
    const auto delay = claim_delay(seen(iso::kAddressClaimedPgn, kEcu), asked);
    ASSERT_TRUE(delay) << "no claim in answer to a request to " << int{destination};
    EXPECT_LE(*delay, kResponseTime);
  }
  run(7s);
  EXPECT_EQ(tc_->activations, 1);
  ASSERT_TRUE(tc_->server.client_address());
  EXPECT_EQ(*tc_->server.client_address(), kEcu);
  // Sections 1-4 of 8 on 24 m at 3 m/s and 250 kg/ha: the left disc spreads 12 m, the right one is shut.
  EXPECT_NEAR(mass_flow(), 0.9, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(StartDelays, TaskControllerFirst, ::testing::Values(500, 1300, 2700, 5000),
                         [](const ::testing::TestParamInfo<int>& delay) { return std::to_string(delay.param) + "ms"; });

// A session in which the ECU meters on the TC's set-points: the starting point of the sessions below.
class MeteringSession : public IsobusSession {
 protected:
  void SetUp() override {
    start_tc();
    run(1s);
    start_ecu(settings());
    run(7s);
    ASSERT_EQ(tc_->activations, 1);
    ASSERT_NEAR(mass_flow(), 0.9, 1e-6);
  }
  virtual CanEcuSettings settings() const { return {}; }

  // How many of the ECU's frames since `from` went out before its working-set master message: process
  // data from an address the TC does not know its working set by (must be none).
  int process_data_before_working_set_master(Nanoseconds from) {
    int count = 0;
    for (const Seen& s : seen_) {
      if (s.time < from || s.id.source == kGlobalAddress || s.id.source >= kNullAddress) continue;
      if (s.id.pgn == iso::kWorkingSetMasterPgn && s.id.source == ecu_address()) return count;
      if (s.id.pgn == kProcessDataPgn && s.id.source == ecu_address()) ++count;
    }
    return -1;  // no working-set master message at all
  }
  std::uint8_t ecu_address() { return ecu_io_->processor().network().address(); }
};

// A NACK storm: the TC drops the ECU's session and answers its process data with NACKs (ISO 11783-3), ten a
// second for 3 s, while its status goes on. Metering stops at once as on TC loss (work state off,
// task_controller_lost), the storm ends one session only, and the ECU reconnects by itself: working-set
// master, pool check, activation, then the TC's set-points again.
TEST_F(MeteringSession, NackStormStopsMeteringAndTheWorkingSetReconnects) {
  const Nanoseconds storm = clock_.now();
  for (int i = 0; i < 30; ++i) {
    tc_nacks_the_ecu();
    run(100ms);
    if (i == 0) {
      EXPECT_EQ(mass_flow(), 0.0) << "metering goes on after the TC refused the ECU";
      EXPECT_FALSE(ecu_.status().work_state_setpoint);
      EXPECT_TRUE(fault_active(Fault::kTaskControllerLost));
    }
  }
  EXPECT_EQ(processor().counters().tc_refusals, 30u);
  EXPECT_EQ(mass_flow(), 0.0);
  EXPECT_EQ(seen(iso::kWorkingSetMasterPgn, kEcu, storm).size(), 0u) << "no reconnection during the storm's first 3 s";
  run(12s);
  EXPECT_EQ(seen(iso::kWorkingSetMasterPgn, kEcu, storm).size(), 1u) << "one reconnection for the whole storm";
  EXPECT_EQ(processor().task_controller_client().connections(), 2u);
  EXPECT_EQ(tc_->activations, 2);
  EXPECT_NEAR(mass_flow(), 0.9, 1e-6) << "the TC's set-points apply again after the reconnection";
}

// One claim carrying the ECU's own NAME from another address: the ECU contends (its claim again) and keeps
// metering. A second within 2 s (a second unit with its NAME): it gives up its address for 3 s (metering
// closed, no_bus_address), then claims again by itself and restarts its working set before any process
// data.
TEST_F(MeteringSession, OwnNameFromAnotherAddressIsContendedThenHeldOffNeverSilencedForGood) {
  const auto own = iso::name_to_bytes(CanEcuSettings{}.name);
  const Nanoseconds first = clock_.now();
  inject(iso::kAddressClaimedPgn, kGlobalAddress, 0x95, own.data(), 8);
  run(100ms);
  EXPECT_EQ(seen(iso::kAddressClaimedPgn, kEcu, first).size(), 1u) << "the ECU contends with its claim";
  EXPECT_TRUE(processor().has_address());
  EXPECT_NEAR(mass_flow(), 0.9, 1e-6) << "one stray frame does not stop the machine";
  run(400ms);
  const Nanoseconds second = clock_.now();
  inject(iso::kAddressClaimedPgn, kGlobalAddress, 0x95, own.data(), 8);
  run(300ms);
  EXPECT_FALSE(processor().has_address());
  EXPECT_EQ(mass_flow(), 0.0);
  EXPECT_TRUE(fault_active(Fault::kNoBusAddress));
  EXPECT_EQ(seen(iso::kAddressClaimedPgn, kNullAddress, second).size(), 1u) << "cannot-claim";
  run(3s);
  ASSERT_TRUE(processor().has_address()) << "claimed again after the 3 s hold-off";
  EXPECT_EQ(ecu_address(), kEcu);
  EXPECT_EQ(process_data_before_working_set_master(second), 0);
  run(8s);
  EXPECT_EQ(tc_->activations, 2);
  EXPECT_NEAR(mass_flow(), 0.9, 1e-6);
  // A second episode holds off 6 s, longer than the TC's 6 s supervision: the ECU keeps listening to the
  // TC's status meanwhile, so it comes back to the same partner and reconnects at once.
  inject(iso::kAddressClaimedPgn, kGlobalAddress, 0x95, own.data(), 8);
  run(200ms);
  inject(iso::kAddressClaimedPgn, kGlobalAddress, 0x95, own.data(), 8);
  run(300ms);
  EXPECT_FALSE(processor().has_address());
  run(6s);
  ASSERT_TRUE(processor().has_address());
  run(3s);
  EXPECT_EQ(processor().task_controller_partner().counters().partners_lost, 0u);
  EXPECT_EQ(tc_->activations, 3);
  EXPECT_NEAR(mass_flow(), 0.9, 1e-6);
}

// A self-configurable ECU whose address a lower NAME claims moves to the next free address (ISO 11783-5),
// stops metering meanwhile, and restarts its working set from the new address: working-set master before
// any process data, then the pool and activation; the TC, which knows its client by NAME, takes it there.
class SelfConfigurableSession : public MeteringSession {
 protected:
  CanEcuSettings settings() const override {
    CanEcuSettings s;
    iso::IsoName n;
    n.self_configurable = true;
    s.name = iso::encode_name(n);
    return s;
  }
};

TEST_F(SelfConfigurableSession, MovesAndRestartsItsWorkingSetFromTheNewAddress) {
  iso::IsoName lower;  // a lower NAME than the ECU's: not self-configurable, identity 1
  lower.identity_number = 1;
  const auto bytes = iso::name_to_bytes(iso::encode_name(lower));
  const Nanoseconds taken = clock_.now();
  inject(iso::kAddressClaimedPgn, kGlobalAddress, kEcu, bytes.data(), 8);
  run(100ms);
  EXPECT_EQ(mass_flow(), 0.0) << "no metering while the ECU has no standing claim";
  EXPECT_FALSE(ecu_.status().work_state_setpoint);
  run(500ms);
  ASSERT_TRUE(processor().has_address());
  EXPECT_NE(ecu_address(), kEcu);
  EXPECT_EQ(process_data_before_working_set_master(taken), 0);
  run(8s);
  ASSERT_TRUE(tc_->server.client_address());
  EXPECT_EQ(*tc_->server.client_address(), ecu_address());
  EXPECT_EQ(tc_->activations, 2);
  EXPECT_NEAR(mass_flow(), 0.9, 1e-6);
}

// A CAN-only machine with a launch table but no product chosen yet: a border (or a narrowed side, or wind
// compensation) cannot be planned, so the TC's command is refused with PDACK 0x80 and the ECU's DM1 carries
// unknown_material, never acknowledged to do nothing. The TC then chooses the product over the bus (DDI
// 57349 = the number of a product the pool lists), and the same command is taken.
class ProductSession : public IsobusSession {
 protected:
  ProductSession() : IsobusSession(true) {}
};

TEST_F(ProductSession, CommandsThatNeedTheProductAreRefusedUntilTheTcChoosesOne) {
  start_tc();
  run(1s);
  start_ecu();
  run(7s);
  ASSERT_EQ(tc_->activations, 1);
  ASSERT_TRUE(ecu_.status().material.empty());
  const Nanoseconds asked = clock_.now();
  ASSERT_EQ(tc_->server.set_value(57344, 1), "");  // left border
  run(100ms);
  EXPECT_EQ(ecu_.status().border_mode, BorderMode::kOff);
  EXPECT_EQ(tc_->server.counters().pdack_errors, 1u);
  int pdack_out_of_range = 0;
  for (const Seen& s : seen(kProcessDataPgn, kEcu, asked)) {
    if ((s.frame.data[0] & 0x0F) == 0xD && s.frame.data[2] == 0x00 && s.frame.data[3] == 0xE0) {
      pdack_out_of_range += s.frame.data[4] == 0x80 ? 1 : 0;
    }
  }
  EXPECT_EQ(pdack_out_of_range, 1) << "PDACK 0x80 (outside the operational range) for DDI 57344";
  run(1100ms);
  bool dm1_names_it = false;
  for (const Seen& s : seen(iso::kDm1Pgn, kEcu, asked)) {
    const auto dm1 = iso::decode_dm1(std::span<const std::uint8_t>(s.frame.data, 6));
    if (!dm1) continue;
    for (const iso::Dtc& d : dm1->active) {
      dm1_names_it = dm1_names_it || d.spn == iso::kProprietarySpnBase + static_cast<std::uint32_t>(Fault::kUnknownMaterial);
    }
  }
  EXPECT_TRUE(dm1_names_it) << "DM1 carries unknown_material";
  // The TC chooses product 1 of the pool's list, then asks for the border again: taken.
  ASSERT_EQ(tc_->server.set_value(57349, 1), "");
  run(100ms);
  EXPECT_EQ(ecu_.status().material, "urea");
  ASSERT_EQ(tc_->server.set_value(57344, 1), "");
  run(100ms);
  EXPECT_EQ(ecu_.status().border_mode, BorderMode::kLeftBorder);
  EXPECT_EQ(tc_->server.counters().pdack_errors, 1u);
  // A product the pool does not list is refused too.
  ASSERT_EQ(tc_->server.set_value(57349, 3), "");
  run(100ms);
  EXPECT_EQ(tc_->server.counters().pdack_errors, 2u);
  EXPECT_EQ(ecu_.status().material, "urea");
}

// The sections of the pool the TC holds: width (DDI 67) and Y offset (DDI 135) of each, in mm.
std::vector<std::pair<std::int32_t, std::int32_t>> pool_sections(const iso::Ddop& pool) {
  std::map<std::uint16_t, const iso::DeviceProperty*> properties;
  for (const iso::DdopObject& o : pool.objects) {
    if (const auto* p = std::get_if<iso::DeviceProperty>(&o)) properties[p->id] = p;
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> out;
  for (const iso::DdopObject& o : pool.objects) {
    const auto* e = std::get_if<iso::DeviceElement>(&o);
    if (e == nullptr || e->type != iso::ElementType::kSection) continue;
    std::int32_t width = -1;
    std::int32_t y = 0;
    for (const std::uint16_t id : e->children) {
      const auto it = properties.find(id);
      if (it == properties.end()) continue;
      if (it->second->ddi == 67) width = it->second->value;
      if (it->second->ddi == 135) y = it->second->value;
    }
    out.emplace_back(width, y);
  }
  return out;
}

// The pool describes the machine as set (ISO 11783-10): the TC sets 12 m, and the ECU replaces its 24 m
// pool (deactivate, transfer, activate) with 8 sections of 1.5 m at -5.25 ... +5.25 m; the TC sets 24 m, and
// the pool goes back to 8 × 3 m at -10.5 ... +10.5 m. Each time the TC activates it again and sends its
// set-points; metering follows the width set.
TEST_F(IsobusSession, ThePoolFollowsTheWorkingWidthTheTcSets) {
  start_tc();
  tc_->width_mm = 12000;
  run(1s);
  start_ecu();
  run(7s);
  ASSERT_TRUE(tc_->server.pool());
  auto sections = pool_sections(*tc_->server.pool());
  ASSERT_EQ(sections.size(), 8u);
  for (std::size_t i = 0; i < sections.size(); ++i) {
    EXPECT_EQ(sections[i].first, 1500) << "section " << i + 1;
    EXPECT_EQ(sections[i].second, -5250 + 1500 * static_cast<std::int32_t>(i)) << "section " << i + 1;
  }
  EXPECT_EQ(tc_->activations, 2) << "the 24 m pool activated, then the 12 m one";
  EXPECT_EQ(processor().task_controller_client().pool_changes(), 1u);
  EXPECT_NEAR(mass_flow(), 0.45, 1e-6) << "sections 1-4 of 12 m at 3 m/s and 250 kg/ha";
  // The operator sets 24 m.
  tc_->width_mm = 24000;
  ASSERT_EQ(tc_->server.set_value(66, 24000), "");
  run(3s);
  sections = pool_sections(*tc_->server.pool());
  ASSERT_EQ(sections.size(), 8u);
  EXPECT_EQ(sections.front(), std::make_pair(3000, -10500));
  EXPECT_EQ(sections.back(), std::make_pair(3000, 10500));
  EXPECT_EQ(tc_->activations, 3);
  EXPECT_EQ(processor().task_controller_client().pool_changes(), 2u);
  EXPECT_NEAR(mass_flow(), 0.9, 1e-6);
}

}  // namespace
}  // namespace spread::firmware::can
