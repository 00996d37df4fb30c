#include "libspread/analysis/metrics/wide_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::metrics {
namespace {

// A landing's kernel on the layout's edges 0..T: F = 0 left of edge `first`, the cubic p on edges
// first..last, 1 right of `last` (first > last: no edge inside the kernel; last < 0: the kernel lies
// wholly left of the layout, first > T: wholly right).
struct EdgeCubic {
  double p[4];
  long first, last;
};

long floor_edge(double position, long edges) { return WideKernelDots::floor_edge(position, edges); }
long ceil_edge(double position, long edges) { return WideKernelDots::ceil_edge(position, edges); }

EdgeCubic edge_cubic(double x, double h, const TrayLayout& trays, long centre) {
  const double w = trays.tray_width_m;
  const double left_m = trays.left_edge_m();
  const long edges = trays.tray_count;
  EdgeCubic e{};
  // Edges strictly inside (x − h, x + h); at u = ±1 the cubic and the constants agree, so an edge on the
  // boundary may go either way.
  e.first = floor_edge((x - h - left_m) / w, edges) + 1;
  e.last = ceil_edge((x + h - left_m) / w, edges) - 1;
  const double alpha = (left_m + static_cast<double>(centre) * w - x) / h;
  const double beta = w / h;
  e.p[0] = 0.25 * (2.0 + 3.0 * alpha - alpha * alpha * alpha);
  e.p[1] = 0.75 * beta * (1.0 - alpha * alpha);
  e.p[2] = -0.75 * alpha * beta * beta;
  e.p[3] = -0.25 * beta * beta * beta;
  return e;
}

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
  const long centre = edges / 2;
  const std::size_t stride = static_cast<std::size_t>(edges) + 2;
  std::fill(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(5 * stride), 0.0);
  // Difference arrays: coefficient r at [r · stride, …), the constant 1 right of a kernel at [4 · stride, …).
  const auto d = [&](int array, long edge) -> double& { return scratch[static_cast<std::size_t>(array) * stride + static_cast<std::size_t>(edge)]; };
  double lost_kg = 0.0, finite_kg = 0.0;
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    const double x = x_m[i], m = mass_kg[i];
    if (!std::isfinite(x)) {
      lost_kg += m;
      continue;
    }
    finite_kg += m;
    const EdgeCubic e = edge_cubic(x, kernel_half_width_m, trays, centre);
    if (e.last < 0) {  // wholly left of the layout: F = 1 on every edge
      d(4, 0) += m;
      continue;
    }
    if (e.first > edges) continue;  // wholly right: F = 0 on every edge
    const long a = std::max(e.first, 0L), b = std::min(e.last, edges);
    if (a <= b) {
      for (int r = 0; r < 4; ++r) {
        d(r, a) += m * e.p[r];
        d(r, b + 1) -= m * e.p[r];
      }
    }
    if (b + 1 <= edges) d(4, b + 1) += m;
  }
  double run[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  double previous = 0.0, first_edge = 0.0;
  for (long j = 0; j <= edges; ++j) {
    for (int r = 0; r < 5; ++r) run[r] += d(r, j);
    const double t = static_cast<double>(j - centre);
    const double cumulative = run[4] + ((run[3] * t + run[2]) * t + run[1]) * t + run[0];
    if (j == 0) {
      first_edge = cumulative;
    } else {
      // A tray's mass is an increase of the cumulative mass; where no kernel covers it, rounding of the
      // large coefficients may leave −1e-17 instead of 0 (found by the capi_predict fuzzer).
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
  const long edges = trays.tray_count;
  const long centre = edges / 2;
  // S_r(j) of gradient g at [(j · 4 + r) · count + g]: a landing's dot products read two runs of 4 · count
  // values.
  for (std::size_t g = 0; g < count; ++g) {
    const std::span<const double> gradient = gradients[g];
    if (gradient.size() != static_cast<std::size_t>(edges)) {
      throw std::invalid_argument("wide_kernel_sums: gradient " + std::to_string(g) + " has " +
                                  std::to_string(gradient.size()) + " values for " + std::to_string(edges) + " trays");
    }
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
}

void WideKernelDots::operator()(double x, double* out) const {
  switch (count_) {
    case 1: return dots<1>(x, out);
    case 2: return dots<2>(x, out);
    case 4: return dots<4>(x, out);
    case 8: return dots<8>(x, out);
    default: return dots<0>(x, out);
  }
}

}  // namespace spread::metrics
