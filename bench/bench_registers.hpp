#pragma once
// SPREAD_BENCH_REGISTERS=baseline|avx|avx2|avx512 limits the registers the run-time kernel choices may take
// (libspread/core/cpu_features.hpp), so one machine gives the figures of the portable path beside its
// widest; unset: the processor's widest.
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "libspread/core/cpu_features.hpp"

namespace spread::bench {

// The limit named by the environment ("widest" when unset), applied; throws on an unknown name.
inline std::string limit_registers_from_env() {
  const char* env = std::getenv("SPREAD_BENCH_REGISTERS");
  const std::string name = env != nullptr ? env : "";
  if (name.empty()) return "widest";
  if (name == "baseline") limit_registers(Registers::kBaseline);
  else if (name == "avx") limit_registers(Registers::kAvx);
  else if (name == "avx2") limit_registers(Registers::kAvx2);
  else if (name == "avx512") limit_registers(Registers::kAvx512);
  else throw std::invalid_argument("SPREAD_BENCH_REGISTERS: '" + name + "' is not baseline, avx, avx2 or avx512");
  return name;
}

}  // namespace spread::bench
