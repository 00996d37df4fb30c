#include "firmware_sim/ecu/fault.hpp"

namespace spread::firmware {

std::string_view fault_name(Fault fault) {
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

bool is_state_fault(Fault fault) {
  switch (fault) {
    case Fault::kWidthOutOfReach:
    case Fault::kCommandTimeout:
    case Fault::kDiscNotAtSpeed:
    case Fault::kSpeedUnavailable:
    case Fault::kDrivingReverse:
    case Fault::kTaskControllerLost:
    case Fault::kNoBusAddress:
      return true;
    default:
      return false;
  }
}

void FaultLog::record(Fault fault, Nanoseconds now) {
  const auto i = static_cast<std::size_t>(fault);
  ++counts_[i];
  last_seen_[i] = now;
  ever_seen_[i] = true;
}

void FaultLog::set_state(Fault fault, bool active, Nanoseconds now) {
  const bool was_active = (state_mask_ & fault_bit(fault)) != 0;
  // A state fault is counted once per entry into the state, not once per loop step.
  if (active && !was_active) record(fault, now);
  if (active) {
    state_mask_ |= fault_bit(fault);
  } else {
    state_mask_ &= ~fault_bit(fault);
  }
}

std::uint64_t FaultLog::total() const {
  std::uint64_t sum = 0;
  for (const auto c : counts_) sum += c;
  return sum;
}

std::uint32_t FaultLog::active_mask(Nanoseconds now) const {
  std::uint32_t mask = state_mask_;
  for (std::size_t i = 0; i < kFaultCount; ++i) {
    const std::uint32_t bit = std::uint32_t{1} << i;
    if (is_state_fault(static_cast<Fault>(i)) || !ever_seen_[i]) continue;
    // Events stay visible for `hold` after their last occurrence.
    if (now - last_seen_[i] < hold_) mask |= bit;
  }
  return mask;
}

}  // namespace spread::firmware
