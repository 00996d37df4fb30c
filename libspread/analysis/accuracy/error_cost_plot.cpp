// Error-against-cost line plots with libspread/analysis/plot's canvas and axes. Log axes are drawn as linear
// axes of log10(value), labelled "log10 …": the shared Axes has nice linear ticks only, and a decade
// per tick is exactly what an error–cost plot wants to show.
#include "libspread/analysis/accuracy/error_cost_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libspread/core/vec3.hpp"
#include "libspread/analysis/plot/axes.hpp"
#include "libspread/analysis/plot/canvas.hpp"

namespace spread::accuracy::detail {
namespace {

using plot::detail::Rgb;
const Rgb kColours[] = {{0.12, 0.47, 0.71}, {0.84, 0.15, 0.16}, {0.17, 0.63, 0.17},
                        {0.58, 0.40, 0.74}, {1.00, 0.50, 0.05}, {0.55, 0.34, 0.29}};

double to_axis(double v, bool log) { return log ? std::log10(v) : v; }

}  // namespace

void write_error_cost_plot(const Plot& p, const std::string& path) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const auto& s : p.series) {
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      if (!(s.x[k] > 0.0 || !p.log_x) || !(s.y[k] > 0.0 || !p.log_y)) continue;
      x_lo = std::min(x_lo, to_axis(s.x[k], p.log_x));
      x_hi = std::max(x_hi, to_axis(s.x[k], p.log_x));
      y_lo = std::min(y_lo, to_axis(s.y[k], p.log_y));
      y_hi = std::max(y_hi, to_axis(s.y[k], p.log_y));
    }
  }
  if (std::isfinite(p.threshold_y)) {
    y_lo = std::min(y_lo, to_axis(p.threshold_y, p.log_y));
    y_hi = std::max(y_hi, to_axis(p.threshold_y, p.log_y));
  }
  if (!std::isfinite(x_lo)) { x_lo = 0.0; x_hi = 1.0; y_lo = 0.0; y_hi = 1.0; }
  if (x_hi - x_lo < 1e-9) { x_lo -= 0.5; x_hi += 0.5; }
  if (y_hi - y_lo < 1e-9) { y_lo -= 0.5; y_hi += 0.5; }
  plot::detail::nice_range(x_lo, x_hi, 6);
  plot::detail::nice_range(y_lo, y_hi, 6);

  plot::detail::Canvas canvas(900, 600);
  cairo_t* cr = canvas.cr();
  const plot::detail::Axes axes(90, 50, 780, 470, x_lo, x_hi, y_lo, y_hi);
  axes.draw_grid(cr);
  cairo_save(cr);
  axes.clip(cr);
  std::vector<plot::detail::LegendEntry> legend;
  if (std::isfinite(p.threshold_y)) {
    const double y = axes.py(to_axis(p.threshold_y, p.log_y));
    const double dash[] = {8.0, 5.0};
    cairo_set_dash(cr, dash, 2, 0.0);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    cairo_set_line_width(cr, 1.5);
    cairo_move_to(cr, axes.left(), y);
    cairo_line_to(cr, axes.left() + axes.width(), y);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0.0);
    legend.push_back({"1 % error budget", {0.3, 0.3, 0.3}, plot::detail::LegendEntry::Kind::kDashedLine});
  }
  for (std::size_t i = 0; i < p.series.size(); ++i) {
    const auto& s = p.series[i];
    const Rgb c = kColours[i % std::size(kColours)];
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_set_line_width(cr, 2.0);
    bool first = true;
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      const double x = axes.px(to_axis(s.x[k], p.log_x)), y = axes.py(to_axis(s.y[k], p.log_y));
      if (first) cairo_move_to(cr, x, y); else cairo_line_to(cr, x, y);
      first = false;
    }
    cairo_stroke(cr);
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      cairo_arc(cr, axes.px(to_axis(s.x[k], p.log_x)), axes.py(to_axis(s.y[k], p.log_y)), 4.0, 0.0, 2.0 * kPi);
      cairo_fill(cr);
    }
    legend.push_back({s.label, c, plot::detail::LegendEntry::Kind::kLine});
  }
  cairo_restore(cr);
  axes.draw_frame(cr, (p.log_x ? "log10 " : "") + p.x_label, (p.log_y ? "log10 " : "") + p.y_label);
  plot::detail::draw_title(cr, p.title, 90 + 390, 12);
  plot::detail::draw_legend(cr, legend, 90 + 780 - 8, 58);
  canvas.write_png(path);
}

}  // namespace spread::accuracy::detail
