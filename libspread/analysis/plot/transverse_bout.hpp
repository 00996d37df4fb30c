#pragma once
// The overlapped bout a transverse chart draws and its legend states — its width in whole trays, its CV
// and its mean per tray — computed without drawing, so a command can put in its --json every number the
// chart prints (a page's legend once read "CV = 54.8 %" where the page's verdict said "NO CV").
#include <span>
#include <string>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/plot/mass_unit.hpp"
#include "libspread/analysis/plot/plot.hpp"

namespace spread::plot {

struct TransverseBout {
  double bout_width_m = 0.0;  // whole trays (0: no bout drawn)
  double cv = 0.0;            // fraction; NaN: no CV (too few trays of the bout read)
  double mean_kg = 0.0;       // per tray, in the series' own unit (kg, or the fraction of the mass)
  // The unit the chart's axis and legend show the mean in ("g", "kg/ha", "% of the mass"), and the mean
  // in it, as the legend prints it to three digits.
  std::string unit;
  double mean_in_unit = 0.0;
};

// The bout of write_transverse_png(tray_mass_kg, trays, ..., options). Throws as it does for a layout
// and options it refuses.
TransverseBout transverse_bout(std::span<const double> tray_mass_kg, const metrics::TrayLayout& trays,
                               const TransverseOptions& options);

namespace detail {

// The drawing's full view of the bout: the overlapped profile over the bout's grid trays, which of them a
// missing tray feeds, and the numbers above.
struct OverlappedBout {
  std::vector<double> kg;
  std::vector<bool> gap;  // per bout tray: fed by a missing tray
  metrics::BoutTrays trays;
  double half_m = 0.0;
  double cv = 0.0;
  double mean_kg = 0.0;
};
OverlappedBout overlapped_bout(std::span<const double> tray_mass_kg, const metrics::TrayLayout& trays,
                               const TransverseOptions& options, bool any_missing);
// The tallest thing drawn (bars, the second series, the profile, the band with `band`), kg or fraction.
double chart_max_kg(std::span<const double> tray_mass_kg, const TransverseOptions& options, const OverlappedBout& bout,
                    bool band);
// The unit of the axis and the legend: the share of the mass, kg/ha on a tray area, else kg, g or mg.
MassUnit chart_unit(std::span<const double> tray_mass_kg, const TransverseOptions& options, const OverlappedBout& bout,
                    bool band);

}  // namespace detail
}  // namespace spread::plot
