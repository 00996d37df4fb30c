#pragma once
// Processor features the numeric kernels choose their registers by at run time, so that one portable
// build (baseline x86-64) still uses the wider registers of the processor it runs on. A kernel taking
// them must give the same bits as its portable path (the same operations lane by lane, no fused
// multiply-add): the choice may change the speed, never a result. (A function compiled for "avx512f" may
// use FMA instructions; the build turns the compiler's contraction of a · b + c into them off,
// -ffp-contract=off in CMakeLists.txt.)
#include <atomic>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace spread {

// The widest registers the run-time choices may take: the processor's widest unless limited (tests limit
// it to compare every path's bits; an object that chose at its construction keeps its choice), or the
// environment: SPREAD_REGISTERS=baseline|avx|avx2|avx512 at start-up (a machine with AVX-512 then gives the
// figures of a processor without, e.g. bench/peers/lammps_drum/compare.sh with SPREAD_REGISTERS=avx2).
enum class Registers : int { kBaseline = 0, kAvx = 1, kAvx2 = 2, kAvx512 = 3 };
namespace detail {
// SPREAD_REGISTERS read once; unset or empty: no limit. Throws std::invalid_argument naming an unknown value.
inline Registers registers_from_environment() {
  const char* env = std::getenv("SPREAD_REGISTERS");
  const std::string name = env != nullptr ? env : "";
  if (name.empty() || name == "avx512") return Registers::kAvx512;
  if (name == "baseline") return Registers::kBaseline;
  if (name == "avx") return Registers::kAvx;
  if (name == "avx2") return Registers::kAvx2;
  throw std::invalid_argument("SPREAD_REGISTERS: '" + name + "' is not baseline, avx, avx2 or avx512");
}
inline std::atomic<int> widest_registers{static_cast<int>(registers_from_environment())};
}  // namespace detail
inline void limit_registers(Registers widest) {
  detail::widest_registers.store(static_cast<int>(widest), std::memory_order_relaxed);
}
inline bool registers_allowed(Registers registers) {
  return static_cast<int>(registers) <= detail::widest_registers.load(std::memory_order_relaxed);
}

namespace detail {
// The processor's features, read once: whether it (and the operating system, which must save their
// registers) has AVX (256-bit registers of 4 doubles or 8 floats), AVX2 (their integer operations too) and
// AVX-512 Foundation (512-bit registers of 8 doubles or 16 floats). None off x86.
struct CpuFeatures {
  bool avx = false;
  bool avx2 = false;
  bool avx512f = false;
};
inline const CpuFeatures& cpu_features() {
  static const CpuFeatures features = [] {
    CpuFeatures f;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    f.avx = __builtin_cpu_supports("avx") != 0;
    f.avx2 = __builtin_cpu_supports("avx2") != 0;
    f.avx512f = __builtin_cpu_supports("avx512f") != 0;
#endif
    return f;
  }();
  return features;
}
}  // namespace detail

// Whether the kernels may take AVX registers: the processor has them and they are allowed.
inline bool cpu_has_avx() { return detail::cpu_features().avx && registers_allowed(Registers::kAvx); }
// Whether the kernels may take AVX2 registers: the processor has them and they are allowed.
inline bool cpu_has_avx2() { return detail::cpu_features().avx2 && registers_allowed(Registers::kAvx2); }
// Whether the kernels may take AVX-512 registers: the processor has them and they are allowed.
inline bool cpu_has_avx512f() { return detail::cpu_features().avx512f && registers_allowed(Registers::kAvx512); }

}  // namespace spread
