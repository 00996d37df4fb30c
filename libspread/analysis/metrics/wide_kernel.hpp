#pragma once
// The Epanechnikov kernel (accumulate_transverse_kernel) over many trays at a cost independent of its
// width. Tray k's share of a landing's kernel is F(u_{k+1}) − F(u_k), u_j = (e_j − x)/h at the layout's
// edges e_j = L + j w, F the kernel's CDF: 0 for u ≤ −1, 1 for u ≥ 1 and the cubic (2 + 3u − u³)/4
// between. On the edges inside the kernel F is one cubic in the edge index j, so in t = j − c (c an edge
// of reference)
//   F = p0 + p1 t + p2 t² + p3 t³,  α = (e_c − x)/h, β = w/h,
//   p0 = (2 + 3α − α³)/4,  p1 = 3β(1 − α²)/4,  p2 = −3αβ²/4,  p3 = −β³/4.
// Binning: the cumulative mass at each edge, C_j = Σ_i m_i F_i(j), is a sum of such cubics over the
// landings whose kernel holds edge j plus the masses of those wholly left of it; adding each landing's
// coefficients to difference arrays at the first and past the last edge it covers and one sweep over the
// edges gives every C_j — O(landings + trays) instead of O(landings × trays per kernel). The edges are
// taken in blocks of 64 or more, each with its own reference edge (its middle), so that |t| and α stay
// small: the result differs from the tray-by-tray sum by about 1e-16 (block β / 2)³ of a landing's mass,
// below 1e-12 of it for any kernel of two trays or more (a tray's mass is never negative: a rounding below
// zero is taken as zero).
// Dot products (the standard errors' Σ_k g_k K_k(x)): by parts, Σ_k g_k (F_{k+1} − F_k) = Σ_j d_j F_j
// with d_j = g_{j−1} − g_j (g_{−1} = g_T = 0), and with prefix sums S_r(j) = Σ_{j' < j} d_{j'} t_{j'}^r (c
// the layout's middle edge) the kernel's part is Σ_r p_r (S_r(b + 1) − S_r(a)) over its edges a..b, plus
// S_0(T + 1) − S_0(b + 1) for the edges right of it (F = 1): O(1) per landing. Here the coefficients grow
// like (distance from the middle / h)³ while F stays in [0, 1], so a dot differs from the tray-by-tray sum
// by about 1e-16 (x/h)³ of the gradient's size — 1e-11 for a landing 20 m out under a 0.8 m kernel, which
// does not move a standard error. They are taken for every kernel: several gradients at once, each
// landing's cubic computed once for all of them.
// Kernels narrower than kWideKernelTrays tray widths keep the tray-by-tray binning (a few trays each).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <span>

#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::metrics {

// Half-widths of at least this many trays are binned by difference arrays (where that is the cheaper).
inline constexpr double kWideKernelTrays = 2.0;
inline bool wide_kernel(double kernel_half_width_m, const TrayLayout& trays) {
  return kernel_half_width_m >= kWideKernelTrays * trays.tray_width_m && trays.tray_count > 0;
}
// Scratch values the binning needs (five difference arrays over the edges); the dot products need
// wide_kernel_sums_size.
std::size_t wide_kernel_scratch_size(const TrayLayout& trays);
std::size_t wide_kernel_sums_size(const TrayLayout& trays, std::size_t gradient_count = 1);

// accumulate_transverse_kernel's result (tray masses added to tray_mass_kg, the lost mass returned) by
// difference arrays; scratch.size() >= wide_kernel_scratch_size(trays). Does not allocate.
double accumulate_wide_kernel(std::span<const double> x_m, std::span<const double> mass_kg, const TrayLayout& trays,
                              double kernel_half_width_m, std::span<double> tray_mass_kg, std::span<double> scratch);

// The prefix sums S_0..S_3 of each gradient over the trays (each gradient.size() == tray_count) into `sums`
// (wide_kernel_sums_size(trays, gradients.size()) values), for wide_kernel_dots.
void wide_kernel_sums(std::span<const std::span<const double>> gradients, const TrayLayout& trays,
                      std::span<double> sums);
// The same for one gradient, the slot-th of gradient_count whose sums `sums` holds.
void wide_kernel_sums_of(std::span<const double> gradient, const TrayLayout& trays, std::span<double> sums,
                         std::size_t gradient_count, std::size_t slot);
// dots[g] = Σ_k gradient_g[k] K_k(x) for the gradient_count gradients whose sums (wide_kernel_sums) it
// reads; all 0 for a non-finite x. Each dot is summed in the same order whatever the count, so it is the
// same bit for bit. Set up once per pass (the divisions), then called per landing.
// floor and ceil of a position in trays clamped to [−2, T + 2] (T = `edges`), without the libm calls
// baseline x86-64 makes of std::floor and std::ceil: a kernel's edges beyond the layout only decide
// "wholly left or right".
inline long kernel_edge_floor(double position, long edges) {
  position = std::clamp(position, -2.0, static_cast<double>(edges) + 2.0);
  const long truncated = static_cast<long>(position);
  return static_cast<double>(truncated) > position ? truncated - 1 : truncated;
}
inline long kernel_edge_ceil(double position, long edges) {
  position = std::clamp(position, -2.0, static_cast<double>(edges) + 2.0);
  const long truncated = static_cast<long>(position);
  return static_cast<double>(truncated) < position ? truncated + 1 : truncated;
}

