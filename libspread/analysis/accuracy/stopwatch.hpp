#pragma once
// Timing of the study's measured points in CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID):
// every measured point runs on one thread, and on a shared machine the wall clock also counts the time
// other processes hold the core (measured: 9 s wall for 1.4 s CPU under load), which CPU time does not.
// A point is repeated until it has used at least `min_total_s` (at least once), and the median of the
// repetitions is taken: it resists the odd slow repetition (cache, frequency) better than the mean.
#include <algorithm>
#include <vector>

#include <time.h>

namespace spread::accuracy::detail {

struct CpuInstant {
  double s = 0.0;
};
inline CpuInstant cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return {static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec)};
}
inline double seconds_since(CpuInstant start) { return cpu_now().s - start.s; }

// Median wall time (s) of one call of `work`.
template <class Work>
double median_time_s(Work&& work, double min_total_s, int max_repeats = 50) {
  std::vector<double> times;
  const CpuInstant begin = cpu_now();
  do {
    const CpuInstant start = cpu_now();
    work();
    times.push_back(seconds_since(start));
  } while (seconds_since(begin) < min_total_s && static_cast<int>(times.size()) < max_repeats);
  std::nth_element(times.begin(), times.begin() + static_cast<long>(times.size() / 2), times.end());
  return times[times.size() / 2];
}

}  // namespace spread::accuracy::detail
