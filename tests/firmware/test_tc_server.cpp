// The task-controller server (ISO 11783-10) against a hand-driven client: the connection sequence, the
// pool transfer by TP, a refused pool, activation, process data and the as-applied log, supervision of
// the client task message, and malformed input.
#include <gtest/gtest.h>

#include <algorithm>

#include "firmware_sim/can/spreader_ddop.hpp"
#include "isobus/ddi.hpp"
#include "isobus/process_data.hpp"
#include "isobus/tc_client.hpp"
#include "isobus/tc_server.hpp"
#include "tools/spread_tractor/section_pattern.hpp"

namespace spread::firmware::can {
namespace {

using namespace isobus;

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr std::uint8_t kTc = 0xF7;
constexpr std::uint8_t kClient = 0x80;

std::vector<std::uint8_t> spreader_pool(int sections = 8) {
  SpreaderDescription d;
  d.section_count = sections;
  d.name = 0xA00A8000001234ull;
  return write_ddop(make_spreader_ddop(d));
}

// The client end: its transport for the pool, and everything the TC sent to it or to all.
struct Harness {
  TcServer tc;
  TransportProtocol client_tp{kClient};
  Nanoseconds now{};
  std::vector<TransportFrame> to_client;  // TC frames on PGN 0xCB00 (TP frames are consumed here)
  std::vector<TransportFrame> from_tc;    // every frame the TC sent, transport ones included, in order

  Harness() { tc.start(kTc, now); pump(); }

