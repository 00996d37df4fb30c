// CV(W) curves for to-and-fro and racetrack, the CV target, and each curve's effective working width
// (metrics::working_width_on_curve: the widest band's upper end, docs/metrics.md "Effective working width").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/plot/axes.hpp"
#include "libspread/analysis/plot/canvas.hpp"
#include "libspread/analysis/plot/plot.hpp"

namespace spread::plot {
namespace {

constexpr detail::Rgb kToAndFroColour{0.25, 0.45, 0.75};
constexpr detail::Rgb kRacetrackColour{0.90, 0.50, 0.10};
constexpr detail::Rgb kTargetColour{0.80, 0.10, 0.10};
constexpr detail::Rgb kSecondColour{0.30, 0.30, 0.30};

void require_curve(std::span<const double> cv, std::size_t widths, const char* name) {
  if (!cv.empty() && cv.size() != widths) {
    throw std::invalid_argument(std::string("write_cv_curve_png: ") + name + " has " + std::to_string(cv.size()) +
                                " values for " + std::to_string(widths) + " widths");
  }
  for (double v : cv) {
    if (std::isnan(v) || v < 0.0) {
      throw std::invalid_argument(std::string("write_cv_curve_png: ") + name + " holds a NaN or negative CV");
    }
  }
}

// The working width the library reports for this curve; -1 when none.
double effective_width_m(std::span<const double> widths_m, std::span<const double> cv, double cv_target) {
  const metrics::WorkingWidth w = metrics::working_width_on_curve(widths_m, cv, cv_target);
  return w.width_m > 0.0 ? w.width_m : -1.0;
}

}  // namespace

void write_cv_curve_png(std::span<const double> widths_m, std::span<const double> cv_to_and_fro,
                        std::span<const double> cv_racetrack, double cv_target, const std::string& path,
                        const std::string& title, const CvCurveOptions& options) {
  if (widths_m.empty()) throw std::invalid_argument("write_cv_curve_png: widths_m is empty");
  for (double w : widths_m) {
    if (!std::isfinite(w)) throw std::invalid_argument("write_cv_curve_png: widths_m holds a non-finite width");
  }
  require_curve(cv_to_and_fro, widths_m.size(), "cv_to_and_fro");
  require_curve(cv_racetrack, widths_m.size(), "cv_racetrack");
  require_curve(options.second_to_and_fro, widths_m.size(), "second_to_and_fro");
  if (cv_to_and_fro.empty() && cv_racetrack.empty()) {
    throw std::invalid_argument("write_cv_curve_png: both CV curves are empty");
  }
  if (!(std::isfinite(cv_target) && cv_target >= 0.0)) {
    throw std::invalid_argument("write_cv_curve_png: cv_target must be finite and >= 0");
  }

  // y range: up to the largest finite CV, but capped so the region near the target stays readable.
  double max_cv = cv_target;
  for (auto curve : {cv_to_and_fro, cv_racetrack, options.second_to_and_fro}) {
    for (double v : curve) {
      if (std::isfinite(v)) max_cv = std::max(max_cv, v);
    }
  }
  const double cap = std::max(0.6, 4.0 * cv_target);
  double y_lo = 0.0, y_hi = 100.0 * std::min(std::max(max_cv, 1.5 * cv_target), cap);
  detail::nice_range(y_lo, y_hi, 8);
  // W axis: up to one width after the last point of any curve on the CV axis.
  std::size_t last_on_scale = 0;
  for (auto curve : {cv_to_and_fro, cv_racetrack, options.second_to_and_fro}) {
    for (std::size_t i = 0; i < curve.size(); ++i) {
      if (100.0 * curve[i] <= y_hi) last_on_scale = std::max(last_on_scale, i);
    }
  }
  double x_lo = *std::min_element(widths_m.begin(), widths_m.end());
  double x_hi = widths_m[std::min(last_on_scale + 1, widths_m.size() - 1)];
  x_lo = std::min(x_lo, 0.0);
  detail::nice_range(x_lo, x_hi, 10);

  detail::Canvas canvas(kImageWidth_px, kImageHeight_px);
  cairo_t* cr = canvas.cr();
  const detail::Axes axes(100.0, 55.0, 860.0, 510.0, x_lo, x_hi, y_lo, y_hi);
  axes.draw_grid(cr);
  axes.clip(cr);

  const double dash[] = {4.0, 4.0};
  cairo_set_source_rgb(cr, kTargetColour.r, kTargetColour.g, kTargetColour.b);
  cairo_set_line_width(cr, 1.5);
  cairo_set_dash(cr, dash, 2, 0.0);
  cairo_move_to(cr, axes.left(), axes.py(100.0 * cv_target));
  cairo_line_to(cr, axes.left() + axes.width(), axes.py(100.0 * cv_target));
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0.0);

