#pragma once
// The ECU's fixed-rate loop (default 20 Hz): between ticks the transports are serviced, at each tick
// the ECU steps once and the transports publish. Time comes only from the injected Clock: with a
// ManualClock a run is a pure function of its inputs.
#include <atomic>
#include <cstdint>
#include <optional>
#include <vector>

#include "libspread/control/ecu.hpp"
#include "libspread/core/clock.hpp"

namespace spread::firmware {

// What the loop drives besides the ECU: message transports.
class LoopIo {
 public:
  virtual ~LoopIo() = default;
  // Handle pending input, waiting at most `max_wait` for some (zero: do not block).
  virtual void pump(Nanoseconds max_wait) = 0;
  // Called after every ECU step with the fresh status (publish, answer triggers, ...).
  virtual void after_step(const EcuStatus& status) = 0;
  // A file descriptor that becomes readable when input arrives (-1: none), so that several
  // transports can wait together (LoopIoGroup).
  virtual int wait_fd() const { return -1; }
};

// Several transports driven by one loop: waits on all their descriptors at once.
class LoopIoGroup final : public LoopIo {
 public:
  void add(LoopIo& io) { members_.push_back(&io); }
  void pump(Nanoseconds max_wait) override;
  void after_step(const EcuStatus& status) override;

 private:
  std::vector<LoopIo*> members_;
};

struct LoopStatistics {
  std::int64_t ticks = 0;
  std::int64_t overruns = 0;       // ticks whose step finished after the next tick was due
  Nanoseconds worst_step{};        // longest ECU step + publish, measured on the injected clock
};

class FixedRateLoop {
 public:
  // rate_hz: loop frequency [Hz], in (0, 1000].
  FixedRateLoop(Clock& clock, double rate_hz);

  Nanoseconds period() const { return period_; }
  // Runs ticks until `duration` (from the call) has elapsed, or `stop` becomes true, whichever first.
  // No duration and no stop flag is refused (it would never return).
  void run(Ecu& ecu, LoopIo& io, std::optional<Nanoseconds> duration, const std::atomic<bool>* stop = nullptr);
  // Exactly one tick: service I/O until the tick is due, step, publish.
  void tick(Ecu& ecu, LoopIo& io);

  const LoopStatistics& statistics() const { return statistics_; }

 private:
  Clock& clock_;
  Nanoseconds period_;
  std::optional<Nanoseconds> next_tick_;
  Nanoseconds last_step_{};
  LoopStatistics statistics_;
};

}  // namespace spread::firmware
