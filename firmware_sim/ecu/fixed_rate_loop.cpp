#include "firmware_sim/ecu/fixed_rate_loop.hpp"

#include <poll.h>

#include <cmath>
#include <algorithm>
#include <stdexcept>
#include <string>

namespace spread::firmware {

FixedRateLoop::FixedRateLoop(Clock& clock, double rate_hz) : clock_(clock) {
  if (!std::isfinite(rate_hz) || !(rate_hz > 0.0) || rate_hz > 1000.0) {
    throw std::invalid_argument("FixedRateLoop: loop rate must be in (0, 1000] Hz, got " + std::to_string(rate_hz));
  }
  period_ = from_seconds(1.0 / rate_hz);
}

void FixedRateLoop::tick(Ecu& ecu, LoopIo& io) {
  if (!next_tick_) {
    last_step_ = clock_.now();
    next_tick_ = last_step_ + period_;
  }
  const Nanoseconds deadline = *next_tick_;
  if (clock_.is_simulated()) {
    // Simulated time: all input that is already there belongs to this tick, then time jumps.
    io.pump(Nanoseconds::zero());
    clock_.sleep_until(deadline);
  } else {
    for (Nanoseconds now = clock_.now(); now < deadline; now = clock_.now()) io.pump(deadline - now);
  }

  const Nanoseconds started = clock_.now();
  const double dt_s = to_seconds(started - last_step_);
  last_step_ = started;
  ecu.step(dt_s);
  io.after_step(ecu.status());
  const Nanoseconds finished = clock_.now();
  ++statistics_.ticks;
  if (finished - started > statistics_.worst_step) statistics_.worst_step = finished - started;

  *next_tick_ += period_;
  if (finished >= *next_tick_) {
    // Missed at least one tick: count it and re-phase instead of bursting to catch up.
    ++statistics_.overruns;
    ecu.record_fault(Fault::kLoopOverrun);
    *next_tick_ = finished + period_;
  }
}

void LoopIoGroup::pump(Nanoseconds max_wait) {
  if (members_.size() == 1) {
    members_.front()->pump(max_wait);
    return;
  }
  if (max_wait > Nanoseconds::zero()) {
    pollfd fds[8];
    nfds_t count = 0;
    bool all_waitable = true;
    for (const LoopIo* io : members_) {
      if (io->wait_fd() < 0 || count == 8) {
        all_waitable = false;
      } else {
        fds[count++] = pollfd{io->wait_fd(), POLLIN, 0};
      }
    }
    // A member without a descriptor cannot be waited on: poll it at 1 ms granularity instead.
    const auto ms = std::chrono::ceil<std::chrono::milliseconds>(max_wait).count();
    const int timeout_ms = all_waitable ? static_cast<int>(ms) : static_cast<int>(std::min<long long>(ms, 1));
    ::poll(fds, count, timeout_ms);
  }
  for (LoopIo* io : members_) io->pump(Nanoseconds::zero());
}

void LoopIoGroup::after_step(const EcuStatus& status) {
  for (LoopIo* io : members_) io->after_step(status);
}

void FixedRateLoop::run(Ecu& ecu, LoopIo& io, std::optional<Nanoseconds> duration, const std::atomic<bool>* stop) {
  if (!duration && stop == nullptr) {
    throw std::invalid_argument("FixedRateLoop::run: needs a duration or a stop flag");
  }
  const Nanoseconds end = duration ? clock_.now() + *duration : Nanoseconds::max();
  while (clock_.now() < end && (stop == nullptr || !stop->load(std::memory_order_relaxed))) tick(ecu, io);
}

}  // namespace spread::firmware