  void pump() {
    for (int round = 0; round < 1000; ++round) {
      bool moved = false;
      for (const TransportFrame& f : tc.take_frames()) {
        moved = true;
        from_tc.push_back(f);
        if (f.pgn == kTcProcessDataPgn) {
          to_client.push_back(f);
        } else {
          client_tp.handle_frame(f, now);
        }
      }
      for (const TransportFrame& f : client_tp.take_frames()) {
        moved = true;
        tc.handle_frame(f.pgn, f.source, f.destination, f.data, now);
      }
      if (!moved) return;
    }
    FAIL() << "frames still moving after 1000 rounds";
  }
  void send(const TcFrame& data, std::uint32_t pgn = kTcProcessDataPgn, std::uint8_t dst = kTc) {
    tc.handle_frame(pgn, kClient, dst, data, now);
    pump();
  }
  void advance(Nanoseconds by, Nanoseconds step = milliseconds(100)) {
    for (Nanoseconds t{}; t < by; t += step) {
      now += step;
      tc.update(now);
      client_tp.update(now);
      pump();
    }
  }
  // The last frame the TC addressed to the client with this first byte.
  std::optional<TcFrame> last(std::uint8_t first_byte) const {
    for (auto it = to_client.rbegin(); it != to_client.rend(); ++it) {
      if (it->destination == kClient && it->data[0] == first_byte) return it->data;
    }
    return std::nullopt;
  }
  void transfer(const std::vector<std::uint8_t>& pool) {
    send(encode_request_pool_transfer(static_cast<std::uint32_t>(pool.size())));
    ASSERT_TRUE(last(0x51));
    ASSERT_EQ((*last(0x51))[1], 0);
    ASSERT_TRUE(client_tp.send({kTcProcessDataPgn, kClient, kTc, encode_pool_transfer(pool)}, now));
    pump();
  }
  // Where in from_tc the TC's end-of-message acknowledgement (TP.CM 19 / ETP.CM 23) and its object-pool
  // transfer response (0x71) stand; -1 when absent.
  std::pair<int, int> eoma_and_pool_response() const {
    int eoma = -1;
    int response = -1;
    for (std::size_t i = 0; i < from_tc.size(); ++i) {
      const TransportFrame& f = from_tc[i];
      if (f.destination != kClient) continue;
      if ((f.pgn == kTpConnectionManagementPgn && f.data[0] == 19) ||
          (f.pgn == kEtpConnectionManagementPgn && f.data[0] == 23)) {
        eoma = static_cast<int>(i);
      }
      if (f.pgn == kTcProcessDataPgn && f.data[0] == 0x71) response = static_cast<int>(i);
    }
    return {eoma, response};
  }
  void answer_version(std::uint8_t version) {
    TcVersion v;
    v.version = version;
    v.sections = 8;
    send(encode_version(v));
  }
  void connect(const std::vector<std::uint8_t>& pool) {
    send(encode_working_set_master(), kWorkingSetMasterPgn, 0xFF);
    send(tc_frame(TcMessage::kRequestVersion));
    send(tc_frame(TcMessage::kRequestStructureLabel));
    transfer(pool);
    send(encode_activate(true));
  }
  std::vector<can::ProcessData> process_data_to_client() const {
    std::vector<can::ProcessData> out;
    for (const auto& f : to_client) {
      const std::uint8_t cmd = f.data[0] & 0x0F;
      if (f.destination == kClient && (cmd == 0x2 || cmd == 0x3)) out.push_back(can::decode_process_data(f.data));
    }
    return out;
  }
};

TEST(TcServer, BroadcastsItsStatusEveryTwoSeconds) {
  Harness h;
  h.advance(seconds(5));
  int status = 0;
  for (const auto& f : h.to_client) {
    if (f.data[0] == 0xFE && f.destination == 0xFF && f.source == kTc) ++status;
  }
  EXPECT_EQ(status, 3);  // t = 0, 2, 4 s
  EXPECT_EQ(h.to_client.front().data[4], 0x01);  // task active
  EXPECT_EQ(h.tc.state(), TcConnectionState::kNone);
}

TEST(TcServer, ConnectsTransfersParsesAndActivatesThePool) {
  Harness h;
  h.send(encode_working_set_master(), kWorkingSetMasterPgn, 0xFF);
  EXPECT_EQ(h.tc.client_address(), kClient);
  h.send(tc_frame(TcMessage::kRequestVersion));
  ASSERT_TRUE(h.last(0x10));
  EXPECT_EQ((*h.last(0x10))[1], TcServerConfig{}.version.version);
  ASSERT_TRUE(h.last(0x00));  // the TC asks for the client's version in turn
  TcVersion client_version;
  client_version.sections = 8;
  h.send(encode_version(client_version));
  ASSERT_TRUE(h.tc.client_version());
  EXPECT_EQ(h.tc.client_version()->sections, 8);

  h.send(tc_frame(TcMessage::kRequestStructureLabel));
  ASSERT_TRUE(h.last(0x11));
  for (int i = 1; i < 8; ++i) EXPECT_EQ((*h.last(0x11))[static_cast<std::size_t>(i)], 0xFF);  // no pool held
  h.send(tc_frame(TcMessage::kRequestLocalizationLabel));
  ASSERT_TRUE(h.last(0x31));

  const auto pool = spreader_pool();
  h.transfer(pool);
  ASSERT_TRUE(h.last(0x71));
  const TcFrame answer = *h.last(0x71);
  EXPECT_EQ(answer[1], 0);
  const std::uint32_t received = answer[2] | (answer[3] << 8) | (answer[4] << 16) | (std::uint32_t{answer[5]} << 24);
  EXPECT_EQ(received, pool.size());
  EXPECT_EQ(h.tc.counters().pools_accepted, 1u);

  EXPECT_FALSE(h.tc.active());
  EXPECT_NE(h.tc.set_value(6, 25000), "");  // not active yet: refused
  h.send(encode_activate(true));
  ASSERT_TRUE(h.last(0x91));
  EXPECT_EQ((*h.last(0x91))[1], 0);
  EXPECT_TRUE(h.tc.active());

  // Element numbers come from the pool, and agree with the spreader's own table.
  for (const int ddi_number : {6, 7, 66, 67, 70, 141, 161, 289, 290, 389, 390, 397}) {
    const auto ddi = static_cast<std::uint16_t>(ddi_number);
    const auto elements = h.tc.elements_for_ddi(ddi);
    ASSERT_FALSE(elements.empty()) << "DDI " << ddi;
    EXPECT_EQ(elements.front(), *element_for_ddi(ddi)) << "DDI " << ddi;
  }
  EXPECT_EQ(h.tc.section_elements().size(), 8u);
  EXPECT_EQ(h.tc.section_elements().front(), 4);
}

// ISO 11783-3 §5.10.3.3 (TP) / ISO 11783-6 (ETP): the message is the receiver's only once its transport
// session is over, so the TC answers the object-pool transfer (ISO 11783-10) after its own
// end-of-message acknowledgement; a client that gets the answer while its session is still open takes it
// for a protocol error. Checked for a pool by TP, one by ETP, and a refused pool.
TEST(TcServer, PoolTransferIsAnsweredAfterTheTransportsEndOfMessageAcknowledgement) {
  for (const int sections : {8, 16}) {
    Harness h;
    h.send(encode_working_set_master(), kWorkingSetMasterPgn, 0xFF);
    h.send(tc_frame(TcMessage::kRequestVersion));
    const auto pool = spreader_pool(sections);
    ASSERT_EQ(pool.size() > kTpMaxBytes, sections == 16) << pool.size() << " bytes";
    h.transfer(pool);
    const auto [eoma, response] = h.eoma_and_pool_response();
    ASSERT_GE(eoma, 0) << sections << " sections: no end-of-message acknowledgement";
    ASSERT_GE(response, 0) << sections << " sections: no pool transfer response";
    EXPECT_LT(eoma, response) << sections << " sections: the pool was answered inside its transport session";
    EXPECT_EQ((*h.last(0x71))[1], 0);
  }
  Harness refused;
  refused.send(encode_working_set_master(), kWorkingSetMasterPgn, 0xFF);
  refused.send(tc_frame(TcMessage::kRequestVersion));
  auto corrupt = spreader_pool();
  corrupt[0] = 'X';
  refused.transfer(corrupt);
  const auto [eoma, response] = refused.eoma_and_pool_response();
  ASSERT_GE(eoma, 0);
  ASSERT_GE(response, 0);
  EXPECT_LT(eoma, response);
  EXPECT_EQ((*refused.last(0x71))[1], 0x01);
}

// ISO 11783-10: the pool follows the lower of the two versions; the version-4 device object adds the
// extended structure label. A client that answers version 3 sends its pool without it, one that answers
// 4 with it, and the TC reads each at that version; a TC of version 3 reads a version-3 pool.
TEST(TcServer, ReadsVersion3AndVersion4PoolsAtTheNegotiatedVersion) {
  SpreaderDescription d;
  d.section_count = 8;
  d.name = 0xA00A8000001234ull;
  const Ddop spreader = make_spreader_ddop(d);
  const auto objects = [](const TcServer& tc) { return tc.pool() ? tc.pool()->objects.size() : 0u; };
  for (const std::uint8_t version : {std::uint8_t{3}, std::uint8_t{4}}) {
    Harness h;
    h.send(encode_working_set_master(), kWorkingSetMasterPgn, 0xFF);
    h.send(tc_frame(TcMessage::kRequestVersion));
    h.answer_version(version);
    h.transfer(write_ddop(spreader, version));
    ASSERT_TRUE(h.last(0x71));
    EXPECT_EQ((*h.last(0x71))[1], 0) << "version " << int{version};
    EXPECT_EQ(objects(h.tc), spreader.objects.size()) << "version " << int{version};
    h.send(encode_activate(true));
    EXPECT_TRUE(h.tc.active()) << "version " << int{version};
  }
  // The other version's layout is refused: the version decides how the device object is read.
  Harness mismatch;
  mismatch.send(encode_working_set_master(), kWorkingSetMasterPgn, 0xFF);
  mismatch.send(tc_frame(TcMessage::kRequestVersion));
  mismatch.answer_version(3);
  mismatch.transfer(write_ddop(spreader, 4));
  EXPECT_EQ((*mismatch.last(0x71))[1], 0x01);

  TcServerConfig version3;
  version3.version.version = 3;
  Harness old_tc;
  old_tc.tc = TcServer(version3);
  old_tc.tc.start(kTc, old_tc.now);
  old_tc.send(encode_working_set_master(), kWorkingSetMasterPgn, 0xFF);
  old_tc.send(tc_frame(TcMessage::kRequestVersion));
  old_tc.answer_version(4);
  old_tc.transfer(write_ddop(spreader, 3));
  EXPECT_EQ((*old_tc.last(0x71))[1], 0);
  EXPECT_EQ(objects(old_tc.tc), spreader.objects.size());
}

TEST(TcServer, SetValuesGoToThePoolsElementsAndReportedValuesAreLogged) {
  Harness h;
  h.connect(spreader_pool());
  ASSERT_TRUE(h.tc.active());
  EXPECT_EQ(h.tc.set_value(static_cast<std::uint16_t>(can::Ddi::kSetpointCondensedWorkState1_16), 0xFF55), "");
  EXPECT_EQ(h.tc.request_value(static_cast<std::uint16_t>(can::Ddi::kActualMassPerArea)), "");
  EXPECT_NE(h.tc.set_value(4242, 1), "");  // no such DDI in the pool
  h.pump();
  const auto sent = h.process_data_to_client();
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].command, 0x3);
  EXPECT_EQ(sent[0].element, 1);  // boom
  EXPECT_EQ(sent[0].ddi, 290);
  EXPECT_EQ(sent[0].value, 0xFF55);
  EXPECT_EQ(sent[1].command, 0x2);
  EXPECT_EQ(sent[1].element, 2);  // bin
  EXPECT_EQ(sent[1].ddi, 7);

