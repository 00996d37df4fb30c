#pragma once
// ISO 11783-5 address claim of one control function, as a state machine without I/O: the caller feeds it
// the address-claimed messages and requests it receives, with the time, and sends what poll() returns.
//
//   not started --start()--> claiming --250 ms uncontested--> claimed
//        claiming/claimed --a lower NAME claims our address--> claiming (next free address, if
//                                       self-configurable) or cannot claim (cannot-claim message)
//        claiming/claimed --our own NAME from another node, once--> our claim again (contend)
//        claiming/claimed --our own NAME again within 2 s--> cannot claim for a hold-off (two units with
//                                       one NAME), then claiming the preferred address again
//        claiming/claimed --another node sends from our address--> our claim again (address violation)
//
// Only in `claimed` may the function send anything but address claims (§4.4.2: no transmission until
// 250 ms after a successful claim, to give a contender with a lower NAME time to object).
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "isobus/isobus_id.hpp"

namespace spread::isobus {

using Nanoseconds = std::chrono::nanoseconds;

inline constexpr std::uint32_t kAddressClaimedPgn = 0xEE00;
// kNullAddress (isobus_id.hpp) is the source of a cannot-claim message.
// Addresses a self-configurable function may take (ISO 11783-5 §4.4.3.4; J1939 "dynamic" range).
inline constexpr std::uint8_t kSelfConfigurableFirst = 128;
inline constexpr std::uint8_t kSelfConfigurableLast = 247;
// The claim stands once it has gone this long without a contender (§4.4.2).
inline constexpr Nanoseconds kClaimSettleTime = std::chrono::milliseconds(250);
// A cannot-claim message is delayed by 0.6 ms × a pseudo-random 0..255 (0-153 ms) so that several losers
// answering the same request do not collide on the bus (§4.4.4.3).
inline constexpr Nanoseconds kCannotClaimDelayUnit = std::chrono::microseconds(600);
// Our NAME seen twice from another node within this window is a second unit with our NAME, not a stray
// frame: one sighting is answered with our claim, a second within the window makes us give up.
inline constexpr Nanoseconds kDuplicateNameWindow = std::chrono::seconds(2);
// After giving up for a duplicate NAME the function stays silent this long (doubled for each further
// episode, at most 16 times: 48 s), then claims its preferred address again. Our NAME seen meanwhile
// starts the hold-off over. A stray frame costs a few seconds, never the rest of the day; two units with
// one NAME take turns at most, and never hold an address at the same time.
inline constexpr Nanoseconds kDuplicateNameHoldOff = std::chrono::seconds(3);
inline constexpr int kDuplicateNameMaxDoublings = 4;
// A claim that stood this long without our NAME from elsewhere ends the doubling.
inline constexpr Nanoseconds kDuplicateNameForgetAfter = std::chrono::seconds(60);

enum class ClaimState { kNotStarted, kClaiming, kClaimed, kCannotClaim };

// One PGN 0xEE00 message to the global address: `source` is the claimed address (kNullAddress for
// cannot-claim), the data is the NAME.
struct ClaimMessage {
  std::uint8_t source = kNullAddress;
  std::uint64_t name = 0;
};

struct AddressClaimCounters {
  std::uint64_t claims_sent = 0;
  std::uint64_t contentions_won = 0;   // a higher NAME claimed our address: we re-asserted our claim
  std::uint64_t contentions_lost = 0;  // a lower NAME claimed our address
  std::uint64_t cannot_claim_sent = 0;
  std::uint64_t duplicate_names = 0;     // claims (or cannot-claims) carrying our own NAME from another node
  std::uint64_t duplicate_name_holds = 0;  // times we gave up for a duplicate NAME (and claimed again later)
  std::uint64_t address_violations = 0;  // other nodes' frames from our address
  std::uint64_t violation_claims = 0;    // claims re-sent because of an address violation
};

class AddressClaim {
 public:
  // `name`: the 64-bit NAME (bit 63 says whether it may choose another address); `preferred_address`:
  // the address it claims first (0-253).
  AddressClaim(std::uint64_t name, std::uint8_t preferred_address);

  void start(Nanoseconds now);
  // An address-claimed message (PGN 0xEE00) from `source` carrying `name`, received at `now`.
  void on_address_claimed(std::uint8_t source, std::uint64_t name, Nanoseconds now);
  // A request for PGN 0xEE00 sent to the global address or to our address (the caller filters others).
  void on_request_for_claim(Nanoseconds now);
  // A frame other than an address claim, from another node, with our address as its source: an address
  // violation. The claim is sent again (at most once per kClaimSettleTime, so a flood of spoofed frames
  // cannot make us flood the bus in turn).
  void on_address_violation(Nanoseconds now);
  // Advances the timers and returns the claim messages due now, oldest first.
  std::vector<ClaimMessage> poll(Nanoseconds now);

  ClaimState state() const { return state_; }
  // Only a standing claim allows sending (§4.4.2).
  bool has_address() const { return state_ == ClaimState::kClaimed; }
  // The address being claimed or held; kNullAddress before start and after losing for good.
  std::uint8_t address() const { return address_; }
  std::uint64_t name() const { return name_; }
  bool self_configurable() const { return (name_ >> 63) != 0; }
  const AddressClaimCounters& counters() const { return counters_; }

 private:
  void claim(std::uint8_t address, Nanoseconds now);
  void lose(Nanoseconds now);
  void on_own_name(Nanoseconds now);
  Nanoseconds hold_off() const;
  void queue(ClaimMessage message, Nanoseconds due);
  std::optional<std::uint8_t> next_candidate() const;
  Nanoseconds cannot_claim_delay() const;

  std::uint64_t name_;
  std::uint8_t preferred_;
  ClaimState state_ = ClaimState::kNotStarted;
  std::uint8_t address_ = kNullAddress;
  Nanoseconds claim_sent_at_{};
  std::optional<Nanoseconds> last_violation_claim_;
  std::optional<Nanoseconds> last_own_name_;  // when our NAME was last seen from another node
  std::optional<Nanoseconds> reclaim_at_;     // giving up for a duplicate NAME: when to claim again
  int hold_offs_ = 0;                         // duplicate-NAME episodes since the claim last stood long
  // The NAME last seen claiming each address (0-253): a self-configurable function skips addresses whose
  // holder would beat it.
  std::array<std::optional<std::uint64_t>, 254> holders_{};
  struct Pending {
    ClaimMessage message;
    Nanoseconds due;
  };
  std::vector<Pending> pending_;
  AddressClaimCounters counters_;
};

}  // namespace spread::isobus
