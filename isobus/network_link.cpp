#include "isobus/network_link.hpp"

#include "isobus/iso_name.hpp"

namespace spread::isobus {
namespace {
constexpr std::uint32_t kRequestPgnNumber = 0xEA00;
constexpr std::uint8_t kNetworkPriority = 6;  // default priority of claims, requests and acknowledgements
}  // namespace

NetworkLink::NetworkLink(const Clock& clock, can::CanFrameSink& tx, std::uint64_t name, std::uint8_t preferred_address)
    : clock_(clock), tx_(tx), configured_address_(preferred_address), claim_(name, preferred_address) {}

void NetworkLink::start() {
  if (started_) return;
  started_ = true;
  claim_.start(clock_.now());
  flush_claims();
}

void NetworkLink::flush_claims() {
  for (const isobus::ClaimMessage& m : claim_.poll(clock_.now())) {
    const auto data = isobus::name_to_bytes(m.name);
    const IsobusId id{kNetworkPriority, isobus::kAddressClaimedPgn, kGlobalAddress, m.source};
    if (!tx_.send(can::make_frame(encode_id(id), data.data(), 8))) ++counters_.send_failures;
  }
}

bool NetworkLink::service() {
  if (!started_) return false;
  flush_claims();
  const bool has = claim_.has_address();
  const bool lost = had_address_ && !has;
  if (lost) ++counters_.address_losses;
  // Nodes that claimed before we joined (a task controller already running) are known only by asking:
  // once our claim stands, a global request for the address claim makes every node claim again
  // (ISO 11783-5 §4.4.3), and the ECU learns which NAME holds which address.
  if (has && !had_address_) request_address_claims();
  had_address_ = has;
  return lost;
}

NetworkLink::Verdict NetworkLink::handle(const IsobusId& id, const can_frame& frame) {
  if (id.pgn == isobus::kAddressClaimedPgn) {
    if (frame.len != 8) return Verdict::kMalformed;
    if (started_) {
      claim_.on_address_claimed(id.source, isobus::name_from_bytes(frame.data), clock_.now());
      flush_claims();
    }
    return Verdict::kHandled;
  }
  if (id.pgn == kRequestPgnNumber) return handle_request(id, frame);
  return Verdict::kNotNetwork;
}

void NetworkLink::on_address_violation() {
  if (!started_) return;
  claim_.on_address_violation(clock_.now());
  flush_claims();
}

NetworkLink::Verdict NetworkLink::handle_request(const IsobusId& id, const can_frame& frame) {
  const bool to_us = address() < kNullAddress && id.destination == address();
  const bool to_all = id.destination == kGlobalAddress;
  if (!to_us && !to_all) return Verdict::kHandled;  // a request for another node
  if (frame.len < 3) return Verdict::kMalformed;
  const std::uint32_t pgn = std::uint32_t{frame.data[0]} | (std::uint32_t{frame.data[1]} << 8) |
                            (std::uint32_t{frame.data[2]} << 16);
  if (pgn == isobus::kAddressClaimedPgn) {
    ++counters_.requests_answered;
    if (started_) {
      claim_.on_request_for_claim(clock_.now());
      flush_claims();
    } else {
      const auto data = isobus::name_to_bytes(claim_.name());
      const IsobusId claim_id{kNetworkPriority, isobus::kAddressClaimedPgn, kGlobalAddress, configured_address_};
      if (!tx_.send(can::make_frame(encode_id(claim_id), data.data(), 8))) ++counters_.send_failures;
    }
    return Verdict::kHandled;
  }
  // ISO 11783-3 §5.4.4: a request sent to one node for a PGN it does not provide is answered with a NACK;
  // a global request is not (every node would NACK at once, for nothing).
  if (to_us) {
    ++counters_.requests_nacked;
    send_nack(pgn, id.source);
  } else {
    ++counters_.requests_ignored;
  }
  return Verdict::kHandled;
}

void NetworkLink::request_address_claims() {
  const std::uint8_t data[3] = {static_cast<std::uint8_t>(isobus::kAddressClaimedPgn),
                                static_cast<std::uint8_t>(isobus::kAddressClaimedPgn >> 8),
                                static_cast<std::uint8_t>(isobus::kAddressClaimedPgn >> 16)};
  const IsobusId id{kNetworkPriority, kRequestPgnNumber, kGlobalAddress, address()};
  if (tx_.send(can::make_frame(encode_id(id), data, 3))) {
    ++counters_.claim_requests_sent;
  } else {
    ++counters_.send_failures;
  }
  // A request to the global address asks every node, its sender included (ISO 11783-5 §4.4.3; SAE
  // J1939-81 likewise): our own frames never come back to us, so we answer it here. Other nodes take a
  // node that has not claimed soon after a global request as gone from the bus (an independent stack
  // drops it after 0.75 s), and a task controller already running would then ignore this ECU.
  claim_.on_request_for_claim(clock_.now());
  flush_claims();
}

void NetworkLink::send_nack(std::uint32_t pgn, std::uint8_t requester) {
  if (!has_address()) return;
  // Acknowledgement (PGN 0xE800): byte 1 control, byte 2 group function (0xFF: none), bytes 3-4 reserved,
  // byte 5 the address being acknowledged, bytes 6-8 the PGN. It goes to the global address with the
  // requester named in byte 5 (ISO 11783-3 §5.4.5: the acknowledgement is always broadcast).
  const std::uint8_t data[8] = {static_cast<std::uint8_t>(AckControl::kNack),
                                0xFF,
                                0xFF,
                                0xFF,
                                requester,
                                static_cast<std::uint8_t>(pgn),
                                static_cast<std::uint8_t>(pgn >> 8),
                                static_cast<std::uint8_t>(pgn >> 16)};
  const IsobusId id{kNetworkPriority, kAcknowledgementPgn, kGlobalAddress, address()};
  if (!tx_.send(can::make_frame(encode_id(id), data, 8))) ++counters_.send_failures;
}

}  // namespace spread::isobus
