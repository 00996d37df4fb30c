#pragma once
// A granular product's size distribution as its spec sheet gives it: a sieve analysis, the mass retained
// between consecutive sieves. Used by the scene (validation), the launch sources (sampling diameters)
// and the tools (the size guide number and uniformity index).
//
// The curve between the sieves: the cumulative mass passing is taken linear in the aperture between two
// consecutive sieves, as the size guide number's standard definition interpolates it (Canadian
// Fertilizer Institute, "Bulk Blend Quality Control Manual", 2013, size guide number and uniformity
// index; The Fertilizer Institute's method: SGN = d50 in mm × 100, UI = d5 / d90 × 100, d_p the aperture
// that p % of the mass passes, read on the cumulative curve by linear interpolation between sieves).
// A mass uniform in d within an interval [a, b] means a number density ∝ d⁻³ there (each granule's mass
// ∝ d³), which is what the number-weighted sampling below draws, so the samples' mass-weighted curve is
// the same piecewise-linear curve and their SGN and UI are the sheet's.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace spread {

struct SieveAnalysis {
  // N + 1 sieve apertures (mm), strictly increasing: the smallest is the bottom of the product (nothing
  // passes it: put the pan's fraction in the interval below the smallest sieve of the sheet, down to a
  // stated size), the largest its top (everything passes it).
  std::vector<double> sieve_mm;
  // N values: mass % retained in [sieve_mm[i], sieve_mm[i+1]) (on sieve i, passing sieve i + 1); sum 100.
  std::vector<double> retained_pct;
  bool empty() const { return sieve_mm.empty() && retained_pct.empty(); }
  bool operator==(const SieveAnalysis&) const = default;
};

// Spec sheets round each fraction (to 0.1 % or 1 %): a sum within this of 100 % is accepted and the
// fractions are taken relative to their sum.
inline constexpr double kSieveSumTolerancePct = 0.5;
// The largest aperture accepted: the table's largest granule (tables::PlausibleLimits::kMaxDiameter_m).
inline constexpr double kMaxSieveMm = 100.0;

// "" when the analysis is usable; otherwise the first problem as "<field>[i]: <problem>" or
// "<field>: <problem>", the field being "sieve_mm" or "sieve_retained_pct" (the scene's key names).
inline std::string sieve_problem(const SieveAnalysis& s) {
  auto num = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return std::string(b);
  };
  const std::size_t n = s.sieve_mm.size();
  if (n < 2) return "sieve_mm: needs at least 2 sieve sizes (the bottom and top of the product), got " + std::to_string(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = s.sieve_mm[i];
    const std::string f = "sieve_mm[" + std::to_string(i) + "]";
    if (!std::isfinite(d) || !(d > 0.0) || d > kMaxSieveMm) return f + ": must be in (0, 100] mm, got " + num(d);
    if (i > 0 && !(d > s.sieve_mm[i - 1]))
      return f + ": sieve sizes must increase, got " + num(d) + " after " + num(s.sieve_mm[i - 1]);
  }
  if (s.retained_pct.size() != n - 1) {
    return "sieve_retained_pct: needs one value per interval between sieves (" + std::to_string(n - 1) + " for " +
           std::to_string(n) + " sieve sizes), got " + std::to_string(s.retained_pct.size());
  }
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double w = s.retained_pct[i];
    if (!std::isfinite(w) || w < 0.0)
      return "sieve_retained_pct[" + std::to_string(i) + "]: must be a mass % >= 0, got " + num(w);
    sum += w;
  }
  if (!(std::abs(sum - 100.0) <= kSieveSumTolerancePct))
    return "sieve_retained_pct: the fractions must sum to 100 %, got " + num(sum) + " %";
  return {};
}

// Cumulative mass % passing each sieve: 0 at the smallest, 100 at the largest (fractions relative to
// their sum). Requires sieve_problem(s).empty().
inline std::vector<double> sieve_passing_pct(const SieveAnalysis& s) {
  double sum = 0.0;
  for (double w : s.retained_pct) sum += w;
  std::vector<double> p(s.sieve_mm.size(), 0.0);
  for (std::size_t i = 0; i < s.retained_pct.size(); ++i) p[i + 1] = p[i] + 100.0 * s.retained_pct[i] / sum;
  p.back() = 100.0;
  return p;
}