  h.advance(milliseconds(300));
  const auto value = can::encode_process_data({0x3, 2, 7, 25000});
  h.tc.handle_frame(kTcProcessDataPgn, kClient, kTc, value, h.now);
  const auto log = h.tc.take_as_applied();
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(log[0].time, h.now);
  EXPECT_EQ(log[0].element, 2);
  EXPECT_EQ(log[0].ddi, 7);
  EXPECT_EQ(log[0].value, 25000);

  // A PDACK with error bits is counted and explained.
  const auto pdack = can::encode_pdack({0x3, 1, 290, 0}, can::kPdackValueOutOfRange);
  h.tc.handle_frame(kTcProcessDataPgn, kClient, kTc, pdack, h.now);
  EXPECT_EQ(h.tc.counters().pdack_errors, 1u);
}

TEST(TcServer, CorruptPoolIsRefusedWithTheReasonAndCannotBeActivated) {
  Harness h;
  h.send(encode_working_set_master(), kWorkingSetMasterPgn, 0xFF);
  h.send(tc_frame(TcMessage::kRequestVersion));
  auto pool = spreader_pool();
  pool[0] = 'X';  // the DVC tag
  h.transfer(pool);
  ASSERT_TRUE(h.last(0x71));
  EXPECT_EQ((*h.last(0x71))[1], 0x01);  // bit 0: error in the pool
  EXPECT_EQ(h.tc.counters().pools_refused, 1u);
  const auto events = h.tc.take_events();
  EXPECT_TRUE(std::any_of(events.begin(), events.end(),
                          [](const std::string& e) { return e.find("refused") != std::string::npos; }));
  h.send(encode_activate(true));
  ASSERT_TRUE(h.last(0x91));
  EXPECT_EQ((*h.last(0x91))[1], 0x01);
  EXPECT_FALSE(h.tc.active());

  // Truncated pools (a transfer cut short by the client) are refused the same way, never read past.
  for (std::size_t cut : {std::size_t{9}, std::size_t{100}, std::size_t{777}}) {
    auto truncated = spreader_pool();
    truncated.resize(cut);
    h.transfer(truncated);
    ASSERT_TRUE(h.last(0x71));
    EXPECT_EQ((*h.last(0x71))[1], 0x01) << cut;
  }
  EXPECT_FALSE(h.tc.pool());

  // Single-byte corruptions anywhere in the pool: each is answered (accepted when the byte is only a
  // value, refused otherwise), and an accepted pool still indexes without reading outside it.
  std::uint32_t seed = 7;
  const auto good = spreader_pool();
  for (int i = 0; i < 300; ++i) {
    seed = seed * 1664525u + 1013904223u;
    auto mutated = good;
    mutated[seed % mutated.size()] ^= static_cast<std::uint8_t>(1u + ((seed >> 16) % 255u));
    h.to_client.clear();
    h.transfer(mutated);
    ASSERT_TRUE(h.last(0x71)) << i;
    const bool accepted = (*h.last(0x71))[1] == 0;
    EXPECT_EQ(accepted, h.tc.pool().has_value()) << i;
  }
}

