#pragma once
// A rectangular plot area mapping data coordinates to pixels, with "nice" ticks (1, 2, 5 × 10^k),
// numbered tick labels, axis labels with units, a title, and a legend.
#include <string>
#include <vector>

#include <cairo.h>

namespace spread::plot::detail {

struct Rgb {
  double r, g, b;
};

// Tick positions covering [lo, hi] with about `target_count` steps of 1, 2 or 5 × 10^k.
std::vector<double> nice_ticks(double lo, double hi, int target_count);
// [lo, hi] widened outwards to the nice tick step (hi > lo is guaranteed on return).
void nice_range(double& lo, double& hi, int target_count);
// Tick label without trailing noise: 0.1 not 0.1000000001, 1e-05 only for tiny steps.
std::string tick_label(double value, double step);

class Axes {
 public:
  // Plot area in pixels (left, top, width, height) and the data ranges shown.
  Axes(double left_px, double top_px, double width_px, double height_px, double x_lo, double x_hi, double y_lo,
       double y_hi);

  double px(double x) const { return left_ + (x - x_lo_) / (x_hi_ - x_lo_) * width_; }
  double py(double y) const { return top_ + height_ - (y - y_lo_) / (y_hi_ - y_lo_) * height_; }
  double left() const { return left_; }
  double top() const { return top_; }
  double width() const { return width_; }
  double height() const { return height_; }
  double x_lo() const { return x_lo_; }
  double x_hi() const { return x_hi_; }
  double y_lo() const { return y_lo_; }
  double y_hi() const { return y_hi_; }

  // Light grid at the ticks (draw before the data).
  void draw_grid(cairo_t* cr) const;
  // Frame, ticks, numbers, axis labels (draw after the data).
  void draw_frame(cairo_t* cr, const std::string& x_label, const std::string& y_label) const;
  // Restricts drawing to the plot area until cairo_restore.
  void clip(cairo_t* cr) const;

 private:
  double left_, top_, width_, height_;
  double x_lo_, x_hi_, y_lo_, y_hi_;
};

void draw_title(cairo_t* cr, const std::string& title, double centre_x_px, double top_px);

struct LegendEntry {
  std::string label;
  Rgb colour;
  enum class Kind { kBox, kLine, kDashedLine, kMarker } kind;
  bool with_marker = false;  // a line with the dot the plot marks on it (e.g. a working width)
};
// Legend box with its top-right corner at (right_px, top_px).
void draw_legend(cairo_t* cr, const std::vector<LegendEntry>& entries, double right_px, double top_px);

}  // namespace spread::plot::detail
