#include "libspread/analysis/plot/axes.hpp"

#include <cmath>
#include <cstdio>

#include "libspread/analysis/plot/canvas.hpp"

namespace spread::plot::detail {
namespace {

constexpr double kTickFont_px = 14.0;
constexpr double kLabelFont_px = 16.0;
constexpr double kTickLength_px = 6.0;

double nice_step(double span, int target_count) {
  const double raw = span / (target_count > 0 ? target_count : 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / magnitude;
  const double nice = fraction < 1.5 ? 1.0 : fraction < 3.5 ? 2.0 : fraction < 7.5 ? 5.0 : 10.0;
  return nice * magnitude;
}

void guard_range(double& lo, double& hi) {
  if (!(std::isfinite(lo) && std::isfinite(hi))) {
    lo = 0.0;
    hi = 1.0;
  }
  if (!(hi > lo)) {
    const double pad = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    lo -= pad;
    hi += pad;
  }
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target_count) {
  guard_range(lo, hi);
  const double step = nice_step(hi - lo, target_count);
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step) {
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
    if (ticks.size() > 100) break;  // cannot happen with a sane step; never loop on
  }
  return ticks;
}

void nice_range(double& lo, double& hi, int target_count) {
  guard_range(lo, hi);
  const double step = nice_step(hi - lo, target_count);
  lo = std::floor(lo / step + 1e-9) * step;
  hi = std::ceil(hi / step - 1e-9) * step;
}

std::string tick_label(double value, double step) {
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  char buffer[32];
  if (decimals > 6) {
    std::snprintf(buffer, sizeof buffer, "%.2g", value);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  }
  return buffer;
}

Axes::Axes(double left_px, double top_px, double width_px, double height_px, double x_lo, double x_hi,
           double y_lo, double y_hi)
    : left_(left_px), top_(top_px), width_(width_px), height_(height_px), x_lo_(x_lo), x_hi_(x_hi),
      y_lo_(y_lo), y_hi_(y_hi) {
  guard_range(x_lo_, x_hi_);
  guard_range(y_lo_, y_hi_);
}

void Axes::clip(cairo_t* cr) const {
  cairo_save(cr);
  cairo_rectangle(cr, left_, top_, width_, height_);
  cairo_clip(cr);
}

void Axes::draw_grid(cairo_t* cr) const {
  cairo_save(cr);
  cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
  cairo_set_line_width(cr, 1.0);
  for (double x : nice_ticks(x_lo_, x_hi_, 10)) {
    cairo_move_to(cr, std::round(px(x)) + 0.5, top_);
    cairo_line_to(cr, std::round(px(x)) + 0.5, top_ + height_);
  }
  for (double y : nice_ticks(y_lo_, y_hi_, 8)) {
    cairo_move_to(cr, left_, std::round(py(y)) + 0.5);
    cairo_line_to(cr, left_ + width_, std::round(py(y)) + 0.5);
  }
  cairo_stroke(cr);
  cairo_restore(cr);
}

void Axes::draw_frame(cairo_t* cr, const std::string& x_label, const std::string& y_label) const {
  cairo_save(cr);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_set_line_width(cr, 1.5);
  cairo_rectangle(cr, left_, top_, width_, height_);
  cairo_stroke(cr);
  set_font(cr, kTickFont_px);

  const std::vector<double> x_ticks = nice_ticks(x_lo_, x_hi_, 10);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1.0;
  for (double x : x_ticks) {
    cairo_move_to(cr, px(x), top_ + height_);
    cairo_line_to(cr, px(x), top_ + height_ + kTickLength_px);
    cairo_stroke(cr);
    draw_text(cr, tick_label(x, x_step), px(x), top_ + height_ + kTickLength_px + 2.0, 0.5, 0.0);
  }
  const std::vector<double> y_ticks = nice_ticks(y_lo_, y_hi_, 8);
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1.0;
  double widest_px = 0.0;
  for (double y : y_ticks) {
    cairo_move_to(cr, left_ - kTickLength_px, py(y));
    cairo_line_to(cr, left_, py(y));
    cairo_stroke(cr);
    const double w = draw_text(cr, tick_label(y, y_step), left_ - kTickLength_px - 4.0, py(y), 1.0, 0.5);
    if (w > widest_px) widest_px = w;
  }
  set_font(cr, kLabelFont_px);
  draw_text(cr, x_label, left_ + 0.5 * width_, top_ + height_ + kTickLength_px + 26.0, 0.5, 0.0);
  draw_text_vertical(cr, y_label, left_ - kTickLength_px - widest_px - 22.0, top_ + 0.5 * height_);
  cairo_restore(cr);
}

void draw_title(cairo_t* cr, const std::string& title, double centre_x_px, double top_px) {
  cairo_save(cr);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  set_font(cr, 20.0, true);
  draw_text(cr, title, centre_x_px, top_px, 0.5, 0.0);
  cairo_restore(cr);
}

void draw_legend(cairo_t* cr, const std::vector<LegendEntry>& entries, double right_px, double top_px) {
  if (entries.empty()) return;
  cairo_save(cr);
  set_font(cr, 14.0);
  double text_px = 0.0;
  for (const LegendEntry& e : entries) {
    cairo_text_extents_t extents;
    cairo_text_extents(cr, e.label.c_str(), &extents);
    if (extents.x_advance > text_px) text_px = extents.x_advance;
  }
  const double row_px = 22.0, swatch_px = 28.0, pad_px = 8.0;
  const double box_w = pad_px + swatch_px + 8.0 + text_px + pad_px;
  const double box_h = pad_px + row_px * static_cast<double>(entries.size()) + pad_px - 4.0;
  const double left = right_px - box_w;
  cairo_rectangle(cr, left, top_px, box_w, box_h);
  cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, 0.9);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
  cairo_set_line_width(cr, 1.0);
  cairo_stroke(cr);
  double y = top_px + pad_px + 0.5 * (row_px - 4.0);
  for (const LegendEntry& e : entries) {
    cairo_set_source_rgb(cr, e.colour.r, e.colour.g, e.colour.b);
    const double x0 = left + pad_px;
    switch (e.kind) {
      case LegendEntry::Kind::kBox:
        cairo_rectangle(cr, x0 + 4.0, y - 6.0, swatch_px - 8.0, 12.0);
        cairo_fill(cr);
        break;
      case LegendEntry::Kind::kLine:
      case LegendEntry::Kind::kDashedLine: {
        const double dash[] = {6.0, 4.0};
        cairo_set_dash(cr, dash, e.kind == LegendEntry::Kind::kDashedLine ? 2 : 0, 0.0);
        cairo_set_line_width(cr, 2.5);
        cairo_move_to(cr, x0, y);
        cairo_line_to(cr, x0 + swatch_px, y);
        cairo_stroke(cr);
        cairo_set_dash(cr, nullptr, 0, 0.0);
        if (e.with_marker) {
          cairo_arc(cr, x0 + 0.5 * swatch_px, y, 5.0, 0.0, 6.283185307179586);
          cairo_fill(cr);
        }
        break;
      }
      case LegendEntry::Kind::kMarker:
        cairo_arc(cr, x0 + 0.5 * swatch_px, y, 5.0, 0.0, 6.283185307179586);
        cairo_fill(cr);
        break;
    }
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    draw_text(cr, e.label, x0 + swatch_px + 8.0, y, 0.0, 0.5);
    y += row_px;
  }
  cairo_restore(cr);
}

}  // namespace spread::plot::detail