TEST(TcServer, OversizedPoolTransferRequestIsRefused) {
  TcServerConfig config;
  config.max_pool_bytes = 100;
  Harness h;
  h.tc = TcServer(config);
  h.tc.start(kTc, h.now);
  h.send(tc_frame(TcMessage::kRequestVersion));
  h.send(encode_request_pool_transfer(101));
  ASSERT_TRUE(h.last(0x51));
  EXPECT_EQ((*h.last(0x51))[1], 1);
  h.send(encode_request_pool_transfer(100));
  EXPECT_EQ((*h.last(0x51))[1], 0);
}

TEST(TcServer, SilentClientIsDroppedAndReconnectsWithItsHeldPool) {
  Harness h;
  const auto pool = spreader_pool();
  h.connect(pool);
  ASSERT_TRUE(h.tc.active());
  // The client task message every 2 s keeps it.
  for (int i = 0; i < 5; ++i) {
    h.send(encode_client_task(true));
    h.advance(seconds(2));
  }
  EXPECT_TRUE(h.tc.active());
  // Process data alone does not: only the client task message proves the client's task loop runs.
  for (int i = 0; i < 70; ++i) {
    h.tc.handle_frame(kTcProcessDataPgn, kClient, kTc, can::encode_process_data({0x3, 0, 141, 1}), h.now);
    h.advance(milliseconds(100));
  }
  EXPECT_FALSE(h.tc.active());
  EXPECT_EQ(h.tc.state(), TcConnectionState::kNone);
  EXPECT_EQ(h.tc.counters().client_timeouts, 1u);
  EXPECT_NE(h.tc.set_value(6, 1), "");

  // It comes back: the structure label now names the held pool, so it activates without a transfer.
  h.send(encode_working_set_master(), kWorkingSetMasterPgn, 0xFF);
  h.send(tc_frame(TcMessage::kRequestStructureLabel));
  const auto parsed = parse_ddop(pool);
  ASSERT_TRUE(parsed.pool);
  const auto& dvc = std::get<DeviceObject>(parsed.pool->objects.front());
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ((*h.last(0x11))[static_cast<std::size_t>(i + 1)], dvc.structure_label[static_cast<std::size_t>(i)]);
  }
  h.send(encode_activate(true));
  EXPECT_EQ((*h.last(0x91))[1], 0);
  EXPECT_TRUE(h.tc.active());
  EXPECT_EQ(h.tc.counters().pools_accepted, 1u);
}

