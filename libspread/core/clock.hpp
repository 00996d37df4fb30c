#pragma once
// The ECU never reads the wall clock itself: every component takes a Clock, so tests drive time by
// hand (ManualClock) and get bit-identical runs, while the executable uses the monotonic clock.
#include <chrono>
#include <thread>

namespace spread {

using Nanoseconds = std::chrono::nanoseconds;

class Clock {
 public:
  virtual ~Clock() = default;
  // Monotonic time since an arbitrary epoch [ns].
  virtual Nanoseconds now() const = 0;
  // Blocks (real clock) or jumps (simulated clock) until now() >= deadline.
  virtual void sleep_until(Nanoseconds deadline) = 0;
  // True when time only moves through sleep_until/advance: I/O must then be polled without waiting.
  virtual bool is_simulated() const = 0;
};

class SteadyClock final : public Clock {
 public:
  Nanoseconds now() const override {
    return std::chrono::duration_cast<Nanoseconds>(std::chrono::steady_clock::now().time_since_epoch());
  }
  void sleep_until(Nanoseconds deadline) override {
    const Nanoseconds remaining = deadline - now();
    if (remaining > Nanoseconds::zero()) std::this_thread::sleep_for(remaining);
  }
  bool is_simulated() const override { return false; }
};

class ManualClock final : public Clock {
 public:
  explicit ManualClock(Nanoseconds start = Nanoseconds::zero()) : now_(start) {}
  Nanoseconds now() const override { return now_; }
  void sleep_until(Nanoseconds deadline) override {
    if (deadline > now_) now_ = deadline;
  }
  bool is_simulated() const override { return true; }
  void advance(Nanoseconds by) { now_ += by; }

 private:
  Nanoseconds now_;
};

inline double to_seconds(Nanoseconds t) { return std::chrono::duration<double>(t).count(); }
inline Nanoseconds from_seconds(double seconds) {
  return std::chrono::duration_cast<Nanoseconds>(std::chrono::duration<double>(seconds));
}

}  // namespace spread
