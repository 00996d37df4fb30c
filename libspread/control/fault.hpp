#pragma once
// Fault codes of the simulated ECU. Each code is one bit of the status word `fault_codes` and has its
// own occurrence counter: bad input is never dropped silently, it is counted and shown for a while.
#include <array>
#include <cstdint>
#include <string_view>

#include "libspread/control/fault_codes.hpp"
#include "libspread/core/clock.hpp"

namespace spread::firmware {

// The codes, their bits and names are published in the ECU's messages: fault_codes.hpp.

// State faults are active exactly while their condition holds; all others are events.
bool is_state_fault(Fault fault);

// Counts every occurrence and keeps an event fault visible for `hold` after its last occurrence, so a
// status reader polling at a lower rate still sees it. State faults are set and cleared explicitly.
class FaultLog {
 public:
  explicit FaultLog(Nanoseconds hold = std::chrono::seconds(2)) : hold_(hold) {}

  void record(Fault fault, Nanoseconds now);
  void set_state(Fault fault, bool active, Nanoseconds now);

  std::uint64_t count(Fault fault) const { return counts_[static_cast<std::size_t>(fault)]; }
  std::uint64_t total() const;
  // Bit mask of the faults that are active now (state faults) or occurred within `hold`.
  std::uint32_t active_mask(Nanoseconds now) const;
  bool is_active(Fault fault, Nanoseconds now) const { return (active_mask(now) & fault_bit(fault)) != 0; }

 private:
  Nanoseconds hold_;
  std::array<std::uint64_t, kFaultCount> counts_{};
  std::array<Nanoseconds, kFaultCount> last_seen_{};
  std::array<bool, kFaultCount> ever_seen_{};
  std::uint32_t state_mask_ = 0;
};

}  // namespace spread::firmware
