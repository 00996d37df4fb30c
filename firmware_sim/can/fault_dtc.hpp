#pragma once
// How the ECU's faults appear in DM1 (ISO 11783-12 / SAE J1939-73): each fault code is a proprietary SPN
// (base + its code, docs/messages.md) with the failure mode that describes it.
#include <algorithm>
#include <cstdint>

#include "libspread/control/fault.hpp"
#include "isobus/dm1.hpp"

namespace spread::firmware::can {

constexpr isobus::Fmi fmi_for(Fault fault) {
  switch (fault) {
    case Fault::kLcmUndecodable:
    case Fault::kLcmWrongFingerprint:
    case Fault::kCanMalformedFrame:
    case Fault::kCanUnknownDdi:
    case Fault::kCanUnsupportedCommand:
    case Fault::kCanNotSettable:
    case Fault::kReplayParseError:
    case Fault::kCanNotFromTaskController:
      return isobus::Fmi::kReceivedNetworkDataError;
    case Fault::kSetpointOutOfRange:
    case Fault::kNotANumber:
    case Fault::kUnknownMaterial:
    case Fault::kUnknownMode:
    case Fault::kStaleSequence:
    case Fault::kSequenceJump:
    case Fault::kAutomaticUnavailable:
      return isobus::Fmi::kDataErratic;
    case Fault::kCommandTimeout:
    case Fault::kTaskControllerLost:
    case Fault::kSpeedUnavailable:
      return isobus::Fmi::kAbnormalUpdateRate;
    default:
      return isobus::Fmi::kConditionExists;
  }
}

inline isobus::Dtc dtc_for(Fault fault, std::uint64_t occurrences) {
  return isobus::Dtc{isobus::kProprietarySpnBase + static_cast<std::uint32_t>(fault), fmi_for(fault),
                     static_cast<std::uint8_t>(std::min<std::uint64_t>(occurrences, 126))};
}

}  // namespace spread::firmware::can
