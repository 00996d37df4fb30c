#pragma once
// Monte Carlo standard errors of a predicted pattern's figures (docs/metrics.md "Uncertainty").
//
// A prediction is a statistic T of N independent launch samples: T = T(P), P the tray masses, each tray a
// sum over samples of their landings' kernel mass. The delta method (the infinitesimal jackknife) gives
//   Var T ≈ 1/(N(N−1)) Σ_s (z_s − z̄)²,   z_s = N Σ_{l ∈ s} φ_l Σ_k (∂T/∂P_k) K_k(x_l),
// with φ_l the landing's share of the total mass and K_k(x) the share of a kernel at x that tray k
// receives. T is invariant to the scale of P (CV, widths), so the normalisation of P needs no term of
// its own. Linear in the landings, no resampling, no allocation. A sample is one launch: with two discs
// its landing s and its mirror (or right-disc flight) n + s move together. With each disc at its own
// setting the discs' landings come from their own interpolations; a table sample that feeds both (the
// rows the two settings share) is still one sample, and SampleBlock says which landings it owns.
#include <cstddef>
#include <cstdint>
#include <span>

#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::predict {

// `count` samples in a row, sample j of the block owning landing first_landing[d] + j of each disc d that
// it feeds (kNoLanding: none).
struct SampleBlock {
  static constexpr std::size_t kNoLanding = SIZE_MAX;
  std::size_t count = 0;
  std::size_t first_landing[2] = {kNoLanding, kNoLanding};
};
inline constexpr std::size_t kMaxSampleBlocks = 4;

struct SampleInfluence {
  std::span<const double> x_m;       // landings, machine frame; sample s owns s (and n + s with two discs)
  std::span<const double> weight;    // each landing's share of the total mass (sum 1)
  std::size_t sample_count = 0;      // n
  unsigned landings_per_sample = 1;  // 1 or 2
  metrics::TrayLayout trays;
  double kernel_half_width_m = 0.0;  // 0: point masses
  // When not empty, the samples instead (sample_count = the sum of the counts, landings_per_sample unused):
  // the blocks in order, each sample owning the landings its block names.
  std::span<const SampleBlock> blocks = {};
  // Room for a pass's gradients (InfluencePass): with a kernel (h > 0) their prefix sums
  // (metrics::wide_kernel_sums_size per gradient), so that each landing's dot products cost the same
  // whatever the kernel's width (wide_kernel.hpp); with point masses their values. As many gradients in a
  // pass as the scratch holds. Empty: tray by tray from the gradients themselves.
  std::span<double> scratch = {};

  // Standard error of a statistic whose derivative with respect to tray k's mass is gradient[k].
  double standard_error(std::span<const double> gradient) const;
  // The same for up to kMaxGradients statistics at once: out[g] = standard_error(gradients[g]), bit for
  // bit, in as few passes over the landings as the scratch allows — each landing's kernel is placed once
  // per pass and dotted with every gradient of the pass. An empty gradient gives NaN.
  static constexpr std::size_t kMaxGradients = 9;
  void standard_errors(std::span<const std::span<const double>> gradients, std::span<double> out) const;
};

// One pass over the landings giving the standard errors of up to capacity() statistics, their gradients
// given one at a time and kept in the influence's scratch — with a kernel their prefix sums
// (wide_kernel.hpp), with point masses their values tray by tray —, so that the caller needs room for one
// gradient only. Does not allocate.
class InfluencePass {
 public:
  // Gradients one pass takes in this influence's scratch: at most SampleInfluence::kMaxGradients, 0 when
  // the scratch cannot hold one.
  static std::size_t capacity(const SampleInfluence& influence);
  // count <= capacity(influence); every slot is then set once.
  InfluencePass(const SampleInfluence& influence, std::size_t count);
  // The gradient of statistic `slot` (< count), one value per tray; an empty one gives NaN.
  void set_gradient(std::size_t slot, std::span<const double> gradient);
  // out[g] for g < count: what SampleInfluence::standard_error gives, bit for bit.
  void standard_errors(std::span<double> out) const;

 private:
  const SampleInfluence& influence_;
  std::size_t count_;
  bool set_[SampleInfluence::kMaxGradients] = {};
  bool used_[SampleInfluence::kMaxGradients] = {};
};

// The gradient of the throw width (the extent between the (1∓f)/2 mass quantiles `extent`, as
// metrics::throw_extent reads them off the trays) with respect to the tray masses, for
// SampleInfluence::standard_error: the influence of a sample on a quantile x_q is (q − F_s(x_q)) /
// f(x_q), f the tray density there and F_s(x_q) the sample's share of the trays left of x_q (whole
// trays, plus x_q's own tray pro rata). False, the gradient untouched, when the trays hold no mass or a
// quantile's tray is empty (no density to divide by). gradient.size() == trays.tray_count.
bool throw_width_gradient(std::span<const double> tray_mass, const metrics::TrayLayout& trays,
                          const metrics::ThrowExtent& extent, double mass_fraction, std::span<double> gradient);

// Weighted standard deviation (m) of the finite lateral landing positions.
double lateral_sd_m(std::span<const double> x_m, std::span<const double> weight);

}  // namespace spread::predict