// The gradients' part of WideKernelDots::dots, `Lanes` (a vector of doubles) at a time: per gradient the
// edges right of the kernel (F = 1), then the cubic's terms over its edges, in the same order whatever the
// width of Lanes, so the same bits.
template <typename Lanes>
__attribute__((always_inline)) inline void combine_wide_kernel_dots(std::size_t count, const double (&p)[4],
                                                                   bool inside, const double* at_a,
                                                                   const double* past_b, const double* past_end,
                                                                   double* out) {
  constexpr std::size_t kWidth = sizeof(Lanes) / sizeof(double);
  std::size_t g = 0;
  for (; g + kWidth <= count; g += kWidth) {
    Lanes end, right, left, sum;
    std::memcpy(&end, past_end + g, sizeof end);
    std::memcpy(&right, past_b + g, sizeof right);
    sum = end - right;
    if (inside) {
      for (std::size_t r = 0; r < 4; ++r) {
        std::memcpy(&right, past_b + r * count + g, sizeof right);
        std::memcpy(&left, at_a + r * count + g, sizeof left);
        sum += p[r] * (right - left);
      }
    }
    std::memcpy(out + g, &sum, sizeof sum);
  }
  for (; g < count; ++g) {
    double sum = past_end[g] - past_b[g];
    if (inside) {
      for (std::size_t r = 0; r < 4; ++r) sum += p[r] * (past_b[r * count + g] - at_a[r * count + g]);
    }
    out[g] = sum;
  }
}

class WideKernelDots {
 public:
  WideKernelDots(double kernel_half_width_m, const TrayLayout& trays, std::span<const double> sums,
                 std::size_t gradient_count);
  void operator()(double x, double* dots) const;
  // Sums in AVX registers where the processor has them (the default) or in SSE ones: the same bits.
  // Returns whether AVX is now used.
  bool set_avx(bool enabled);
  // The same with the count known at compile time (kCount == gradient_count; 0: read at run time), the
  // gradients two at a time in SSE registers.
  template <std::size_t kCount>
  void dots(double x, double* out) const;
  // dots() with the gradients `Lanes` (a vector of doubles) at a time, inlined into the caller: a caller
  // compiled for AVX passes four doubles and avx = false (its own registers are AVX's), other callers two
  // and avx_ (then AVX through a call where the processor has it).
  template <std::size_t kCount, typename Lanes>
  void dots_in(double x, double* out, bool avx) const;
  bool avx() const { return avx_; }
  // What dots() reads for a landing at x: its cubic's coefficients p and where its edges a..b lie in the
  // sums (at_a: edge a's, past_b: edge b + 1's, past_end: past the last edge's; `inside`: a <= b). False
  // when every dot is 0 (x not finite, or its kernel wholly off the layout). For passes that combine the
  // sums themselves (combine_wide_kernel_dots' order of operations).
  struct Reach {
    double p[4];
    const double* at_a;
    const double* past_b;
    const double* past_end;
    bool inside;
  };
  bool reach(double x, Reach& out) const;


 private:
  // The gradients' part of dots() four at a time in AVX registers (on x86 processors that have AVX): each
  // lane takes the same multiplications and additions in the same order, without fused multiply-adds, so
  // the same bits as in SSE.
  static void combine_avx(std::size_t count, const double (&p)[4], bool inside, const double* at_a,
                          const double* past_b, const double* past_end, double* out);
  bool avx_ = false;
  std::span<const double> sums_;
  std::size_t count_;
  long edges_, centre_;
  double left_m_, inverse_width_, half_width_trays_, beta_;
};

__attribute__((always_inline)) inline bool WideKernelDots::reach(double x, Reach& out) const {
  if (!std::isfinite(x)) return false;
  // The edges inside the kernel (wide_kernel.cpp's edge_cubic with the divisions taken once per pass):
  // u = (x − L)/w in trays, α = (e_c − x)/h = (c − u) β.
  const double u = (x - left_m_) * inverse_width_;
  const long first = kernel_edge_floor(u - half_width_trays_, edges_) + 1;
  const long last = kernel_edge_ceil(u + half_width_trays_, edges_) - 1;
  // Wholly left of the layout (F = 1 everywhere: Σ d_j = g_{−1} − g_T = 0) or wholly right (F = 0).
  if (last < 0 || first > edges_) return false;
  const long a = std::max(first, 0L), b = std::min(last, edges_);
  out.at_a = &sums_[static_cast<std::size_t>(a) * 4 * count_];
  out.past_b = &sums_[static_cast<std::size_t>(b + 1) * 4 * count_];
  out.past_end = &sums_[static_cast<std::size_t>(edges_ + 1) * 4 * count_];
  out.inside = a <= b;
  const double alpha = (static_cast<double>(centre_) - u) * beta_;
  out.p[0] = 0.25 * (2.0 + 3.0 * alpha - alpha * alpha * alpha);
  out.p[1] = 0.75 * beta_ * (1.0 - alpha * alpha);
  out.p[2] = -0.75 * alpha * beta_ * beta_;
  out.p[3] = -0.25 * beta_ * beta_ * beta_;
  return true;
}

template <std::size_t kCount, typename Lanes>
__attribute__((always_inline)) inline void WideKernelDots::dots_in(double x, double* out, bool avx) const {
  const std::size_t count = kCount != 0 ? kCount : count_;
  for (std::size_t g = 0; g < count; ++g) out[g] = 0.0;
  Reach r;
  if (!reach(x, r)) return;
#if defined(__x86_64__) || defined(__i386__)
  if (avx) {
    combine_avx(count, r.p, r.inside, r.at_a, r.past_b, r.past_end, out);
    return;
  }
#endif
  combine_wide_kernel_dots<Lanes>(count, r.p, r.inside, r.at_a, r.past_b, r.past_end, out);
}

template <std::size_t kCount>
void WideKernelDots::dots(double x, double* out) const {
  typedef double Double2 __attribute__((vector_size(16)));
  dots_in<kCount, Double2>(x, out, avx_);
}

}  // namespace spread::metrics