  std::vector<detail::LegendEntry> legend;
  struct Curve {
    std::span<const double> cv;
    std::string name;
    detail::Rgb colour;
    bool dashed;  // racetrack dashed on top, so identical curves (symmetric patterns) both show
    double line_width_px;
  };
  const std::string prefix = options.series_label.empty() ? "" : options.series_label + " ";
  int curve_index = 0;
  for (const Curve& c : {Curve{cv_to_and_fro, prefix + "to-and-fro", kToAndFroColour, false, 4.0},
                         Curve{cv_racetrack, prefix + "racetrack", kRacetrackColour, true, 2.5},
                         Curve{options.second_to_and_fro, options.second_label + " to-and-fro", kSecondColour, false,
                               2.0}}) {
    if (c.cv.empty()) continue;
    // Off-scale and infinite CVs (empty bouts) are drawn just above the top edge and clipped.
    const double off_scale = y_hi + 0.05 * (y_hi - y_lo);
    cairo_set_source_rgb(cr, c.colour.r, c.colour.g, c.colour.b);
    const double curve_dash[] = {10.0, 6.0};
    cairo_set_dash(cr, curve_dash, c.dashed ? 2 : 0, 0.0);
    cairo_set_line_width(cr, c.line_width_px);
    for (std::size_t i = 0; i < widths_m.size(); ++i) {
      const double y = std::min(100.0 * c.cv[i], off_scale);
      if (i == 0) {
        cairo_move_to(cr, axes.px(widths_m[i]), axes.py(y));
      } else {
        cairo_line_to(cr, axes.px(widths_m[i]), axes.py(y));
      }
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0.0);
    const double w_eff = effective_width_m(widths_m, c.cv, cv_target);
    char label[96];
    if (w_eff >= 0.0) {
      std::snprintf(label, sizeof label, "%s: working width %.1f m (dot)", c.name.c_str(), w_eff);
      // Mark: a vertical dashed line down to the axis and a dot on the target line.
      cairo_set_line_width(cr, 1.5);
      cairo_set_dash(cr, dash, 2, 0.0);
      cairo_move_to(cr, axes.px(w_eff), axes.py(100.0 * cv_target));
      cairo_line_to(cr, axes.px(w_eff), axes.top() + axes.height());
      cairo_stroke(cr);
      cairo_set_dash(cr, nullptr, 0, 0.0);
      cairo_arc(cr, axes.px(w_eff), axes.py(100.0 * cv_target), 6.0, 0.0, 6.283185307179586);
      cairo_fill(cr);
      detail::set_font(cr, 14.0);
      char value[32];
      std::snprintf(value, sizeof value, "%.1f m", w_eff);
      // Right of the marker line, or left of it when the text would run past the right edge of the axes
      // (the working width is often the largest W plotted).
      cairo_text_extents_t extents;
      cairo_text_extents(cr, value, &extents);
      const bool fits_right = axes.px(w_eff) + 5.0 + extents.x_advance <= axes.left() + axes.width() - 2.0;
      detail::draw_text(cr, value, axes.px(w_eff) + (fits_right ? 5.0 : -5.0),
                        axes.top() + axes.height() - 8.0 - 20.0 * curve_index, fits_right ? 0.0 : 1.0, 1.0);
    } else {
      std::snprintf(label, sizeof label, "%s: no width meets the target", c.name.c_str());
    }
    legend.push_back({label, c.colour,
                      c.dashed ? detail::LegendEntry::Kind::kDashedLine : detail::LegendEntry::Kind::kLine,
                      w_eff >= 0.0});
    ++curve_index;
  }
  cairo_restore(cr);  // clip

  char target_label[64];
  std::snprintf(target_label, sizeof target_label, "target CV %.0f %%", 100.0 * cv_target);
  legend.push_back({target_label, kTargetColour, detail::LegendEntry::Kind::kDashedLine});
  axes.draw_frame(cr, "bout width W (m)", "coefficient of variation CV (%)");
  // Top left, where the CV of narrow bouts is low: its right edge from the widest label (draw_legend's
  // layout: 8 px pad, 28 px swatch, 8 px gap, the text, 8 px pad; 14 px font).
  cairo_save(cr);
  detail::set_font(cr, 14.0);
  double text_px = 0.0;
  for (const detail::LegendEntry& e : legend) {
    cairo_text_extents_t extents;
    cairo_text_extents(cr, e.label.c_str(), &extents);
    text_px = std::max(text_px, extents.x_advance);
  }
  cairo_restore(cr);
  detail::draw_legend(cr, legend, axes.left() + 8.0 + 52.0 + text_px, axes.top() + 8.0);
  detail::draw_title(cr, title, 0.5 * kImageWidth_px, 14.0);
  canvas.write_png(path);
}

}  // namespace spread::plot
