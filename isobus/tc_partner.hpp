#pragma once
// The ECU's partner task controller: the one node whose process-data commands and TC status the ECU takes
// (ISO 11783-10 client and server are partners, identified by their ISO 11783-5 NAMEs). A state machine
// without I/O: address claims, TC status messages and the time go in; whether a source is the partner,
// and when the partnership ends, come out.
//
//   no partner --TC status from an address whose claim carries a task controller's NAME--> partner
//   partner --6 s without its TC status / its address claimed by another NAME / its NAME says cannot
//             claim or claims another address--> no partner (the ECU treats it as a TC gone silent)
//
// A task controller's NAME (ISO 11783-1 NAME function table): industry group 2, device class 0
// (non-specific system), function 130. Function 130 means something else in other device classes (in
// class 5, fertilisers, it is product pressure), so all three are checked. A node that never claimed an
// address has no NAME, and so cannot be the partner.
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace spread::isobus {

using Nanoseconds = std::chrono::nanoseconds;

inline constexpr std::uint8_t kFunctionTaskController = 130;
inline constexpr std::uint8_t kDeviceClassNonSpecific = 0;

// Whether a NAME is that of a task controller (see above).
bool is_task_controller_name(std::uint64_t name);

struct TcPartnerCounters {
  std::uint64_t partners_chosen = 0;
  std::uint64_t partners_lost = 0;
  std::uint64_t status_not_from_a_tc = 0;     // TC status from an address without a TC's claim
  std::uint64_t status_from_other_tc = 0;     // TC status from a second TC while one is the partner
};

class TaskControllerPartner {
 public:
  enum class Status {
    kPartner,       // from the partner (or it just became the partner)
    kNotATc,        // the source has no address claim with a TC's NAME: ignore
    kOtherTc,       // another TC while the partner is held: ignore
  };

  // An address-claimed message (PGN 0xEE00) from `source` (0xFE: cannot claim) with `name`. Returns true
  // when it ends the partnership (the partner's address taken by another NAME, the partner's NAME at
  // another address or unable to claim).
  bool on_address_claimed(std::uint8_t source, std::uint64_t name);
  // A TC status message from `source`.
  Status on_tc_status(std::uint8_t source, Nanoseconds now);
  // Returns true when the partner's TC status has just been missing for longer than `timeout`.
  bool update(Nanoseconds now, Nanoseconds timeout);

  bool is_partner(std::uint8_t source) const { return partner_ && partner_->address == source; }
  std::optional<std::uint8_t> address() const {
    return partner_ ? std::optional<std::uint8_t>(partner_->address) : std::nullopt;
  }
  std::optional<std::uint64_t> name() const {
    return partner_ ? std::optional<std::uint64_t>(partner_->name) : std::nullopt;
  }
  const std::string& last_loss() const { return last_loss_; }  // why the last partnership ended
  const TcPartnerCounters& counters() const { return counters_; }

 private:
  void lose(std::string why);

  struct Partner {
    std::uint8_t address = 0;
    std::uint64_t name = 0;
    Nanoseconds last_status{};
  };
  std::optional<Partner> partner_;
  // The NAME last seen claiming each address (0-253).
  std::array<std::optional<std::uint64_t>, 254> names_{};
  std::string last_loss_;
  TcPartnerCounters counters_;
};

}  // namespace spread::isobus
