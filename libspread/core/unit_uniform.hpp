#pragma once
// A double uniform in [0, 1) from the top 53 bits of a 64-bit draw (e.g. std::mt19937_64): every value
// k · 2^−53 equally likely. Our own rather than std::uniform_real_distribution, whose output differs
// between standard libraries — seeded runs must give the same numbers everywhere (determinism).
#include <cstdint>

namespace spread {

inline double unit_uniform(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

}  // namespace spread
