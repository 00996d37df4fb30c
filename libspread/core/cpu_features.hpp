#pragma once
// Processor features the numeric kernels choose their registers by at run time, so that one portable
// build (baseline x86-64) still uses the wider registers of the processor it runs on. A kernel taking
// them must give the same bits as its portable path (the same operations lane by lane, no fused
// multiply-add): the choice may change the speed, never a result.

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

}  // namespace spread
