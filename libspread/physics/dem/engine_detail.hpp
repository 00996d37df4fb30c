#pragma once
// What the engine's passes (engine.cpp and the pass files next to it) share; not part of the API.
#include <any>
#include <array>
#include <chrono>
#include <cstddef>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/force_variants.hpp"

namespace spread::dem {

// The passes' tables over kForceVariants (force_variants.hpp), entry I for variant I. Each table is built
// in the file that defines its pass (which makes that file compile every variant's instantiation) and
// read by force_dispatch.cpp.
using ForcePass = void (DemEngine::*)();
using ForcePassTable = std::array<ForcePass, kForceVariantCount>;
struct ForcePassTables {
  template <std::size_t... I>
  static constexpr ForcePassTable wall(std::index_sequence<I...>) {
    return {&DemEngine::wall_forces<PassVariant<I>>...};
  }
  template <std::size_t... I>
  static constexpr ForcePassTable particle(std::index_sequence<I...>) {
    return {&DemEngine::particle_forces<PassVariant<I>>...};
  }
  template <std::size_t... I>
  static constexpr ForcePassTable coeffs(std::index_sequence<I...>) {
    return {&DemEngine::update_pair_coeffs<VariantLaw<I>>...};
  }
};
extern const ForcePassTable kWallPasses;       // wall_pass.cpp
extern const ForcePassTable kParticlePasses;   // pair_pass.cpp
extern const ForcePassTable kCoeffUpdates;     // pair_coeffs_table.cpp

// The law's Coeffs table held in the engine's std::any (pair_coeffs_table.cpp fills it).
template <class Law>
const typename Law::Coeffs* coeffs_table(const std::any& table) {
  return std::any_cast<std::vector<typename Law::Coeffs>>(&table)->data();
}

}  // namespace spread::dem

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
// The threads of the enclosing parallel region (1 outside one, or without OpenMP).
inline int thread_count() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

}  // namespace spread::dem::detail
