#include "libspread/physics/drum/regime_map_plot.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "libspread/analysis/plot/axes.hpp"
#include "libspread/analysis/plot/canvas.hpp"

namespace spread::drum {

namespace {
using plot::detail::Rgb;
Rgb regime_colour(Regime r) {
  switch (r) {
    case Regime::kSlipping: return {0.55, 0.55, 0.55};
    case Regime::kSlumping: return {0.58, 0.40, 0.74};
    case Regime::kRolling: return {0.12, 0.47, 0.71};
    case Regime::kCascading: return {0.17, 0.63, 0.17};
    case Regime::kCataracting: return {1.00, 0.50, 0.05};
    case Regime::kCentrifuging: return {0.84, 0.15, 0.16};
  }
  return {0, 0, 0};
}
}  // namespace

void write_regime_map_png(const std::vector<RegimeEvidence>& runs, const std::string& path, const std::string& title) {
  if (runs.empty()) throw std::runtime_error(path + ": no runs to plot");
  namespace pd = plot::detail;
  pd::Canvas canvas(900, 560);
  cairo_t* cr = canvas.cr();
  double x_lo = 1e300, x_hi = -1e300, y_lo = 0.0, y_hi = 10.0;
  for (const auto& r : runs) {
    const double x = std::log10(std::max(r.froude, 1e-6));
    x_lo = std::min(x_lo, x);
    x_hi = std::max(x_hi, x);
    y_lo = std::min(y_lo, r.angle_of_repose_deg);
    y_hi = std::max(y_hi, r.angle_of_repose_deg);
  }
  x_lo -= 0.15;
  x_hi += 0.15;
  pd::nice_range(y_lo, y_hi, 6);
  const pd::Axes ax(80, 70, 620, 420, x_lo, x_hi, y_lo, y_hi);
  ax.draw_grid(cr);
  // Fr = 1: a particle at the wall is held by centrifugal force alone.
  if (x_lo < 0.0 && x_hi > 0.0) {
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    const double dash[] = {6.0, 4.0};
    cairo_set_dash(cr, dash, 2, 0.0);
    cairo_move_to(cr, ax.px(0.0), ax.py(y_lo));
    cairo_line_to(cr, ax.px(0.0), ax.py(y_hi));
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0.0);
  }
  for (const auto& r : runs) {
    const Rgb c = regime_colour(r.regime);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    const double px = ax.px(std::log10(std::max(r.froude, 1e-6))), py = ax.py(r.angle_of_repose_deg);
    cairo_arc(cr, px, py, 7.0, 0.0, 2.0 * kPi);
    cairo_fill(cr);
    // Band at the top of the plot: the regime along the Fr axis.
    cairo_rectangle(cr, px - 5.0, ax.top() - 18.0, 10.0, 12.0);
    cairo_fill(cr);
  }
  ax.draw_frame(cr, "log10 Fr  (Fr = ω²R/g; dashed: Fr = 1)", "dynamic angle of repose (deg)");
  pd::draw_title(cr, title, 80 + 310, 18);
  std::vector<pd::LegendEntry> legend;
  for (Regime g : {Regime::kSlipping, Regime::kSlumping, Regime::kRolling, Regime::kCascading, Regime::kCataracting,
                   Regime::kCentrifuging})
    legend.push_back({regime_name(g), regime_colour(g), pd::LegendEntry::Kind::kMarker});
  pd::draw_legend(cr, legend, 880, 80);
  canvas.write_png(path);
}

}  // namespace spread::drum
