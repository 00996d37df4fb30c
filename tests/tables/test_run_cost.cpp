// A row's cost as lookup_builder reports it: the run's CPU time on the clock the sweep chose, and that per
// 1,000 launches in the log line of each finished run.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "lookup_builder/progress.hpp"
#include "lookup_builder/run_cost.hpp"

namespace spread::lookup {
namespace {

// Work the optimiser cannot drop: about 0.1 s of CPU.
double busy_work() {
  volatile double sum = 0.0;
  for (int k = 0; k < 30'000'000; ++k) sum = sum + std::sqrt(static_cast<double>(k));
  return sum;
}

TEST(RunCost, ThreadClockMeasuresTheRunsWorkAndNoMoreThanItsWallTime) {
  const RunTimer timer(CpuClock::kThread);
  busy_work();
  const RunCost cost = timer.stop();
  EXPECT_GT(cost.cpu_s, 0.01);
  EXPECT_LE(cost.cpu_s, cost.wall_s + 0.01);  // one thread cannot spend more CPU than wall time
}

TEST(RunCost, WithoutACpuClockTheCostIsNotMeasuredAndNotPerLaunch) {
  const RunCost cost = RunTimer(CpuClock::kNone).stop();
  EXPECT_LT(cost.cpu_s, 0.0);
  EXPECT_LT(cpu_s_per_1000_launches(cost, 4000), 0.0);
  EXPECT_LT(cpu_s_per_1000_launches(RunCost{1.0, 2.0}, 0), 0.0);
  EXPECT_DOUBLE_EQ(cpu_s_per_1000_launches(RunCost{1.0, 2.0}, 4000), 0.5);
}

TEST(RunCost, TheLogLineNamesTheCpuTimePerThousandLaunches) {
  std::ostringstream log;
  Progress progress(&log, false, 2);
  progress.finished("Urea @ 600 rpm", "4000 samples (dem)", 3.0, 2.5, 0.75);
  progress.finished("Urea @ 750 rpm", "4000 samples (dem)", 3.0);
  EXPECT_NE(log.str().find("[1/2] Urea @ 600 rpm: 4000 samples (dem), 3.00 s (CPU 2.50 s, 0.75 s per 1000 launches)"),
            std::string::npos)
      << log.str();
  EXPECT_NE(log.str().find("[2/2] Urea @ 750 rpm: 4000 samples (dem), 3.00 s\n"), std::string::npos) << log.str();
}

}  // namespace
}  // namespace spread::lookup
