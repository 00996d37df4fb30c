#pragma once
// Fault codes of the simulated ECU. Each code is one bit of the status word `fault_codes` and has its
// own occurrence counter: bad input is never dropped silently, it is counted and shown for a while.
#include <array>
#include <cstdint>
#include <string_view>

#include "libspread/core/clock.hpp"

namespace spread::firmware {

// The numeric values are the bit positions published in status_t.fault_codes and documented in
// docs/messages.md: append new codes, never renumber.
enum class Fault : std::uint8_t {
  kLcmUndecodable = 0,        // LCM payload shorter than its fingerprint or failing to decode
  kLcmWrongFingerprint = 1,   // LCM payload of another type or another version of command_t
  kCanMalformedFrame = 2,     // truncated or oversized record, DLC != 8 for a PGN this ECU reads
  kCanUnknownDdi = 3,         // process data for a DDI this ECU does not implement
  kCanUnsupportedCommand = 4, // process data command nibble this ECU does not implement
  kSetpointOutOfRange = 5,    // a set-point outside its documented range (rate, width, rpm, speed, sections)
  kNotANumber = 6,            // NaN or infinity in a numeric field
  kUnknownMaterial = 7,       // material not present in the loaded tables (or empty / too long)
  kUnknownMode = 8,           // mode value other than manual (0) or automatic (1)
  kStaleSequence = 9,         // command sequence number repeated or older than the last accepted one
  kAutomaticUnavailable = 10, // automatic mode or wind compensation requested without spread tables loaded
  kWidthOutOfReach = 11,      // state: the set-point working width cannot be reached at the CV target
  kCommandTimeout = 12,       // state: the LCM controller owning the work state fell silent; work state off
  kLoopOverrun = 13,          // a loop step finished after the next tick was due
  kPredictionFailed = 14,     // the C API returned an error for a prediction
  kReplayParseError = 15,     // a candump log line that could not be parsed
  kCanNotSettable = 16,       // set-value for a DDI that is read-only (e.g. actual values, 70)
  kDiscNotAtSpeed = 17,       // state: spreading requested but the disc is stopped or off its target; metering closed
  kSpeedUnavailable = 18,     // state: work state on without a valid ground speed (lost, error, not available)
  kDrivingReverse = 19,       // state: work state on while the tractor reports reverse; metering closed
  kTaskControllerLost = 20,   // state: the task controller owning the work state stopped its status; work state off
  kSequenceJump = 21,         // command sequence far ahead of the last one, not (yet) confirmed by its successor
  kNoBusAddress = 22,         // state: the ECU has no standing ISO 11783-5 address claim; metering closed
  kCanNotFromTaskController = 23,  // process data / TC status from a node that is not the partner TC: ignored
};
inline constexpr std::size_t kFaultCount = 24;

// Short stable identifier, e.g. "setpoint_out_of_range".
std::string_view fault_name(Fault fault);
// State faults are active exactly while their condition holds; all others are events.
bool is_state_fault(Fault fault);
constexpr std::uint32_t fault_bit(Fault fault) { return std::uint32_t{1} << static_cast<unsigned>(fault); }

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
