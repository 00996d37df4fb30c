#pragma once
// What one run of a sweep cost: its wall time and, where it can be told apart from the other runs, the CPU
// time spent on it -- the figure a table's builder pays per row (docs/building-tables.md "What a row costs").
// The CPU time is the calling thread's when the run computes on that thread alone (one DEM thread per run,
// as `--jobs N` gives), the process's when runs go one at a time (their OpenMP threads included), and not
// measured when several runs share the process on threads of their own.
#include <cstddef>

namespace spread::lookup {

struct RunCost {
  double wall_s = 0.0;
  double cpu_s = -1.0;  // < 0: not measured
};

enum class CpuClock { kThread, kProcess, kNone };

class RunTimer {
 public:
  explicit RunTimer(CpuClock clock);
  RunCost stop() const;

 private:
  CpuClock clock_;
  double wall0_s_;
  double cpu0_s_;
};

// CPU seconds per 1,000 launches (the run's samples); < 0 when the CPU time was not measured or there are none.
double cpu_s_per_1000_launches(const RunCost& cost, std::size_t launches);

}  // namespace spread::lookup
