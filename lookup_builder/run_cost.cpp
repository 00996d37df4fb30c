#include "lookup_builder/run_cost.hpp"

#include <ctime>

namespace spread::lookup {

namespace {
double seconds_of(clockid_t id) {
  timespec t{};
  clock_gettime(id, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
clockid_t cpu_clock_id(CpuClock clock) {
  return clock == CpuClock::kThread ? CLOCK_THREAD_CPUTIME_ID : CLOCK_PROCESS_CPUTIME_ID;
}
}  // namespace

RunTimer::RunTimer(CpuClock clock)
    : clock_(clock),
      wall0_s_(seconds_of(CLOCK_MONOTONIC)),
      cpu0_s_(clock == CpuClock::kNone ? 0.0 : seconds_of(cpu_clock_id(clock))) {}

RunCost RunTimer::stop() const {
  RunCost cost;
  cost.wall_s = seconds_of(CLOCK_MONOTONIC) - wall0_s_;
  if (clock_ != CpuClock::kNone) cost.cpu_s = seconds_of(cpu_clock_id(clock_)) - cpu0_s_;
  return cost;
}

double cpu_s_per_1000_launches(const RunCost& cost, std::size_t launches) {
  if (cost.cpu_s < 0.0 || launches == 0) return -1.0;
  return 1000.0 * cost.cpu_s / static_cast<double>(launches);
}

}  // namespace spread::lookup