TEST(TcServer, ClientThatStallsWhileConnectingIsDropped) {
  Harness h;
  h.send(tc_frame(TcMessage::kRequestVersion));
  EXPECT_EQ(h.tc.state(), TcConnectionState::kConnecting);
  h.advance(milliseconds(6100));
  EXPECT_EQ(h.tc.state(), TcConnectionState::kNone);
  // A second node may connect now.
  h.tc.handle_frame(kTcProcessDataPgn, 0x90, kTc, tc_frame(TcMessage::kRequestVersion), h.now);
  EXPECT_EQ(h.tc.client_address(), 0x90);
}

TEST(TcServer, OneClientAtATime) {
  Harness h;
  h.send(tc_frame(TcMessage::kRequestVersion));
  h.tc.handle_frame(kTcProcessDataPgn, 0x90, kTc, tc_frame(TcMessage::kRequestVersion), h.now);
  EXPECT_EQ(h.tc.client_address(), kClient);
  EXPECT_EQ(h.tc.counters().other_clients_ignored, 1u);
}

TEST(TcServer, MalformedFramesAreCountedNeverCrash) {
  Harness h;
  const std::uint8_t short_frame[3] = {0x00, 0xFF, 0xFF};
  h.tc.handle_frame(kTcProcessDataPgn, kClient, kTc, short_frame, h.now);
  h.tc.handle_frame(kTpConnectionManagementPgn, kClient, kTc, short_frame, h.now);
  h.tc.handle_frame(kWorkingSetMasterPgn, kClient, 0xFF, std::span<const std::uint8_t>{}, h.now);
  TcFrame unknown = tc_frame(TcMessage::kRequestVersion);
  unknown[0] = 0xA1;  // delete object pool: not supported
  h.tc.handle_frame(kTcProcessDataPgn, kClient, kTc, unknown, h.now);
  TcFrame bad_activate = encode_activate(true);
  bad_activate[1] = 0x42;
  h.send(tc_frame(TcMessage::kRequestVersion));
  h.send(bad_activate);
  EXPECT_EQ(h.tc.counters().malformed_frames, 5u);
  EXPECT_FALSE(h.tc.active());
  // Every TP/ETP-looking frame with random bytes: no crash, no pool.
  std::uint32_t seed = 1;
  for (int i = 0; i < 20000; ++i) {
    std::array<std::uint8_t, 8> b{};
    for (auto& x : b) {
      seed = seed * 1664525u + 1013904223u;
      x = static_cast<std::uint8_t>(seed >> 24);
    }
    const std::uint32_t pgns[] = {kTpConnectionManagementPgn, kTpDataTransferPgn, kEtpConnectionManagementPgn,
                                  kEtpDataTransferPgn, kTcProcessDataPgn};
    h.tc.handle_frame(pgns[i % 5], kClient, kTc, b, h.now);
    if (i % 100 == 0) h.advance(milliseconds(100));
  }
  (void)h.tc.take_frames();
  SUCCEED();
}

