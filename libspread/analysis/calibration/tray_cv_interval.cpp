#include "libspread/analysis/calibration/tray_cv_interval.hpp"

#include <algorithm>
#include <cmath>

#include "libspread/analysis/calibration/cv_without_missing.hpp"

namespace spread::calibration {
namespace {

// 97.5 % quantile of the standard normal: the two-sided 95 % interval.
constexpr double kNormal975 = 1.959963984540054;

}  // namespace

TrayCvInterval tray_cv_interval(const TrayTest& test, int bout_tray_count, metrics::Overlap overlap) {
  TrayCvInterval r;
  std::vector<double> mass = test.layout_mass_kg;
  const auto cv_of = [&](const std::vector<double>& m) {
    return cv_without_missing(m, test.layout_missing, test.layout, bout_tray_count, overlap);
  };
  r.cv = cv_of(mass);
  const std::size_t passes = test.pass_mass_kg.size();
  if (passes < 2 || !std::isfinite(r.cv)) return r;

  // Each pass scaled to the mean pass's total over the trays read in every pass.
  const std::size_t trays = test.position_m.size();
  std::vector<double> total(passes, 0.0);
  for (std::size_t i = 0; i < trays; ++i) {
    bool all = true;
    for (const auto& pass : test.pass_mass_kg) all = all && !std::isnan(pass[i]);
    if (!all) continue;
    for (std::size_t p = 0; p < passes; ++p) total[p] += test.pass_mass_kg[p][i];
  }
  double mean_total = 0.0;
  for (double t : total) mean_total += t / static_cast<double>(passes);
  for (double t : total) {
    if (!(t > 0.0)) return r;
  }

  // u²(m̄_i) per tray read; NaN where fewer than two passes were read (pooled below).
  std::vector<double> u2(trays, std::nan(""));
  double relative_sum = 0.0;
  int relative_count = 0;
  for (std::size_t i = 0; i < trays; ++i) {
    double sum = 0.0, squares = 0.0;
    int read = 0;
    for (std::size_t p = 0; p < passes; ++p) {
      const double m = test.pass_mass_kg[p][i];
      if (std::isnan(m)) continue;
      const double scaled = m * mean_total / total[p];
      sum += scaled;
      squares += scaled * scaled;
      ++read;
    }
    if (read < 2) continue;
    const double mean = sum / read;
    const double variance = std::max(0.0, (squares - read * mean * mean) / (read - 1));
    u2[i] = variance / read;
    if (mean > 0.0) {
      relative_sum += variance / (mean * mean);
      ++relative_count;
    }
  }
  const double pooled_relative = relative_count > 0 ? relative_sum / relative_count : 0.0;

  // The layout index of each tray read, as the reader places them (tray_csv.cpp).
  const double w = test.layout.tray_width_m;
  double variance = 0.0;
  for (std::size_t i = 0; i < trays; ++i) {
    if (test.missing[i]) continue;
    const double u2_i = std::isnan(u2[i]) ? pooled_relative * test.mass_kg[i] * test.mass_kg[i] : u2[i];
    // Passes of one shape leave only rounding in the variance: no uncertainty from that tray.
    if (!(u2_i > 1e-20 * test.mass_kg[i] * test.mass_kg[i])) continue;
    const long index = std::clamp(std::lround((test.position_m[i] - test.layout.left_edge_m()) / w - 0.5), 0L,
                                  static_cast<long>(test.layout.tray_count - 1));
    const auto k = static_cast<std::size_t>(index);
    const double kept = mass[k];
    // Central difference with a step well inside the tray's own uncertainty (the CV is smooth there) and
    // far above the rounding of the mass.
    const double h = 1e-3 * std::sqrt(u2_i) + 1e-9 * kept;
    mass[k] = kept + h;
    const double up = cv_of(mass);
    mass[k] = std::max(0.0, kept - h);
    const double down = cv_of(mass);
    const double step = kept + h - mass[k];
    mass[k] = kept;
    const double slope = (up - down) / step;
    variance += slope * slope * u2_i;
  }
  r.standard_uncertainty = std::sqrt(variance);
  r.low = std::max(0.0, r.cv - kNormal975 * r.standard_uncertainty);
  r.high = r.cv + kNormal975 * r.standard_uncertainty;
  r.available = true;
  return r;
}

}  // namespace spread::calibration
