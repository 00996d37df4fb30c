// Fuzz harness: ISO 11783-3 TP / ISO 11783-6 ETP reassembly (isobus/transport_protocol).
// Input: 1 flag byte (bit 0: we send a 100-byte TP message to 0x81, bit 1: a 2000-byte ETP message to 0x82,
// bit 2: a 30-byte BAM), then records of 12 bytes: PGN selector (low 2 bits: TP.CM, TP.DT, ETP.CM, ETP.DT),
// source, destination, 8 data bytes, milliseconds the clock advances after the frame.
// Checked: every frame sent is a TP/ETP frame from our address (to the global address only for our own
// BAM), abort reasons are the standard's, received messages have legal sizes, the session count stays
// within its limit, and no session outlives its timeouts.
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input.hpp"
#include "isobus/transport_protocol.hpp"

namespace {

constexpr const char* kHarness = "fuzz_transport_protocol";
namespace iso = spread::isobus;
constexpr std::uint8_t kOwn = 0x80;
constexpr iso::TransportLimits kLimits{8192, 8, 16};

void check_sent(iso::TransportProtocol& tp) {
  for (const iso::TransportFrame& f : tp.take_frames()) {
    if (f.source != kOwn) spread::fuzz::fail(kHarness, "frame not from our address");
    const bool cm = f.pgn == iso::kTpConnectionManagementPgn || f.pgn == iso::kEtpConnectionManagementPgn;
    const bool dt = f.pgn == iso::kTpDataTransferPgn || f.pgn == iso::kEtpDataTransferPgn;
    if (!cm && !dt) spread::fuzz::fail(kHarness, "frame with PGN " + std::to_string(f.pgn));
    if (f.destination == kOwn || f.destination == 0xFE) spread::fuzz::fail(kHarness, "frame to ourselves / null");
    if (f.destination == 0xFF) {
      const bool bam = (f.pgn == iso::kTpConnectionManagementPgn && f.data[0] == 32) || f.pgn == iso::kTpDataTransferPgn;
      if (!bam) spread::fuzz::fail(kHarness, "global frame that is not part of our BAM");
    }
    if (cm && f.data[0] == 255) {
      const int r = f.data[1];
      if (!((r >= 1 && r <= 12) || r == 14 || r == 15 || r == 250)) {
        spread::fuzz::fail(kHarness, "abort reason " + std::to_string(r));
      }
    }
  }
  for (const iso::TransportMessage& m : tp.take_received()) {
    const std::size_t n = m.data.size();
    if (n < iso::kTpMinBytes || n > kLimits.max_receive_bytes) spread::fuzz::fail(kHarness, "message size " + std::to_string(n));
    if (m.destination == 0xFF && n > iso::kTpMaxBytes) spread::fuzz::fail(kHarness, "BAM above 1785 bytes");
    if (m.source == kOwn || m.source >= 0xFE) spread::fuzz::fail(kHarness, "message from our / a null address");
  }
  tp.take_ended();
  if (tp.session_count() > kLimits.max_sessions) spread::fuzz::fail(kHarness, "more sessions than the limit");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  spread::fuzz::FuzzInput input(data, size);
  std::chrono::nanoseconds now{0};
  iso::TransportProtocol tp(kOwn, kLimits);
  const auto flags = input.take<std::uint8_t>();
  auto payload = [](std::size_t n) {
    std::vector<std::uint8_t> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::uint8_t>(i);
    return v;
  };
  if ((flags & 1u) != 0) tp.send({0xCB00, kOwn, 0x81, payload(100)}, now);
  if ((flags & 2u) != 0) tp.send({0xCB00, kOwn, 0x82, payload(2000)}, now);
  if ((flags & 4u) != 0) tp.send({0xFEE6, kOwn, 0xFF, payload(30)}, now);
  check_sent(tp);
  static constexpr std::array<std::uint32_t, 4> kPgns{iso::kTpConnectionManagementPgn, iso::kTpDataTransferPgn,
                                                      iso::kEtpConnectionManagementPgn, iso::kEtpDataTransferPgn};
  while (input.remaining() > 0) {
    iso::TransportFrame f;
    f.pgn = kPgns[input.take<std::uint8_t>() & 3u];
    f.source = input.take<std::uint8_t>();
    f.destination = input.take<std::uint8_t>();
    f.data = input.take<std::array<std::uint8_t, 8>>();
    tp.handle_frame(f, now);
    check_sent(tp);
    const auto step_ms = input.take<std::uint8_t>();
    if (step_ms > 0) {
      now += std::chrono::milliseconds(step_ms);
      tp.update(now);
      check_sent(tp);
    }
  }
  // Silence: every session must end by its timeout (the longest is T2/T3 = 1.25 s; our BAM needs 5 × 50 ms).
  for (int i = 0; i < 40 && tp.session_count() > 0; ++i) {
    now += std::chrono::milliseconds(50);
    tp.update(now);
    check_sent(tp);
  }
  if (tp.session_count() != 0) spread::fuzz::fail(kHarness, "a session outlived its timeouts");
  return 0;
}
