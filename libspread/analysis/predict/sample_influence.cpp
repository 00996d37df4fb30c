#include "libspread/analysis/predict/sample_influence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libspread/analysis/metrics/wide_kernel.hpp"

namespace spread::predict {
namespace {

// Σ_k gradient[k] K_k(x): the kernel's share in each tray, weighted by the gradient.
double kernel_dot(double x, std::span<const double> gradient, const metrics::TrayLayout& trays, double h) {
  if (!std::isfinite(x)) return 0.0;
  const double left_m = trays.left_edge_m();
  const double w = trays.tray_width_m;
  const long last = static_cast<long>(trays.tray_count) - 1;
  if (h == 0.0) {
    const double position = (x - left_m) / w;
    if (!(position >= 0.0 && position < trays.tray_count)) return 0.0;
    return gradient[static_cast<std::size_t>(position)];
  }
  const long first = std::max(0L, static_cast<long>(std::floor((x - h - left_m) / w)));
  const long end = std::min(last, static_cast<long>(std::floor((x + h - left_m) / w)));
  double sum = 0.0;
  double below = metrics::epanechnikov_cdf((left_m + static_cast<double>(first) * w - x) / h);
  for (long k = first; k <= end; ++k) {
    const double above = metrics::epanechnikov_cdf((left_m + static_cast<double>(k + 1) * w - x) / h);
    sum += gradient[static_cast<std::size_t>(k)] * (above - below);
    below = above;
  }
  return sum;
}

// Share of a landing's kernel mass left of a tray edge at `edge_m` (point masses: tray k is the half-open
// [edge_k, edge_k+1), so a landing on an edge belongs to the tray to its right).
double share_left_of_edge(double x, double edge_m, double h, double inv_h) {
  if (h == 0.0) return x < edge_m ? 1.0 : 0.0;
  return metrics::epanechnikov_cdf((edge_m - x) * inv_h);
}

// A quantile x_q as throw_extent reads it off the trays: inside tray `tray`, a `fraction` of the tray
// width from its left edge (the tray's mass spread uniformly across it).
struct TrayQuantile {
  long tray = 0;
  double fraction = 0.0;
};

TrayQuantile tray_quantile(double x_q, const metrics::TrayLayout& trays) {
  const double w = trays.tray_width_m;
  const double position = (x_q - trays.left_edge_m()) / w;
  TrayQuantile q;
  q.tray = std::min(static_cast<long>(trays.tray_count) - 1, std::max(0L, static_cast<long>(position)));
  q.fraction = std::clamp(position - static_cast<double>(q.tray), 0.0, 1.0);
  return q;
}

// A landing's contribution to the quantile equation C(x_q) = q·S, C the cumulative tray mass (linear
// within a tray) and S the mass in the trays: its kernel's share in the trays left of x_q's tray plus
// that tray's share times `fraction` (left), and its share in all trays (inside). This is what the
// estimator sees — not the share of the kernel left of x_q itself: with point masses the two differ for
// every landing in x_q's tray, and at a steep pattern edge (all of that tray's landings on one side of
// x_q) the latter gave every sample the same influence and a standard error of zero.
struct QuantileShare {
  double left = 0.0, inside = 0.0;
};

QuantileShare quantile_share(double x, const TrayQuantile& q, const metrics::TrayLayout& trays, double h,
                             double inv_h) {
  if (!std::isfinite(x)) return {};
  const double w = trays.tray_width_m;
  const double layout_left_m = trays.left_edge_m();
  const double tray_left_m = layout_left_m + static_cast<double>(q.tray) * w;
  // Each share once (a cdf per edge): left of the layout, of x_q's tray, of its right edge, of the layout.
  const double left_of_layout = share_left_of_edge(x, layout_left_m, h, inv_h);
  const double left_of_tray = share_left_of_edge(x, tray_left_m, h, inv_h);
  const double below = left_of_tray - left_of_layout;
  const double in_tray = share_left_of_edge(x, tray_left_m + w, h, inv_h) - left_of_tray;
  const double inside = share_left_of_edge(x, -layout_left_m, h, inv_h) - left_of_layout;
  return {below + q.fraction * in_tray, inside};
}

// kernel_dot for several gradients at once: sums[g] = Σ_k gradients[g][k] K_k(x), each summed in the same
// order as kernel_dot, so every sum is bit for bit kernel_dot's.
void kernel_dots(double x, std::span<const std::span<const double>> gradients, const metrics::TrayLayout& trays,
                 double h, double* sums) {
  const std::size_t count = gradients.size();
  for (std::size_t g = 0; g < count; ++g) sums[g] = 0.0;
  if (!std::isfinite(x)) return;
  const double left_m = trays.left_edge_m();
  const double w = trays.tray_width_m;
  const long last = static_cast<long>(trays.tray_count) - 1;
  if (h == 0.0) {
    const double position = (x - left_m) / w;
    if (!(position >= 0.0 && position < trays.tray_count)) return;
    for (std::size_t g = 0; g < count; ++g) sums[g] = gradients[g][static_cast<std::size_t>(position)];
    return;
  }
  const long first = std::max(0L, static_cast<long>(std::floor((x - h - left_m) / w)));
  const long end = std::min(last, static_cast<long>(std::floor((x + h - left_m) / w)));
  double below = metrics::epanechnikov_cdf((left_m + static_cast<double>(first) * w - x) / h);
  for (long k = first; k <= end; ++k) {
    const double above = metrics::epanechnikov_cdf((left_m + static_cast<double>(k + 1) * w - x) / h);
    const double share = above - below;
    for (std::size_t g = 0; g < count; ++g) sums[g] += gradients[g][static_cast<std::size_t>(k)] * share;
    below = above;
  }
}

// Calls visit(s, landing) for every landing of sample s, sample by sample in order (s = 0 … n − 1), and
// done(s) after each sample's landings.
template <typename Visit, typename Done>
void for_each_sample(const SampleInfluence& in, Visit visit, Done done) {
  const std::size_t n = in.sample_count;
  if (in.blocks.empty()) {
    for (std::size_t s = 0; s < n; ++s) {
      for (unsigned d = 0; d < in.landings_per_sample; ++d) visit(s + d * n);
      done();
    }
    return;
  }
  for (const SampleBlock& block : in.blocks) {
    for (std::size_t j = 0; j < block.count; ++j) {
      for (std::size_t first : block.first_landing) {
        if (first != SampleBlock::kNoLanding) visit(first + j);
      }
      done();
    }
  }
}

template <typename PerLanding>
double influence_standard_error(const SampleInfluence& in, PerLanding per_landing) {
  const std::size_t n = in.sample_count;
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0, sum_squares = 0.0;
  double z = 0.0;
  for_each_sample(
      in, [&](std::size_t l) { z += in.weight[l] * per_landing(in.x_m[l]); },
      [&] {
        z *= static_cast<double>(n);
        sum += z;
        sum_squares += z * z;
        z = 0.0;
      });
  const double mean = sum / static_cast<double>(n);
  const double variance_of_z = std::max(0.0, (sum_squares - mean * sum) / static_cast<double>(n - 1));
  return std::sqrt(variance_of_z / static_cast<double>(n));
}

}  // namespace

bool SampleInfluence::wide() const {
  return metrics::wide_kernel(kernel_half_width_m, trays) && scratch.size() >= metrics::wide_kernel_sums_size(trays);
}

double SampleInfluence::standard_error(std::span<const double> gradient) const {
  if (wide()) {
    metrics::wide_kernel_sums(gradient, trays, scratch);
    return influence_standard_error(
        *this, [&](double x) { return metrics::wide_kernel_dot(x, kernel_half_width_m, trays, scratch); });
  }
  return influence_standard_error(*this, [&](double x) { return kernel_dot(x, gradient, trays, kernel_half_width_m); });
}

void SampleInfluence::standard_errors(std::span<const std::span<const double>> gradients,
                                      std::span<double> out) const {
  // Gradients in use (non-empty), compacted; the others report NaN.
  std::span<const double> used[kMaxGradients];
  std::size_t slot[kMaxGradients];
  std::size_t count = 0;
  for (std::size_t g = 0; g < gradients.size() && g < kMaxGradients; ++g) {
    out[g] = std::numeric_limits<double>::quiet_NaN();
    if (!gradients[g].empty()) {
      used[count] = gradients[g];
      slot[count] = g;
      ++count;
    }
  }
  const std::size_t n = sample_count;
  if (n < 2 || count == 0) return;
  if (wide()) {
    for (std::size_t g = 0; g < count; ++g) out[slot[g]] = standard_error(used[g]);
    return;
  }
  // influence_standard_error, per gradient, with the same operations in the same order.
  double sum[kMaxGradients] = {}, sum_squares[kMaxGradients] = {};
  double z[kMaxGradients], dots[kMaxGradients];
  const std::span<const std::span<const double>> active(used, count);
  for (std::size_t g = 0; g < count; ++g) z[g] = 0.0;
  for_each_sample(
      *this,
      [&](std::size_t l) {
        kernel_dots(x_m[l], active, trays, kernel_half_width_m, dots);
        for (std::size_t g = 0; g < count; ++g) z[g] += weight[l] * dots[g];
      },
      [&] {
        for (std::size_t g = 0; g < count; ++g) {
          z[g] *= static_cast<double>(n);
          sum[g] += z[g];
          sum_squares[g] += z[g] * z[g];
          z[g] = 0.0;
        }
      });
  for (std::size_t g = 0; g < count; ++g) {
    const double mean = sum[g] / static_cast<double>(n);
    const double variance_of_z = std::max(0.0, (sum_squares[g] - mean * sum[g]) / static_cast<double>(n - 1));
    out[slot[g]] = std::sqrt(variance_of_z / static_cast<double>(n));
  }
}

double SampleInfluence::throw_width_standard_error(std::span<const double> tray_mass,
                                                   const metrics::ThrowExtent& extent, double mass_fraction) const {
  double total = 0.0;
  for (double m : tray_mass) total += m > 0.0 ? m : 0.0;
  const double w = trays.tray_width_m;
  auto density_at = [&](double x) {  // of the normalised distribution, per m
    const double position = (x - trays.left_edge_m()) / w;
    const long k = std::min(static_cast<long>(trays.tray_count) - 1, std::max(0L, static_cast<long>(position)));
    return tray_mass[static_cast<std::size_t>(k)] / (total * w);
  };
  const double q_left = 0.5 * (1.0 - mass_fraction), q_right = 0.5 * (1.0 + mass_fraction);
  const double f_left = density_at(extent.left_m), f_right = density_at(extent.right_m);
  if (!(total > 0.0) || !(f_left > 0.0) || !(f_right > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  // Width = x_right − x_left. Perturbing the trays by a landing's shares moves x_q by
  // (q·inside − left) / f(x_q) per unit of landing share (from C(x_q) = q·S; inside = 1 for a landing
  // whose kernel lies within the layout).
  const TrayQuantile at_left = tray_quantile(extent.left_m, trays), at_right = tray_quantile(extent.right_m, trays);
  const double h = kernel_half_width_m, inv_h = h > 0.0 ? 1.0 / h : 0.0;
  return influence_standard_error(*this, [&](double x) {
    const QuantileShare r = quantile_share(x, at_right, trays, h, inv_h);
    const QuantileShare l = quantile_share(x, at_left, trays, h, inv_h);
    return (q_right * r.inside - r.left) / f_right - (q_left * l.inside - l.left) / f_left;
  });
}

double lateral_sd_m(std::span<const double> x_m, std::span<const double> weight) {
  double sw = 0.0, swx = 0.0;
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    if (std::isfinite(x_m[i])) {
      sw += weight[i];
      swx += weight[i] * x_m[i];
    }
  }
  if (!(sw > 0.0)) return 0.0;
  const double mean = swx / sw;
  double swd = 0.0;
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    if (std::isfinite(x_m[i])) swd += weight[i] * (x_m[i] - mean) * (x_m[i] - mean);
  }
  return std::sqrt(swd / sw);
}

}  // namespace spread::predict
