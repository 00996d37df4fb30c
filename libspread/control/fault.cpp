#include "libspread/control/fault.hpp"

namespace spread::firmware {

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
