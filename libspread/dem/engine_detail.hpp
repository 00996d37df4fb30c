#pragma once
// What the engine's passes (engine.cpp and the pass files next to it) share; not part of the API.
#include <chrono>

#ifdef _OPENMP
#include <omp.h>
#endif

// Every (contact law, rotation, rolling) combination of the force pass, as X(Law, kRotation, kRolling):
// the pass files instantiate their templates for each, and force_dispatch.cpp picks one per call.
#define SPREAD_DEM_FORCE_VARIANTS(X)                                                                      \
  X(HertzThornton, false, false) X(HertzThornton, false, true) X(HertzThornton, true, false)              \
  X(HertzThornton, true, true) X(LinearSpringDashpot, false, false) X(LinearSpringDashpot, false, true)   \
  X(LinearSpringDashpot, true, false) X(LinearSpringDashpot, true, true)

namespace spread::dem::detail {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// A parallel region per pass costs a few microseconds of fork/join; below a few thousand items (and
// on a loaded machine) it costs more than it saves.
inline constexpr long long kMinParallelItems = 4096;

inline int thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

}  // namespace spread::dem::detail
