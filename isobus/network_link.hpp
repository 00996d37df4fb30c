#pragma once
// ISO 11783 network management of the ECU on a CAN frame sink: the address claim (ISO 11783-5, the state
// machine in isobus/address_claim.hpp), requests for the address claim, and the negative acknowledgement
// of requests for PGNs this ECU does not provide (ISO 11783-3 §5.4.4 / §5.4.5).
//
// Two modes. Started (a live bus: start() at power-up): the ECU's address is whatever the claim procedure
// holds, and has_address() is true only while a claim stands — 250 ms after claiming, not contested by a
// lower NAME. Not started (candump replay, process-data unit tests): the configured address is used as is
// and has_address() is true, so a log replays exactly as recorded.
#include <cstdint>

#include "isobus/address_claim.hpp"
#include "isobus/can/can_frame_port.hpp"
#include "isobus/isobus_id.hpp"
#include "libspread/core/clock.hpp"

namespace spread::isobus {

inline constexpr std::uint32_t kAcknowledgementPgn = 0xE800;
// Control byte of the acknowledgement message (ISO 11783-3 §5.4.5, J1939-21 §5.4.4).
enum class AckControl : std::uint8_t { kAck = 0, kNack = 1, kAccessDenied = 2, kCannotRespond = 3 };

struct NetworkCounters {
  std::uint64_t requests_answered = 0;  // requests for the address claim
  std::uint64_t requests_nacked = 0;    // requests to us for a PGN we do not provide: NACK sent
  std::uint64_t requests_ignored = 0;   // global requests for a PGN we do not provide (never NACKed)
  std::uint64_t address_losses = 0;     // a standing claim taken by a lower NAME (or a failed re-claim)
  std::uint64_t claim_requests_sent = 0;  // our requests for everyone's address claim (once our claim stands)
  std::uint64_t send_failures = 0;
};

class NetworkLink {
 public:
  enum class Verdict {
    kNotNetwork,  // not a network-management frame: the caller handles it
    kHandled,     // consumed (answered, ignored or fed to the claim)
    kMalformed,   // a request or a claim with too few data bytes
  };

  NetworkLink(const Clock& clock, can::CanFrameSink& tx, std::uint64_t name, std::uint8_t preferred_address);

  // Begins the address claim (sends the first claim at once).
  void start();
  bool started() const { return started_; }
  // Sends the claim messages that are due and advances the 250 ms settle timer. Call often (every loop
  // pump); returns true when the ECU has just lost its address (a standing claim, or the last candidate).
  bool service();

  Verdict handle(const IsobusId& id, const can_frame& frame);
  // A global request for every node's address claim, answered by our own claim at once (the request asks
  // us too). Sent by itself once our claim stands; a tool that waits for a node may ask again.
  void request_address_claims();
  // Another node sent a frame (not an address claim) from our address: ISO 11783-5 address violation,
  // answered with our claim (rate-limited in AddressClaim). Nothing when not started (a replay).
  void on_address_violation();

  // The source address to send from: the claimed one, or the configured one when not started.
  std::uint8_t address() const { return started_ ? claim_.address() : configured_address_; }
  // True when the ECU may send anything besides address claims, and may act on process data: a standing
  // claim (or not started). Metering must stop when this turns false: without an address the ECU can
  // neither report nor be supervised by a task controller (ISO 11783-5 §4.4.4.3, cannot claim: silent).
  bool has_address() const { return !started_ || claim_.has_address(); }
  const isobus::AddressClaim& claim() const { return claim_; }
  const NetworkCounters& counters() const { return counters_; }

 private:
  Verdict handle_request(const IsobusId& id, const can_frame& frame);
  void send_nack(std::uint32_t pgn, std::uint8_t requester);
  void flush_claims();

  const Clock& clock_;
  can::CanFrameSink& tx_;
  std::uint8_t configured_address_;
  isobus::AddressClaim claim_;
  bool started_ = false;
  bool had_address_ = false;
  NetworkCounters counters_;
};

}  // namespace spread::isobus
