#include "libspread/analysis/metrics/wide_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "libspread/core/cpu_features.hpp"

namespace spread::metrics {
namespace {

void require_scratch(std::size_t have, std::size_t need, const char* what) {
  if (have < need) {
    throw std::invalid_argument(std::string(what) + ": scratch has " + std::to_string(have) + " values, needs " +
                                std::to_string(need));
  }
}

}  // namespace

std::size_t wide_kernel_scratch_size(const TrayLayout& trays) { return 5 * (static_cast<std::size_t>(trays.tray_count) + 2); }
std::size_t wide_kernel_sums_size(const TrayLayout& trays, std::size_t gradient_count) {
  return 4 * gradient_count * (static_cast<std::size_t>(trays.tray_count) + 2);
}

double accumulate_wide_kernel(std::span<const double> x_m, std::span<const double> mass_kg, const TrayLayout& trays,
                              double kernel_half_width_m, std::span<double> tray_mass_kg, std::span<double> scratch) {
  require_scratch(scratch.size(), wide_kernel_scratch_size(trays), "accumulate_wide_kernel");
  const long edges = trays.tray_count;  // edges 0..T
  const double left_m = trays.left_edge_m();
  const double inverse_width = 1.0 / trays.tray_width_m;
  const double half_width_trays = kernel_half_width_m * inverse_width;
  const double beta = trays.tray_width_m / kernel_half_width_m;
  // The edges in blocks of `block` edges, each block's cubics in t = j − c_B about its own middle edge c_B:
  // |t| stays within block/2, so the coefficients stay small (rounding ~1e-16 (block β / 2)³ of a landing's
  // mass) wherever the landing is, and a kernel (at most 2h/w + 1 edges) spans at most two blocks.
  int block_bits = 6;  // a power of two: the block of an edge is a shift, not a division
  while (static_cast<double>(1L << block_bits) < 2.0 * half_width_trays + 4.0) ++block_bits;
  const long block = 1L << block_bits, half_block = block / 2;
  // Difference arrays per edge j: the four coefficients and the constant 1 right of a kernel, at
  // [5 j, 5 j + 5). A coefficient added at an edge holds to the end of its block (where the sweep restarts)
  // unless taken off before.
  const std::size_t stride = static_cast<std::size_t>(edges) + 2;
  std::fill(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(5 * stride), 0.0);
  const auto d = [&](long edge) { return &scratch[5 * static_cast<std::size_t>(edge)]; };
  double lost_kg = 0.0, finite_kg = 0.0;
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    const double x = x_m[i], m = mass_kg[i];
    if (!std::isfinite(x)) {
      lost_kg += m;
      continue;
    }
    finite_kg += m;
    // Edges strictly inside (x − h, x + h), in trays from the left edge; at u = ±1 the cubic and the
    // constants agree, so an edge on the boundary may go either way.
    const double u = (x - left_m) * inverse_width;
    const long first = kernel_edge_floor(u - half_width_trays, edges) + 1;
    const long last = kernel_edge_ceil(u + half_width_trays, edges) - 1;
    if (last < 0) {  // wholly left of the layout: F = 1 on every edge
      d(0)[4] += m;
      continue;
    }
    if (first > edges) continue;  // wholly right: F = 0 on every edge
    const long a = std::max(first, 0L), b = std::min(last, edges);
    for (long start = (a >> block_bits) << block_bits; start <= b; start += block) {
      const long from = std::max(a, start), to = std::min(b, start + block - 1);
      // F at edge j = α + β t with t = j − c_B: α = (e_{c_B} − x)/h = (c_B − u) β.
      const double alpha = (static_cast<double>(start + half_block) - u) * beta;
      const double p[4] = {0.25 * (2.0 + 3.0 * alpha - alpha * alpha * alpha), 0.75 * beta * (1.0 - alpha * alpha),
                           -0.75 * alpha * beta * beta, -0.25 * beta * beta * beta};
      double* begin = d(from);
      for (int r = 0; r < 4; ++r) begin[r] += m * p[r];
      if (to + 1 < start + block) {
        double* end = d(to + 1);
        for (int r = 0; r < 4; ++r) end[r] -= m * p[r];
      }
    }
    if (b + 1 <= edges) d(b + 1)[4] += m;
  }
  double run[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  double previous = 0.0, first_edge = 0.0;
  for (long j = 0; j <= edges; ++j) {
    const long in_block = j & (block - 1);
    if (in_block == 0) run[0] = run[1] = run[2] = run[3] = 0.0;  // a new block, its own cubics
    const double* here = d(j);
    for (int r = 0; r < 5; ++r) run[r] += here[r];
    const double t = static_cast<double>(in_block - half_block);
    const double cumulative = run[4] + ((run[3] * t + run[2]) * t + run[1]) * t + run[0];
    if (j == 0) {
      first_edge = cumulative;
    } else {
      // A tray's mass is an increase of the cumulative mass; where no kernel covers it, rounding may leave
      // −1e-17 instead of 0 (found by the capi_predict fuzzer).
      tray_mass_kg[static_cast<std::size_t>(j - 1)] += std::max(0.0, cumulative - previous);
    }
    previous = cumulative;
  }
  // Mass left of the first edge and right of the last (previous is the cumulative at the last edge).
  return lost_kg + first_edge + (finite_kg - previous);
}

void wide_kernel_sums(std::span<const std::span<const double>> gradients, const TrayLayout& trays,
                      std::span<double> sums) {
  const std::size_t count = gradients.size();
  require_scratch(sums.size(), wide_kernel_sums_size(trays, count), "wide_kernel_sums");
  for (std::size_t g = 0; g < count; ++g) wide_kernel_sums_of(gradients[g], trays, sums, count, g);
}

void wide_kernel_sums_of(std::span<const double> gradient, const TrayLayout& trays, std::span<double> sums,
                         std::size_t gradient_count, std::size_t slot) {
  require_scratch(sums.size(), wide_kernel_sums_size(trays, gradient_count), "wide_kernel_sums_of");
  const long edges = trays.tray_count;
  const long centre = edges / 2;
  const std::size_t count = gradient_count, g = slot;
  if (slot >= count || gradient.size() != static_cast<std::size_t>(edges)) {
    throw std::invalid_argument("wide_kernel_sums_of: gradient " + std::to_string(slot) + " of " +
                                std::to_string(count) + " has " + std::to_string(gradient.size()) + " values for " +
                                std::to_string(edges) + " trays");
  }
  // S_r(j) of gradient g at [(j · 4 + r) · count + g]: a landing's dot products read two runs of 4 · count
  // values.
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  for (long j = 0; j <= edges + 1; ++j) {
    for (int r = 0; r < 4; ++r) sums[(static_cast<std::size_t>(j) * 4 + static_cast<std::size_t>(r)) * count + g] = s[r];
    if (j > edges) break;
    const double before = j > 0 ? gradient[static_cast<std::size_t>(j - 1)] : 0.0;
    const double here = j < edges ? gradient[static_cast<std::size_t>(j)] : 0.0;
    const double dj = before - here;
    const double t = static_cast<double>(j - centre);
    s[0] += dj;
    s[1] += dj * t;
    s[2] += dj * t * t;
    s[3] += dj * t * t * t;
  }
}

WideKernelDots::WideKernelDots(double kernel_half_width_m, const TrayLayout& trays, std::span<const double> sums,
                               std::size_t gradient_count)
    : sums_(sums),
      count_(gradient_count),
      edges_(trays.tray_count),
      centre_(trays.tray_count / 2),
      left_m_(trays.left_edge_m()),
      inverse_width_(1.0 / trays.tray_width_m),
      half_width_trays_(kernel_half_width_m / trays.tray_width_m),
      beta_(trays.tray_width_m / kernel_half_width_m) {
  require_scratch(sums.size(), wide_kernel_sums_size(trays, gradient_count), "WideKernelDots");
  set_avx(true);
}

bool WideKernelDots::set_avx(bool enabled) {
  avx_ = enabled && cpu_has_avx();
  return avx_;
}

#if defined(__x86_64__) || defined(__i386__)
__attribute__((target("avx"))) void WideKernelDots::combine_avx(std::size_t count, const double (&p)[4], bool inside,
                                                                const double* at_a, const double* past_b,
                                                                const double* past_end, double* out) {
  typedef double Double4 __attribute__((vector_size(32)));
  combine_wide_kernel_dots<Double4>(count, p, inside, at_a, past_b, past_end, out);
}
#endif

void WideKernelDots::operator()(double x, double* out) const { dots<0>(x, out); }

}  // namespace spread::metrics
