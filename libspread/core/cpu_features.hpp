#pragma once
// Processor features the numeric kernels choose their registers by at run time, so that one portable
// build (baseline x86-64) still uses the wider registers of the processor it runs on. A kernel taking
// them must give the same bits as its portable path (the same operations lane by lane, no fused
// multiply-add): the choice may change the speed, never a result. (A function compiled for "avx512f" may
// use FMA instructions; the build turns the compiler's contraction of a · b + c into them off,
// -ffp-contract=off in CMakeLists.txt.)

namespace spread {

// Whether the processor (and the operating system, which must save its registers) has AVX: 256-bit
// registers of 4 doubles or 8 floats. Always false off x86.
inline bool cpu_has_avx() {
#if defined(__x86_64__) || defined(__i386__)
  static const bool avx = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx") != 0;
  }();
  return avx;
#else
  return false;
#endif
}

// Whether the processor (and the operating system) has AVX-512 Foundation: 512-bit registers of 8 doubles
// or 16 floats. Always false off x86.
inline bool cpu_has_avx512f() {
#if defined(__x86_64__) || defined(__i386__)
  static const bool avx512f = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") != 0;
  }();
  return avx512f;
#else
  return false;
#endif
}

}  // namespace spread
