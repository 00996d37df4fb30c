#pragma once
// The ECU's fault codes as its messages publish them: bit n of status_t.fault_codes and heartbeat_t.fault_codes
// is code n, and DM1 reports code n as proprietary SPN base + n (docs/messages.md). The ECU raises and counts
// them (fault.hpp); a tractor reads them by name (tools/spread_tractor).
#include <cstddef>
#include <cstdint>
#include <string_view>

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
constexpr std::string_view fault_name(Fault fault) {
  switch (fault) {
    case Fault::kLcmUndecodable: return "lcm_undecodable";
    case Fault::kLcmWrongFingerprint: return "lcm_wrong_fingerprint";
    case Fault::kCanMalformedFrame: return "can_malformed_frame";
    case Fault::kCanUnknownDdi: return "can_unknown_ddi";
    case Fault::kCanUnsupportedCommand: return "can_unsupported_command";
    case Fault::kSetpointOutOfRange: return "setpoint_out_of_range";
    case Fault::kNotANumber: return "not_a_number";
    case Fault::kUnknownMaterial: return "unknown_material";
    case Fault::kUnknownMode: return "unknown_mode";
    case Fault::kStaleSequence: return "stale_sequence";
    case Fault::kAutomaticUnavailable: return "automatic_unavailable";
    case Fault::kWidthOutOfReach: return "width_out_of_reach";
    case Fault::kCommandTimeout: return "command_timeout";
    case Fault::kLoopOverrun: return "loop_overrun";
    case Fault::kPredictionFailed: return "prediction_failed";
    case Fault::kReplayParseError: return "replay_parse_error";
    case Fault::kCanNotSettable: return "can_not_settable";
    case Fault::kDiscNotAtSpeed: return "disc_not_at_speed";
    case Fault::kSpeedUnavailable: return "speed_unavailable";
    case Fault::kDrivingReverse: return "driving_reverse";
    case Fault::kTaskControllerLost: return "task_controller_lost";
    case Fault::kSequenceJump: return "sequence_jump";
    case Fault::kNoBusAddress: return "no_bus_address";
    case Fault::kCanNotFromTaskController: return "can_not_from_task_controller";
  }
  return "unknown_fault";
}

constexpr std::uint32_t fault_bit(Fault fault) { return std::uint32_t{1} << static_cast<unsigned>(fault); }

}  // namespace spread::firmware
