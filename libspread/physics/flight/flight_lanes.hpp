#pragma once
// Arithmetic written once for one flight (T = double) or for kFlightLanes flights side by side
// (T = FlightLanes: GCC/Clang vector extension; four doubles, two SSE2 registers on the x86-64 baseline:
// measured a little faster than two, no faster with eight), as the DEM's contact lanes
// (libspread/physics/dem/lanes.hpp). Every operation acts lane by lane with the same IEEE operation
// as the scalar code — no fused multiply-add on the baseline, sqrt and division correctly rounded, and no
// libm call (power_06459 below is plain arithmetic) — so a flight gives bit for bit the same landing
// whether it flew in a lane or alone.
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

// Four lanes are two SSE2 registers on the x86-64 baseline: GCC notes that a 32-byte vector passed by value
// would use another ABI with AVX. Everything here is inline and within the flight library, never an
// interface between objects built with different flags.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace spread::flight::detail {

inline constexpr int kFlightLanes = 4;
using FlightLanes = double __attribute__((vector_size(8 * kFlightLanes)));
using FlightLaneBits = std::int64_t __attribute__((vector_size(8 * kFlightLanes)));

template <class T> inline T splat(double v);
template <> inline double splat<double>(double v) { return v; }
template <> inline FlightLanes splat<FlightLanes>(double v) {
  FlightLanes r;  // each lane set (not 0 + v: that turns −0 into +0)
  for (int l = 0; l < kFlightLanes; ++l) r[l] = v;
  return r;
}

// Bits of a double and back (T = double: std::uint64_t as std::int64_t).
inline std::int64_t as_bits(double v) { return std::bit_cast<std::int64_t>(v); }
inline FlightLaneBits as_bits(FlightLanes v) { return reinterpret_cast<FlightLaneBits>(v); }
inline double from_bits(std::int64_t b) { return std::bit_cast<double>(b); }
inline FlightLanes from_bits(FlightLaneBits b) { return reinterpret_cast<FlightLanes>(b); }

// sqrt lane by lane (correctly rounded, as std::sqrt).
inline double lane_sqrt(double v) { return std::sqrt(v); }
inline FlightLanes lane_sqrt(FlightLanes v) {
  FlightLanes r;
#if defined(__SSE2__)
  // sqrtpd on each register's two lanes (std::sqrt per lane keeps a branch to the errno path for each).
  static_assert(sizeof(FlightLanes) % sizeof(__m128d) == 0);
  for (std::size_t part = 0; part < sizeof(FlightLanes); part += sizeof(__m128d)) {
    __m128d pair;
    std::memcpy(&pair, reinterpret_cast<const char*>(&v) + part, sizeof pair);
    pair = _mm_sqrt_pd(pair);
    std::memcpy(reinterpret_cast<char*>(&r) + part, &pair, sizeof pair);
  }
#else
  for (int l = 0; l < kFlightLanes; ++l) r[l] = std::sqrt(v[l]);
#endif
  return r;
}

// if_greater where a > b, else otherwise, lane by lane.
inline double select_greater(double a, double b, double if_greater, double otherwise) {
  return a > b ? if_greater : otherwise;
}
inline FlightLanes select_greater(FlightLanes a, FlightLanes b, FlightLanes if_greater, FlightLanes otherwise) {
  const FlightLaneBits m = a > b;
  return from_bits((as_bits(if_greater) & m) | (as_bits(otherwise) & ~m));
}

