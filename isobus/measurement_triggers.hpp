#pragma once
// ISO 11783-10 measurement commands: a task controller asks the client to send a process data value by
// itself, per element and DDI,
//   4 time interval [ms]        every interval
//   5 distance interval [mm]    every so much distance driven
//   6 minimum threshold         once when the value crosses to at or above the threshold
//   7 maximum threshold         once when the value crosses to at or below the threshold
// (with both set: once on entering the window between them; a value already inside when the threshold is
// set is sent once at the next evaluation, as a crossing from unknown). Sending on every change while
// inside would flood the bus with a value that moves each loop step, and a TC asks for a threshold to
// learn when it is crossed.
//   8 change threshold          when the value moved at least this much since it was last sent
// An interval or change threshold of 0 cancels that trigger. The triggers live in a fixed table (no
// allocation in the loop); the TC's connection ending clears it.
#include <array>
#include <cstdint>
#include <cstdlib>
#include <optional>

#include "libspread/core/clock.hpp"

namespace spread::isobus {

struct MeasurementSubscription {
  std::uint8_t requester = 0xFF;  // the TC's address: values go there
  std::uint16_t element = 0;
  std::uint16_t ddi = 0;
  std::int32_t time_interval_ms = 0;       // 0: off
  std::int32_t distance_interval_mm = 0;   // 0: off
  std::optional<std::int32_t> minimum;     // command 6
  std::optional<std::int32_t> maximum;     // command 7
  std::int32_t change_threshold = 0;       // command 8; 0: off
  bool inside_thresholds = false;          // the value was within the thresholds at the last evaluation
  Nanoseconds next_time{};
  double distance_mm = 0.0;                // driven since the last distance-triggered value [mm]
  std::optional<std::int32_t> last_sent;
  bool in_use = false;
};

class MeasurementTriggers {
 public:
  static constexpr std::size_t kCapacity = 32;

  // Applies measurement command `command` (4-8) with `value`. False when the table is full.
  bool apply(std::uint8_t requester, std::uint8_t command, std::uint16_t element, std::uint16_t ddi,
             std::int32_t value, Nanoseconds now);
  void clear() { table_ = {}; }
  std::size_t active() const;

  // Calls `emit(subscription, value)` for every value due now. `value_of(ddi)` gives the current value
  // (nullopt: none); `driven_mm` is the distance driven since the last call.
  template <typename ValueOf, typename Emit>
  void evaluate(Nanoseconds now, double driven_mm, ValueOf value_of, Emit emit) {
    for (MeasurementSubscription& s : table_) {
      if (!s.in_use) continue;
      const std::optional<std::int32_t> v = value_of(s.ddi);
      if (!v) continue;
      bool due = false;
      if (s.time_interval_ms > 0 && now >= s.next_time) {
        due = true;
        s.next_time = now + std::chrono::milliseconds(s.time_interval_ms);
      }
      if (s.distance_interval_mm > 0) {
        s.distance_mm += driven_mm;
        if (s.distance_mm >= s.distance_interval_mm) {
          due = true;
          s.distance_mm = 0.0;
        }
      }
      if (s.minimum || s.maximum) {
        const bool inside = (!s.minimum || *v >= *s.minimum) && (!s.maximum || *v <= *s.maximum);
        if (inside && !s.inside_thresholds) due = true;  // crossing into the window: once
        s.inside_thresholds = inside;
      }
      if (s.change_threshold > 0 &&
          (!s.last_sent || std::llabs(static_cast<long long>(*v) - *s.last_sent) >= s.change_threshold)) {
        due = true;
      }
      if (!due) continue;
      s.last_sent = *v;
      emit(s, *v);
    }
  }

 private:
  std::array<MeasurementSubscription, kCapacity> table_{};
};

}  // namespace spread::isobus
