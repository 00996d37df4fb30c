#include "libspread/analysis/predict/sample_influence.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "libspread/analysis/metrics/wide_kernel.hpp"
#include "libspread/core/cpu_features.hpp"

namespace spread::predict {
namespace {

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

// sums[g] = Σ_k gradients[g][k] K_k(x) tray by tray, each summed in the same order whatever the count of
// gradients.
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

// The standard error of the mean of n samples' z from Σ z and Σ z²: sqrt(Var z / n), Var z the sample
// variance (n − 1), never below 0 through rounding.
inline double standard_error_of(double sum, double sum_squares, std::size_t n) {
  const double mean = sum / static_cast<double>(n);
  const double variance_of_z = std::max(0.0, (sum_squares - mean * sum) / static_cast<double>(n - 1));
  return std::sqrt(variance_of_z / static_cast<double>(n));
}

// Calls visit(s, landing) for every landing of sample s, sample by sample in order (s = 0 … n − 1), and
// done(s) after each sample's landings.
template <typename Visit, typename Done>
__attribute__((always_inline)) inline void for_each_sample(const SampleInfluence& in, Visit visit, Done done) {
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

// The standard errors of `count` statistics in one pass over the landings: dots(x, d) writes each
// statistic's Σ_k g_k K_k(x) into d[0..count).
template <std::size_t kCount = 0, typename Dots>
__attribute__((always_inline)) inline void influence_pass(const SampleInfluence& in, std::size_t count_at_run_time, Dots dots, double* out) {
  const std::size_t count = kCount != 0 ? kCount : count_at_run_time;
  const std::size_t n = in.sample_count;
  double sum[SampleInfluence::kMaxGradients] = {}, sum_squares[SampleInfluence::kMaxGradients] = {};
  double z[SampleInfluence::kMaxGradients] = {}, d[SampleInfluence::kMaxGradients];
  for_each_sample(
      in,
      [&](std::size_t l) __attribute__((always_inline)) {
        dots(in.x_m[l], d);
        for (std::size_t g = 0; g < count; ++g) z[g] += in.weight[l] * d[g];
      },
      [&]() __attribute__((always_inline)) {
        for (std::size_t g = 0; g < count; ++g) {
          z[g] *= static_cast<double>(n);
          sum[g] += z[g];
          sum_squares[g] += z[g] * z[g];
          z[g] = 0.0;
        }
      });
  for (std::size_t g = 0; g < count; ++g) out[g] = standard_error_of(sum[g], sum_squares[g], n);
}

// The pass over a wide kernel's dots: here through dots() (AVX sums by a call per landing where the
// processor has them), or compiled for AVX with the sums inlined (the same operations, so the same bits).
template <std::size_t kCount>
void wide_kernel_pass(const SampleInfluence& in, std::size_t count, const metrics::WideKernelDots& dots,
                      double* se) {
  influence_pass<kCount>(
      in, count, [&dots](double x, double* d) __attribute__((always_inline)) { dots.template dots<kCount>(x, d); },
      se);
}
#if defined(__x86_64__) || defined(__i386__)
// Four doubles side by side: one AVX register (GCC/Clang vector extension).
typedef double FourDoubles __attribute__((vector_size(32)));
template <std::size_t kCount>
__attribute__((target("avx"))) void wide_kernel_pass_avx(const SampleInfluence& in, std::size_t count,
                                                          const metrics::WideKernelDots& dots, double* se) {
  influence_pass<kCount>(
      in, count,
      [&dots](double x, double* d) __attribute__((always_inline)) { dots.template dots_in<kCount, FourDoubles>(x, d, false); },
      se);
}
// The same for a multiple of the lanes' width of gradients with every running value in registers:
// influence_pass' operations in its order, lane by lane (combine_wide_kernel_dots' for the dots), so the
// same bits — but its arrays of z and sums, indexed by loops, went through memory on every landing. Lanes:
// a vector of doubles (four: AVX, eight: AVX-512), kVectors of them.
template <typename Lanes, std::size_t kVectors>
__attribute__((always_inline)) inline void pass_in_registers(const SampleInfluence& in,
                                                            const metrics::WideKernelDots& dots, double* se) {
  constexpr std::size_t kWidth = sizeof(Lanes) / sizeof(double);
  constexpr std::size_t kCount = kWidth * kVectors;
  // Into an out-parameter: a lambda returning a wide vector would change its ABI.
  const auto load = [](const double* at, Lanes& v) __attribute__((always_inline)) { std::memcpy(&v, at, sizeof v); };
  const double n = static_cast<double>(in.sample_count);
  Lanes z[kVectors] = {}, sum[kVectors] = {}, sum_squares[kVectors] = {};
  for_each_sample(
      in,
      [&](std::size_t l) __attribute__((always_inline)) {
        Lanes d[kVectors] = {};
        metrics::WideKernelDots::Reach r;
        if (dots.reach(in.x_m[l], r)) {
#pragma GCC unroll 2
          for (std::size_t v = 0; v < kVectors; ++v) {
            Lanes end, right, left;
            load(r.past_end + kWidth * v, end);
            load(r.past_b + kWidth * v, right);
            d[v] = end - right;
            if (r.inside) {
#pragma GCC unroll 4
              for (std::size_t k = 0; k < 4; ++k) {
                load(r.past_b + k * kCount + kWidth * v, right);
                load(r.at_a + k * kCount + kWidth * v, left);
                d[v] += r.p[k] * (right - left);
              }
            }
          }
        }
        const double weight = in.weight[l];
#pragma GCC unroll 2
        for (std::size_t v = 0; v < kVectors; ++v) z[v] += weight * d[v];
      },
      [&]() __attribute__((always_inline)) {
#pragma GCC unroll 2
        for (std::size_t v = 0; v < kVectors; ++v) {
          z[v] *= n;
          sum[v] += z[v];
          sum_squares[v] += z[v] * z[v];
          z[v] = Lanes{};
        }
      });
  double sums[kCount], squares[kCount];
  std::memcpy(sums, sum, sizeof sums);
  std::memcpy(squares, sum_squares, sizeof squares);
  for (std::size_t g = 0; g < kCount; ++g) se[g] = standard_error_of(sums[g], squares[g], in.sample_count);
}
typedef double EightDoubles __attribute__((vector_size(64)));
// 4 or 8 gradients in one or two AVX registers.
template <std::size_t kVectors>
__attribute__((target("avx"))) void wide_kernel_pass_avx_registers(const SampleInfluence& in,
                                                                    const metrics::WideKernelDots& dots, double* se) {
  pass_in_registers<FourDoubles, kVectors>(in, dots, se);
}
// 8 gradients in one AVX-512 register: half the instructions and reads of two AVX registers.
__attribute__((target("avx512f"))) void wide_kernel_pass_avx512(const SampleInfluence& in,
                                                                const metrics::WideKernelDots& dots, double* se) {
  pass_in_registers<EightDoubles, 1>(in, dots, se);
}
#endif

}  // namespace

std::size_t InfluencePass::capacity(const SampleInfluence& influence) {
  if (influence.trays.tray_count <= 0) return 0;
  const std::size_t per_gradient = influence.kernel_half_width_m > 0.0
                                       ? metrics::wide_kernel_sums_size(influence.trays, 1)
                                       : static_cast<std::size_t>(influence.trays.tray_count);
  return std::min(SampleInfluence::kMaxGradients, influence.scratch.size() / per_gradient);
}

InfluencePass::InfluencePass(const SampleInfluence& influence, std::size_t count)
    : influence_(influence), count_(count) {
  if (count == 0 || count > capacity(influence)) {
    throw std::invalid_argument("InfluencePass: " + std::to_string(count) + " gradients, the scratch holds " +
                                std::to_string(capacity(influence)));
  }
}

void InfluencePass::set_gradient(std::size_t slot, std::span<const double> gradient) {
  const SampleInfluence& in = influence_;
  const std::size_t trays = static_cast<std::size_t>(in.trays.tray_count);
  if (slot >= count_ || (!gradient.empty() && gradient.size() != trays)) {
    throw std::invalid_argument("InfluencePass::set_gradient: slot " + std::to_string(slot) + " of " +
                                std::to_string(count_) + ", " + std::to_string(gradient.size()) + " values for " +
                                std::to_string(trays) + " trays");
  }
  set_[slot] = true;
  used_[slot] = !gradient.empty();
  if (in.kernel_half_width_m > 0.0) {
    if (gradient.empty()) {
      for (std::size_t j = 0; j < 4 * (trays + 2); ++j) in.scratch[j * count_ + slot] = 0.0;
    } else {
      metrics::wide_kernel_sums_of(gradient, in.trays, in.scratch, count_, slot);
    }
    return;
  }
  // Point masses: tray k's values of the pass's gradients side by side at [k · count, (k + 1) · count).
  for (std::size_t k = 0; k < trays; ++k) in.scratch[k * count_ + slot] = gradient.empty() ? 0.0 : gradient[k];
}

void InfluencePass::standard_errors(std::span<double> out) const {
  const SampleInfluence& in = influence_;
  for (std::size_t g = 0; g < count_; ++g) {
    if (!set_[g]) throw std::logic_error("InfluencePass::standard_errors: gradient " + std::to_string(g) + " not set");
    out[g] = std::numeric_limits<double>::quiet_NaN();
  }
  if (in.sample_count < 2) return;
  double se[SampleInfluence::kMaxGradients];
  const std::size_t count = count_;
  if (in.kernel_half_width_m > 0.0) {
    const metrics::WideKernelDots dots(in.kernel_half_width_m, in.trays, in.scratch, count);
    const auto pass = [&]<std::size_t kCount>() {
#if defined(__x86_64__) || defined(__i386__)
      if (dots.avx()) {
        if constexpr (kCount == 8) {
          if (cpu_has_avx512f()) {
            wide_kernel_pass_avx512(in, dots, se);
            return;
          }
        }
        if constexpr (kCount == 4 || kCount == 8) {
          wide_kernel_pass_avx_registers<kCount / 4>(in, dots, se);
        } else {
          wide_kernel_pass_avx<kCount>(in, count, dots, se);
        }
        return;
      }
#endif
      wide_kernel_pass<kCount>(in, count, dots, se);
    };
    // The counts a prediction's passes usually have, with their loops unrolled at compile time.
    switch (count) {
      case 1: pass.template operator()<1>(); break;
      case 2: pass.template operator()<2>(); break;
      case 4: pass.template operator()<4>(); break;
      case 6: pass.template operator()<6>(); break;
      case 8: pass.template operator()<8>(); break;
      case 9: pass.template operator()<9>(); break;
      default: pass.template operator()<0>(); break;
    }
  } else {
    // A point mass lies in one tray (the half-open [e_k, e_k+1)): its dots are that tray's row.
    const double left_m = in.trays.left_edge_m(), w = in.trays.tray_width_m;
    const double tray_count = static_cast<double>(in.trays.tray_count);
    influence_pass(
        in, count,
        [&](double x, double* d) {
          const double position = (x - left_m) / w;
          if (!(position >= 0.0 && position < tray_count)) {
            for (std::size_t g = 0; g < count; ++g) d[g] = 0.0;
            return;
          }
          const double* row = &in.scratch[static_cast<std::size_t>(position) * count];
          for (std::size_t g = 0; g < count; ++g) d[g] = row[g];
        },
        se);
  }
  for (std::size_t g = 0; g < count; ++g) {
    if (used_[g]) out[g] = se[g];
  }
}

double SampleInfluence::standard_error(std::span<const double> gradient) const {
  double se = std::numeric_limits<double>::quiet_NaN();
  standard_errors(std::span(&gradient, 1), std::span(&se, 1));
  return se;
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
  if (sample_count < 2 || count == 0) return;
  double se[kMaxGradients];
  const std::size_t per_pass = InfluencePass::capacity(*this);
  if (per_pass > 0) {
    for (std::size_t first = 0; first < count; first += per_pass) {
      const std::size_t batch = std::min(per_pass, count - first);
      InfluencePass pass(*this, batch);
      for (std::size_t g = 0; g < batch; ++g) pass.set_gradient(g, used[first + g]);
      pass.standard_errors(std::span(se + first, batch));
    }
  } else {
    // No scratch: tray by tray from the gradients themselves.
    const std::span<const std::span<const double>> active(used, count);
    influence_pass(
        *this, count, [&](double x, double* d) { kernel_dots(x, active, trays, kernel_half_width_m, d); }, se);
  }
  for (std::size_t g = 0; g < count; ++g) out[slot[g]] = se[g];
}

bool throw_width_gradient(std::span<const double> tray_mass, const metrics::TrayLayout& trays,
                          const metrics::ThrowExtent& extent, double mass_fraction, std::span<double> gradient) {
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
  if (!(total > 0.0) || !(f_left > 0.0) || !(f_right > 0.0)) return false;
  // Width = x_right − x_left. A landing's kernel shares K_k move the quantile equation C(x_q) = q·S by
  // q·inside − left, where inside = Σ_k K_k (the share in the trays) and left = Σ_{k < t} K_k + φ K_t, t
  // and φ x_q's tray and fraction across it (throw_extent reads the tray's mass as uniform across it): so
  // x_q moves by Σ_k (q − [k < t] − φ [k = t]) K_k / f(x_q), f the tray density at x_q. This is what the
  // estimator sees — not the share of the kernel left of x_q itself: with point masses the two differ
  // for every landing in x_q's tray, and at a steep pattern edge (all of that tray's landings on one side
  // of x_q) the latter gave every sample the same influence and a standard error of zero.
  const TrayQuantile at_left = tray_quantile(extent.left_m, trays), at_right = tray_quantile(extent.right_m, trays);
  const auto coefficient = [](long k, const TrayQuantile& at, double q) {
    return q - (k < at.tray ? 1.0 : 0.0) - (k == at.tray ? at.fraction : 0.0);
  };
  for (long k = 0; k < static_cast<long>(gradient.size()); ++k) {
    gradient[static_cast<std::size_t>(k)] =
        coefficient(k, at_right, q_right) / f_right - coefficient(k, at_left, q_left) / f_left;
  }
  return true;
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