// Both ends of this code base in one process: the ECU's TC client, its transport, and this server.
TEST(TcServer, ConnectsTheEcusOwnTcClient) {
  SpreaderDescription d;
  d.name = 0xA00A8000001234ull;
  const Ddop ddop = make_spreader_ddop(d);
  const auto& dvc = std::get<DeviceObject>(ddop.objects.front());
  TaskControllerClient client(write_ddop(ddop), dvc.structure_label, dvc.localization_label);
  TcServer tc;
  TransportProtocol client_tp{kClient};
  Nanoseconds now{};
  tc.start(kTc, now);
  auto pump = [&] {
    for (int round = 0; round < 1000; ++round) {
      bool moved = false;
      for (const TransportFrame& f : tc.take_frames()) {
        moved = true;
        if (f.pgn == kTcProcessDataPgn) {
          if (f.destination == kClient || f.destination == 0xFF) client.handle_message(f.source, f.data, now);
        } else {
          client_tp.handle_frame(f, now);
        }
      }
      for (const TcOutgoing& m : client.take_outgoing()) {
        moved = true;
        if (m.data.size() > 8) {
          ASSERT_TRUE(client_tp.send({m.pgn, kClient, m.destination, m.data}, now));
        } else {
          tc.handle_frame(m.pgn, kClient, m.destination, m.data, now);
        }
      }
      for (const TransportFrame& f : client_tp.take_frames()) {
        moved = true;
        tc.handle_frame(f.pgn, f.source, f.destination, f.data, now);
      }
      if (!moved) return;
    }
  };
  for (int i = 0; i < 100 && !client.connected(); ++i) {
    now += milliseconds(100);
    tc.update(now);
    client.update(now);
    client_tp.update(now);
    pump();
  }
  ASSERT_TRUE(client.connected()) << tc_client_state_name(client.state()) << " " << client.last_error();
  EXPECT_TRUE(tc.active());
  EXPECT_EQ(tc.section_elements().size(), 8u);
  // Client task messages keep the connection for a minute.
  for (int i = 0; i < 600; ++i) {
    now += milliseconds(100);
    tc.update(now);
    client.update(now);
    client_tp.update(now);
    pump();
  }
  EXPECT_TRUE(tc.active());
  EXPECT_TRUE(client.connected());
  EXPECT_EQ(tc.counters().client_timeouts, 0u);
}

// The pattern a person types for the TC's section set-point, as DDI 290's 2 bits per section.
TEST(TcServer, SectionPatternBecomesTheCondensedWorkState) {
  using spread::tractor::condensed_work_state_from_pattern;
  // Sections 1-4 on (01), 5-8 off (00), 9-16 not named (11).
  EXPECT_EQ(condensed_work_state_from_pattern("11110000"), static_cast<std::int32_t>(0xFFFF0055u));
  EXPECT_EQ(condensed_work_state_from_pattern("0"), static_cast<std::int32_t>(0xFFFFFFFCu));
  EXPECT_EQ(condensed_work_state_from_pattern("1111111111111111"), static_cast<std::int32_t>(0x55555555u));
  EXPECT_FALSE(condensed_work_state_from_pattern(""));
  EXPECT_FALSE(condensed_work_state_from_pattern("11112"));
  EXPECT_FALSE(condensed_work_state_from_pattern("11111111111111111"));
}

TEST(TcServer, MeasurementCommandsUseOnlyTheTriggersThePoolOffers) {
  Harness h;
  h.connect(spreader_pool());
  ASSERT_TRUE(h.tc.active());
  EXPECT_EQ(h.tc.measure(7, MeasurementCommand::kTimeInterval, 500), "");
  EXPECT_EQ(h.tc.measure(161, MeasurementCommand::kChangeThreshold, 1), "");
  // DDI 161 offers time and on-change triggers only; DDI 6 (a set-point) neither distance nor thresholds.
  EXPECT_NE(h.tc.measure(161, MeasurementCommand::kDistanceInterval, 1000), "");
  EXPECT_NE(h.tc.measure(6, MeasurementCommand::kMinimumThreshold, 0), "");
  EXPECT_NE(h.tc.measure(4242, MeasurementCommand::kTimeInterval, 500), "");
  h.pump();
  std::vector<can::ProcessData> sent;
  for (const auto& f : h.to_client) {
    if (f.destination == kClient && (f.data[0] & 0x0F) >= 0x4 && (f.data[0] & 0x0F) <= 0x8) {
      sent.push_back(can::decode_process_data(f.data));
    }
  }
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].command, 0x4);
  EXPECT_EQ(sent[0].element, 2);
  EXPECT_EQ(sent[0].value, 500);
  EXPECT_EQ(sent[1].command, 0x8);
  EXPECT_EQ(sent[1].element, 1);
  EXPECT_EQ(sent[1].ddi, 161);
}

}  // namespace
}  // namespace spread::firmware::can
