#include "isobus/measurement_triggers.hpp"

namespace spread::isobus {

bool MeasurementTriggers::apply(std::uint8_t requester, std::uint8_t command, std::uint16_t element,
                                std::uint16_t ddi, std::int32_t value, Nanoseconds now) {
  MeasurementSubscription* slot = nullptr;
  for (MeasurementSubscription& s : table_) {
    if (s.in_use && s.requester == requester && s.element == element && s.ddi == ddi) {
      slot = &s;
      break;
    }
  }
  if (slot == nullptr) {
    for (MeasurementSubscription& s : table_) {
      if (!s.in_use) {
        slot = &s;
        *slot = MeasurementSubscription{};
        slot->in_use = true;
        slot->requester = requester;
        slot->element = element;
        slot->ddi = ddi;
        break;
      }
    }
  }
  if (slot == nullptr) return false;
  switch (command) {
    case 0x4:
      slot->time_interval_ms = value;
      slot->next_time = now;  // the first value goes out at once
      break;
    case 0x5:
      slot->distance_interval_mm = value;
      slot->distance_mm = 0.0;
      break;
    case 0x6:
      slot->minimum = value;
      slot->inside_thresholds = false;  // a value inside the new window is reported once
      break;
    case 0x7:
      slot->maximum = value;
      slot->inside_thresholds = false;
      break;
    case 0x8: slot->change_threshold = value; break;
    default: break;
  }
  return true;
}

std::size_t MeasurementTriggers::active() const {
  std::size_t n = 0;
  for (const MeasurementSubscription& s : table_) n += s.in_use ? 1u : 0u;
  return n;
}

}  // namespace spread::isobus
