#include "tools/spread/chart_json.hpp"

#include <cmath>

#include "libspread/analysis/plot/transverse_bout.hpp"

namespace spread::cli {

nlohmann::json chart_json(const plot::PatternReport& page) {
  if (!(page.chart.bout_width_m > 0.0)) return nullptr;
  plot::TransverseOptions options = page.chart;
  options.mean_band = true;  // as the page draws it (report_pdf.cpp)
  const plot::TransverseBout bout = plot::transverse_bout(page.tray_mass_kg, page.trays, options);
  return {{"bout_width_m", bout.bout_width_m},
          {"cv_percent", std::isfinite(bout.cv) ? nlohmann::json(100.0 * bout.cv) : nlohmann::json(nullptr)},
          {"bout_mean", bout.mean_in_unit},
          {"bout_mean_unit", bout.unit}};
}

}  // namespace spread::cli
