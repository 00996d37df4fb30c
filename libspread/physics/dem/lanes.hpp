#pragma once
// Arithmetic written once for one contact (T = double), for two contacts side by side (T = Lanes2:
// two doubles in one SSE2 register, GCC/Clang vector extension), for four (T = Lanes4: one AVX register where
// the caller is compiled for it, else two SSE2 registers) or for eight (T = Lanes8: one AVX-512 register
// where the caller is compiled for it). The contact laws and the pair geometry are templates over T; the
// pair pass feeds the touching pairs two at a time, or in batches of eight (AVX-512) or four (AVX2, and the
// portable batched pass).
//
// Every operation acts lane by lane with the same IEEE operation as the scalar code (no fused
// multiply-add on the x86-64 baseline, sqrt and division correctly rounded), so a pair gives bit for bit
// the same force whether it went through a lane or alone. A branch of the scalar code becomes a
// select of both outcomes; the costly ones (a sqrt on slip) are computed only if some lane needs them.
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#endif

// Eight-lane values pass only between always-inline functions inside functions compiled for AVX-512 (the
// pair pass): no call ever takes or returns one, so the compilers' note that the ABI of such a call
// differs without AVX-512 does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace spread::dem::lanes {

using Lanes2 = double __attribute__((vector_size(16)));
using Mask2 = decltype(Lanes2{} < Lanes2{});  // lane all ones (true) or all zeros
using Lanes4 = double __attribute__((vector_size(32)));
using Mask4 = decltype(Lanes4{} < Lanes4{});
using Lanes8 = double __attribute__((vector_size(64)));
using Mask8 = decltype(Lanes8{} < Lanes8{});

// Broadcast: the same value in every lane.
template <class T> inline T splat(double v);
template <> inline double splat<double>(double v) { return v; }
template <> inline Lanes2 splat<Lanes2>(double v) { return Lanes2{v, v}; }
template <> inline Lanes4 splat<Lanes4>(double v) { return Lanes4{v, v, v, v}; }
template <> inline Lanes8 splat<Lanes8>(double v) { return Lanes8{v, v, v, v, v, v, v, v}; }

inline double sqrt(double v) { return std::sqrt(v); }
inline Lanes2 sqrt(Lanes2 v) {
#if defined(__SSE2__)
  return _mm_sqrt_pd(v);
#else
  return Lanes2{std::sqrt(v[0]), std::sqrt(v[1])};
#endif
}
// Four correctly rounded roots, two two-lane roots (in an AVX function GCC may join them; a portable one
// never calls into AVX code).
inline Lanes4 sqrt(Lanes4 v) {
  const Lanes2 low = sqrt(Lanes2(__builtin_shufflevector(v, v, 0, 1))), high = sqrt(Lanes2(__builtin_shufflevector(v, v, 2, 3)));
  return __builtin_shufflevector(low, high, 0, 1, 2, 3);
}
// Eight correctly rounded roots. The eight-lane code runs only inside AVX-512 functions. GCC: one
// instruction, in a function of that target that is not forced inline (a template of the default target
// calls it) and is inlined once the template is; no call to it is left (the pass's tests compare its bits
// with the portable pass). Clang refuses even such a call, so there, and off x86, four two-lane roots.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target("avx512f"))) inline Lanes8 sqrt(Lanes8 v) { return _mm512_mask_sqrt_pd(v, 0xFF, v); }
#else
inline Lanes8 sqrt(Lanes8 v) {
  for (int k = 0; k < 8; k += 2) {
    const Lanes2 s = sqrt(Lanes2{v[k], v[k + 1]});
    v[k] = s[0];
    v[k + 1] = s[1];
  }
  return v;
}
#endif