// Re^0.6459 for the Haider–Levenspiel drag (seed Eq. 32) as 2^(0.6459 log2 Re), in plain arithmetic so
// that lanes can run it (glibc's exp/log are scalar calls, most of a flight's cost). Relative error a few
// ulp (below 1e-15), the accuracy of exp(0.6459 log Re) itself:
//   log: Re = 2^e m, m ∈ [√½, √2); ln m = 2 atanh s = 2s Σ_{k=0..9} s^{2k}/(2k+1), s = (m−1)/(m+1),
//        |s| <= 0.1716: the first term left out is below 4e-18.
//   exp: y = 0.6459 log2 Re = n + f, n = round(y), |f| <= 1/2; 2^f = Σ_{k=0..13} g^k/k!, g = f ln 2,
//        |g| <= 0.347: the first term left out is below 4e-18; 2^n put into the exponent bits.
// Polynomials by Estrin's scheme (short dependency chains). Re = 0 gives ~1e-199 (24 + that is 24:
// C_D Re stays the Stokes 24 exactly, as exp(−∞) did); Re < 2^−1022 (never, in flight) the same.
template <class T>
[[gnu::always_inline]] inline T power_06459(T re) {
  using Bits = decltype(as_bits(re));
  constexpr std::int64_t kMantissa = 0x000FFFFFFFFFFFFF;
  constexpr std::int64_t kOneBits = 0x3FF0000000000000;
  constexpr double kRoundMagic = 6755399441055744.0;  // 1.5 · 2^52: y + it rounds y to an integer
  const Bits bits = as_bits(re);
  // Exponent e (as a double, via the same magic number: exact for |e| < 2^51) and mantissa m ∈ [1, 2).
  const Bits exponent_bits = ((bits >> 52) & 0x7FF) - 1023;
  T e = from_bits(exponent_bits + as_bits(splat<T>(kRoundMagic))) - kRoundMagic;
  T m = from_bits((bits & kMantissa) | kOneBits);
  const T sqrt2 = splat<T>(1.4142135623730951);
  e = select_greater(m, sqrt2, e + 1.0, e);
  m = select_greater(m, sqrt2, m * 0.5, m);
  const T s = (m - 1.0) / (m + 1.0);
  const T z = s * s;
  const T z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
  const T p01 = 1.0 + z * (1.0 / 3.0), p23 = 1.0 / 5.0 + z * (1.0 / 7.0), p45 = 1.0 / 9.0 + z * (1.0 / 11.0);
  const T p67 = 1.0 / 13.0 + z * (1.0 / 15.0), p89 = 1.0 / 17.0 + z * (1.0 / 19.0);
  const T atanh_sum = (p01 + z2 * p23) + z4 * (p45 + z2 * p67) + z8 * p89;
  constexpr double kExponent = 0.6459;
  constexpr double kExponentTimesTwoLog2E = 2.0 * 0.6459 * 1.4426950408889634;  // 0.6459 · 2/ln 2
  const T y = kExponent * e + kExponentTimesTwoLog2E * (s * atanh_sum);
  const T shifted = y + kRoundMagic;
  const T n = shifted - kRoundMagic;
  const T g = (y - n) * 0.6931471805599453;
  const T g2 = g * g, g4 = g2 * g2, g8 = g4 * g4;
  const T q01 = 1.0 + g, q23 = 1.0 / 2.0 + g * (1.0 / 6.0), q45 = 1.0 / 24.0 + g * (1.0 / 120.0);
  const T q67 = 1.0 / 720.0 + g * (1.0 / 5040.0), q89 = 1.0 / 40320.0 + g * (1.0 / 362880.0);
  const T q1011 = 1.0 / 3628800.0 + g * (1.0 / 39916800.0), q1213 = 1.0 / 479001600.0 + g * (1.0 / 6227020800.0);
  const T two_to_f = ((q01 + g2 * q23) + g4 * (q45 + g2 * q67)) + g8 * ((q89 + g2 * q1011) + g4 * q1213);
  // 2^n: n is the low bits of `shifted` (two's complement), |n| <= 1100; biased into the exponent field.
  const Bits n_int = as_bits(shifted) - as_bits(splat<T>(kRoundMagic));
  return two_to_f * from_bits((n_int + 1023) << 52);
}

}  // namespace spread::flight::detail

#pragma GCC diagnostic pop