// d_p (mm): the aperture that `percent` % of the mass passes, linear between the sieves of the
// cumulative curve; an interval without mass is skipped (the curve is flat there).
inline double sieve_passing_size_mm(const SieveAnalysis& s, double percent) {
  const std::vector<double> p = sieve_passing_pct(s);
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    if (p[i + 1] > p[i] && percent <= p[i + 1]) {
      const double t = std::max(0.0, (percent - p[i]) / (p[i + 1] - p[i]));
      return s.sieve_mm[i] + t * (s.sieve_mm[i + 1] - s.sieve_mm[i]);
    }
  }
  return s.sieve_mm.back();
}

// Size guide number: d50 in mm × 100. Uniformity index: d5 / d90 × 100 (the definitions above).
inline double size_guide_number(const SieveAnalysis& s) { return 100.0 * sieve_passing_size_mm(s, 50.0); }
inline double uniformity_index(const SieveAnalysis& s) {
  return 100.0 * sieve_passing_size_mm(s, 5.0) / sieve_passing_size_mm(s, 90.0);
}

// The number distribution of the granules of a sieve analysis (mass uniform in d within each interval,
// so number ∝ d⁻³ there): what a feed releases granule by granule. Per unit mass and per ρπ/6, an
// interval [a, b] with mass fraction w holds w (a + b) / (2 a² b²) granules (∫ d⁻³ over [a, b] / (b − a)).
class SieveNumberDistribution {
 public:
  explicit SieveNumberDistribution(const SieveAnalysis& s) : sieve_mm_(s.sieve_mm) {
    double mass = 0.0;
    for (double w : s.retained_pct) mass += w;
    double number = 0.0, first = 0.0, second = 0.0;
    cumulative_.assign(s.sieve_mm.size(), 0.0);
    for (std::size_t i = 0; i < s.retained_pct.size(); ++i) {
      const double a = s.sieve_mm[i], b = s.sieve_mm[i + 1], w = s.retained_pct[i] / mass;
      const double n = w * (a + b) / (2.0 * a * a * b * b);
      number += n;
      cumulative_[i + 1] = number;
      first += w / (a * b);                    // ∫ d · d⁻³ / (b − a)
      second += w * std::log(b / a) / (b - a);  // ∫ d² · d⁻³ / (b − a)
      if (w > 0.0 && min_mm_ == 0.0) min_mm_ = a;
      if (w > 0.0) max_mm_ = b;
    }
    for (double& c : cumulative_) c /= number;
    cumulative_.back() = 1.0;
    mean_cube_mm3_ = 1.0 / number;
    mean_mm_ = first / number;
    sd_mm_ = std::sqrt(std::max(0.0, second / number - mean_mm_ * mean_mm_));
  }
  // The diameter (m) whose number fraction below is u ∈ [0, 1): the interval by its granule count, then
  // the inverse of the d⁻³ law within it, d = (a⁻² − v (a⁻² − b⁻²))^(−1/2), v the fraction into the interval.
  double diameter_m(double u) const {
    std::size_t i = 0;
    while (i + 2 < cumulative_.size() && !(u < cumulative_[i + 1])) ++i;
    const double span = cumulative_[i + 1] - cumulative_[i];
    const double v = span > 0.0 ? std::min(1.0, std::max(0.0, (u - cumulative_[i]) / span)) : 0.0;
    const double a = sieve_mm_[i], b = sieve_mm_[i + 1];
    return 1e-3 / std::sqrt(1.0 / (a * a) - v * (1.0 / (a * a) - 1.0 / (b * b)));
  }
  double min_m() const { return 1e-3 * min_mm_; }             // the bottom of the lowest interval with mass
  double max_m() const { return 1e-3 * max_mm_; }             // the top of the highest
  double mean_cube_m3() const { return 1e-9 * mean_cube_mm3_; }  // E[d³] over granules
  double mean_m() const { return 1e-3 * mean_mm_; }           // number mean
  double sd_m() const { return 1e-3 * sd_mm_; }               // number standard deviation

 private:
  std::vector<double> sieve_mm_;
  std::vector<double> cumulative_;  // granule fraction below each sieve
  double min_mm_ = 0.0, max_mm_ = 0.0, mean_cube_mm3_ = 0.0, mean_mm_ = 0.0, sd_mm_ = 0.0;
};

}  // namespace spread