// select(m, a, b): a where m holds, else b.
inline double select(bool m, double a, double b) { return m ? a : b; }
inline Lanes2 select(Mask2 m, Lanes2 a, Lanes2 b) {
  return reinterpret_cast<Lanes2>((reinterpret_cast<Mask2>(a) & m) | (reinterpret_cast<Mask2>(b) & ~m));
}
inline Lanes4 select(Mask4 m, Lanes4 a, Lanes4 b) {
  return reinterpret_cast<Lanes4>((reinterpret_cast<Mask4>(a) & m) | (reinterpret_cast<Mask4>(b) & ~m));
}
inline Lanes8 select(Mask8 m, Lanes8 a, Lanes8 b) {
  return reinterpret_cast<Lanes8>((reinterpret_cast<Mask8>(a) & m) | (reinterpret_cast<Mask8>(b) & ~m));
}
inline bool both(bool a, bool b) { return a && b; }
inline Mask2 both(Mask2 a, Mask2 b) { return a & b; }
inline Mask4 both(Mask4 a, Mask4 b) { return a & b; }
inline Mask8 both(Mask8 a, Mask8 b) { return a & b; }
inline bool any(bool m) { return m; }
inline bool any(Mask2 m) { return (m[0] | m[1]) != 0; }
inline bool all(bool m) { return m; }
inline bool all(Mask2 m) { return (m[0] & m[1]) != 0; }
// Four and eight lanes folded in halves: 8 → 4 → 2 → 1.
inline bool any(Mask4 m) { return any(__builtin_shufflevector(m, m, 0, 1) | __builtin_shufflevector(m, m, 2, 3)); }
inline bool all(Mask4 m) { return all(__builtin_shufflevector(m, m, 0, 1) & __builtin_shufflevector(m, m, 2, 3)); }
inline bool any(Mask8 m) {
  const Mask4 h = __builtin_shufflevector(m, m, 0, 1, 2, 3) | __builtin_shufflevector(m, m, 4, 5, 6, 7);
  return any(__builtin_shufflevector(h, h, 0, 1) | __builtin_shufflevector(h, h, 2, 3));
}
inline bool all(Mask8 m) {
  const Mask4 h = __builtin_shufflevector(m, m, 0, 1, 2, 3) & __builtin_shufflevector(m, m, 4, 5, 6, 7);
  return all(__builtin_shufflevector(h, h, 0, 1) & __builtin_shufflevector(h, h, 2, 3));
}

// std::max(0.0, v) lane by lane: v where 0 < v, else +0 (a NaN becomes 0, as std::max(0.0, NaN)).
inline double max0(double v) { return 0.0 < v ? v : 0.0; }
inline Lanes2 max0(Lanes2 v) { return select(Lanes2{0.0, 0.0} < v, v, Lanes2{0.0, 0.0}); }
inline Lanes4 max0(Lanes4 v) { return select(splat<Lanes4>(0.0) < v, v, splat<Lanes4>(0.0)); }
inline Lanes8 max0(Lanes8 v) { return select(splat<Lanes8>(0.0) < v, v, splat<Lanes8>(0.0)); }

// A 3-vector of T (the contact kernel's own; Eigen's Vec3 stays the interface type).
template <class T>
struct V3 {
  T x, y, z;
};
template <class T> inline V3<T> operator+(const V3<T>& a, const V3<T>& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class T> inline V3<T> operator-(const V3<T>& a, const V3<T>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class T> inline V3<T> operator*(T s, const V3<T>& a) { return {s * a.x, s * a.y, s * a.z}; }
template <class T> inline V3<T> operator*(const V3<T>& a, T s) { return {a.x * s, a.y * s, a.z * s}; }
template <class T> inline T dot(const V3<T>& a, const V3<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T> inline T squared_norm(const V3<T>& a) { return dot(a, a); }
template <class T> inline V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T, class M> inline V3<T> select(M m, const V3<T>& a, const V3<T>& b) {
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}
template <class T> inline V3<T> zero3() { return {splat<T>(0.0), splat<T>(0.0), splat<T>(0.0)}; }

// Lane l of a two-lane value, and two scalars packed.
inline double lane(Lanes2 v, int l) { return v[l]; }
inline Lanes2 pack(double a, double b) { return Lanes2{a, b}; }
template <class T> inline V3<double> lane3(const V3<T>& v, int l) { return {v.x[l], v.y[l], v.z[l]}; }

}  // namespace spread::dem::lanes

#pragma GCC diagnostic pop
