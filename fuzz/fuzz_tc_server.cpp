// Fuzz harness: the ISO 11783-10 task-controller server (isobus/tc_server).
// Input: 1 flag byte (bit 0: a well-behaved client 0x80 first connects with the spreader's 8-section pool
// through a real TP session, so the records below also reach the active state), then records of 11 bytes:
//   kind (bits 0-2: 0 TP.CM, 1 TP.DT, 2 ETP.CM, 3 ETP.DT, 4 PGN 0xCB00, 5 working-set master, 6 set_value,
//         7 request_value or, when byte 6 is odd, a measurement command 4 + byte 7 mod 5;
//         bit 3: source 0x90 instead of 0x80; bits 4-7: payload length 0-15, above 8 = 8),
//   destination, 8 data bytes (set/request/measure: DDI in bytes 0-1, value in bytes 2-5), milliseconds to
//   advance.
// Checked: every frame sent is from the TC's address, on PGN 0xCB00 or TP/ETP, never to itself or the null
// address, and broadcast only as the TC status; active implies a held pool and a client; as-applied
// records come from a client address; the TC status keeps its 2 s rhythm.
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "firmware_sim/can/spreader_ddop.hpp"
#include "fuzz/fuzz_input.hpp"
#include "isobus/tc_server.hpp"

namespace {

constexpr const char* kHarness = "fuzz_tc_server";
namespace iso = spread::isobus;
constexpr std::uint8_t kTc = 0xF7;
constexpr std::uint8_t kClient = 0x80;
constexpr std::uint8_t kOther = 0x90;

bool is_transport(std::uint32_t pgn) {
  return pgn == iso::kTpConnectionManagementPgn || pgn == iso::kTpDataTransferPgn ||
         pgn == iso::kEtpConnectionManagementPgn || pgn == iso::kEtpDataTransferPgn;
}

void check(iso::TcServer& tc, std::vector<iso::TransportFrame>& frames, std::chrono::nanoseconds now) {
  for (const iso::TransportFrame& f : tc.take_frames()) {
    if (f.source != kTc) spread::fuzz::fail(kHarness, "frame not from the TC's address");
    if (f.pgn != iso::kTcProcessDataPgn && !is_transport(f.pgn)) {
      spread::fuzz::fail(kHarness, "frame with PGN " + std::to_string(f.pgn));
    }
    if (f.destination == kTc || f.destination == 0xFE) spread::fuzz::fail(kHarness, "frame to itself / null");
    if (f.pgn == iso::kTcProcessDataPgn && f.destination == 0xFF && f.data[0] != 0xFE) {
      spread::fuzz::fail(kHarness, "broadcast process data that is not the TC status");
    }
    frames.push_back(f);
  }
  if (tc.active() && (!tc.pool() || !tc.client_address())) spread::fuzz::fail(kHarness, "active without pool/client");
  for (const iso::AsAppliedRecord& r : tc.take_as_applied()) {
    if (r.source != kClient && r.source != kOther) spread::fuzz::fail(kHarness, "value logged from a non-client");
  }
  tc.take_events();
  // One status at start, then one per 2 s.
  const auto expected_max = static_cast<std::uint64_t>(now / iso::kTcStatusInterval) + 1;
  if (tc.counters().status_sent > expected_max) spread::fuzz::fail(kHarness, "TC status more often than every 2 s");
}

// A well-behaved client connects: working-set master, version, label, pool by TP, activate.
void connect(iso::TcServer& tc, std::chrono::nanoseconds now) {
  spread::firmware::can::SpreaderDescription d;
  const std::vector<std::uint8_t> pool = iso::write_ddop(spread::firmware::can::make_spreader_ddop(d));
  iso::TransportProtocol client_tp(kClient);
  auto single = [&](std::uint32_t pgn, std::uint8_t dst, const iso::TcFrame& data) {
    tc.handle_frame(pgn, kClient, dst, data, now);
  };
  single(iso::kWorkingSetMasterPgn, 0xFF, iso::encode_working_set_master());
  single(iso::kTcProcessDataPgn, kTc, iso::tc_frame(iso::TcMessage::kRequestVersion));
  single(iso::kTcProcessDataPgn, kTc, iso::tc_frame(iso::TcMessage::kRequestStructureLabel));
  single(iso::kTcProcessDataPgn, kTc, iso::encode_request_pool_transfer(static_cast<std::uint32_t>(pool.size())));
  client_tp.send({iso::kTcProcessDataPgn, kClient, kTc, iso::encode_pool_transfer(pool)}, now);
  for (int round = 0; round < 1000; ++round) {
    bool moved = false;
    for (const iso::TransportFrame& f : tc.take_frames()) {
      if (is_transport(f.pgn)) {
        moved = true;
        client_tp.handle_frame(f, now);
      }
    }
    for (const iso::TransportFrame& f : client_tp.take_frames()) {
      moved = true;
      tc.handle_frame(f.pgn, f.source, f.destination, f.data, now);
    }
    if (!moved) break;
  }
  single(iso::kTcProcessDataPgn, kTc, iso::encode_activate(true));
  if (!tc.active()) spread::fuzz::fail(kHarness, "the well-behaved client did not get activated");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  spread::fuzz::FuzzInput input(data, size);
  std::chrono::nanoseconds now{0};
  iso::TcServer tc;
  std::vector<iso::TransportFrame> frames;
  tc.start(kTc, now);
  const auto flags = input.take<std::uint8_t>();
  if ((flags & 1u) != 0) connect(tc, now);
  check(tc, frames, now);
  constexpr std::uint32_t kPgns[] = {iso::kTpConnectionManagementPgn, iso::kTpDataTransferPgn,
                                     iso::kEtpConnectionManagementPgn, iso::kEtpDataTransferPgn,
                                     iso::kTcProcessDataPgn, iso::kWorkingSetMasterPgn};
  while (input.remaining() > 0) {
    const auto kind = input.take<std::uint8_t>();
    const auto destination = input.take<std::uint8_t>();
    const auto bytes = input.take<std::array<std::uint8_t, 8>>();
    const auto advance_ms = input.take<std::uint8_t>();
    const std::uint8_t source = (kind & 0x08u) != 0 ? kOther : kClient;
    const std::size_t length = (kind >> 4) > 8 ? 8 : (kind >> 4);
    const unsigned op = kind & 0x07u;
    if (op <= 5) {
      tc.handle_frame(kPgns[op], source, destination, std::span<const std::uint8_t>(bytes.data(), length), now);
    } else {
      const auto ddi = static_cast<std::uint16_t>(bytes[0] | (bytes[1] << 8));
      const auto value = static_cast<std::int32_t>(static_cast<std::uint32_t>(bytes[2]) | (std::uint32_t{bytes[3]} << 8) |
                                                   (std::uint32_t{bytes[4]} << 16) | (std::uint32_t{bytes[5]} << 24));
      if (op == 6) {
        (void)tc.set_value(ddi, value);
      } else if ((bytes[6] & 1u) != 0) {
        (void)tc.measure(ddi, static_cast<iso::MeasurementCommand>(4 + bytes[7] % 5), value);
      } else {
        (void)tc.request_value(ddi);
      }
    }
    check(tc, frames, now);
    now += std::chrono::milliseconds(advance_ms);
    tc.update(now);
    check(tc, frames, now);
    frames.clear();
  }
  return 0;
}
