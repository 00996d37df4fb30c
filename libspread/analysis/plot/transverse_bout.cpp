#include "libspread/analysis/plot/transverse_bout.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::plot {
namespace detail {

OverlappedBout overlapped_bout(std::span<const double> tray_mass_kg, const metrics::TrayLayout& trays,
                               const TransverseOptions& options, bool any_missing) {
  OverlappedBout b;
  const bool overlapped = options.bout_width_m > 0.0;
  if (overlapped) {
    b.trays = metrics::bout_trays(trays, metrics::bout_tray_count(trays, options.bout_width_m));
    b.kg.resize(static_cast<std::size_t>(b.trays.grid_trays));
    metrics::overlapped_profile(tray_mass_kg, trays, options.bout_width_m, options.overlap, b.kg);
    // The overlap is a sum of shifted (and for to-and-fro mirrored) copies of the pattern, so overlapping
    // the missing trays' indicator marks every bout tray one of them feeds.
    b.gap.assign(b.kg.size(), false);
    if (any_missing) {
      std::vector<double> indicator(options.missing_trays.size()), fed(b.kg.size());
      for (std::size_t k = 0; k < indicator.size(); ++k) indicator[k] = options.missing_trays[k] ? 1.0 : 0.0;
      metrics::overlapped_profile(indicator, trays, options.bout_width_m, options.overlap, fed);
      for (std::size_t j = 0; j < fed.size(); ++j) b.gap[j] = fed[j] > 0.0;
    }
    b.half_m = 0.5 * b.trays.bout_trays * trays.tray_width_m;
  }
  // The CV the legend and band show, and the bout's mean per tray: x̄ = Σ w_j P_j / n with the weights of
  // metrics::cv_at_trays (1, or 1/2 for the two trays a bout edge cuts) — the x̄ of that CV. With missing
  // trays only the caller's CV (which leaves them out) is one; NaN then is none.
  b.cv = !overlapped                                     ? 0.0
         : !std::isnan(options.bout_cv) || any_missing ? options.bout_cv
                                                        : metrics::cv_at_width(tray_mass_kg, trays, options.bout_width_m,
                                                                               options.overlap);
  double weight = 0.0;
  for (std::size_t j = 0; j < b.kg.size(); ++j) {
    if (b.gap[j]) continue;
    const bool cut = b.trays.cut_edges && (j == 0 || j + 1 == b.kg.size());
    b.mean_kg += (cut ? 0.5 : 1.0) * b.kg[j];
    weight += cut ? 0.5 : 1.0;
  }
  if (overlapped) b.mean_kg = weight > 0.0 ? b.mean_kg / weight : 0.0;
  return b;
}

double chart_max_kg(std::span<const double> tray_mass_kg, const TransverseOptions& options, const OverlappedBout& bout,
                    bool band) {
  double max_kg = 0.0;
  for (double m : tray_mass_kg) max_kg = std::max(max_kg, m);
  for (double m : options.second_tray_mass_kg) max_kg = std::max(max_kg, m);
  for (double m : bout.kg) max_kg = std::max(max_kg, m);
  if (band) max_kg = std::max(max_kg, bout.mean_kg * (1.0 + bout.cv));
  return max_kg;
}

MassUnit chart_unit(std::span<const double> tray_mass_kg, const TransverseOptions& options, const OverlappedBout& bout,
                    bool band) {
  if (options.units == MassUnits::kFraction) return {"% of the mass", 100.0};
  // kg per tray ÷ A (m²) · 10 000 m²/ha.
  if (options.tray_area_m2 > 0.0) return {"kg/ha", 1e4 / options.tray_area_m2};
  return mass_unit_for(chart_max_kg(tray_mass_kg, options, bout, band));
}

}  // namespace detail

TransverseBout transverse_bout(std::span<const double> tray_mass_kg, const metrics::TrayLayout& trays,
                               const TransverseOptions& options) {
  if (tray_mass_kg.size() != static_cast<std::size_t>(trays.tray_count) || !std::isfinite(options.bout_width_m)) {
    throw std::invalid_argument("transverse_bout: the trays do not fit the layout, or the bout width is not finite");
  }
  const bool any_missing = std::find(options.missing_trays.begin(), options.missing_trays.end(), true) !=
                           options.missing_trays.end();
  const detail::OverlappedBout b = detail::overlapped_bout(tray_mass_kg, trays, options, any_missing);
  const bool band = b.half_m > 0.0 && options.mean_band && std::isfinite(b.cv) && b.mean_kg > 0.0;
  const detail::MassUnit unit = detail::chart_unit(tray_mass_kg, options, b, band);
  return {2.0 * b.half_m, b.cv, b.mean_kg, unit.name, b.mean_kg * unit.per_kg};
}

}  // namespace spread::plot
