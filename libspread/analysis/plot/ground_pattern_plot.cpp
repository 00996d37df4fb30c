// Heat map of the machine's ground pattern (kg/m² or g/m²) with a colour bar and the disc centres.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "libspread/core/vec3.hpp"
#include "libspread/analysis/plot/axes.hpp"
#include "libspread/analysis/plot/canvas.hpp"
#include "libspread/analysis/plot/colour_map.hpp"
#include "libspread/analysis/plot/plot.hpp"

namespace spread::plot {
namespace {

void require_drawable(const metrics::GroundPattern& pattern) {
  if (pattern.nx <= 0 || pattern.ny <= 0) {
    throw std::invalid_argument("write_ground_pattern_png: the ground pattern is empty (nx = " +
                                std::to_string(pattern.nx) + ", ny = " + std::to_string(pattern.ny) + ")");
  }
  if (pattern.mass_kg.size() != static_cast<std::size_t>(pattern.nx) * static_cast<std::size_t>(pattern.ny)) {
    throw std::invalid_argument("write_ground_pattern_png: mass_kg has " + std::to_string(pattern.mass_kg.size()) +
                                " cells, expected nx × ny = " + std::to_string(pattern.nx) + " × " +
                                std::to_string(pattern.ny));
  }
  if (pattern.nx > 32767 || pattern.ny > 32767) {
    throw std::invalid_argument("write_ground_pattern_png: the grid (" + std::to_string(pattern.nx) + " × " +
                                std::to_string(pattern.ny) + " cells) is too large to draw; use a larger cell");
  }
  if (!(std::isfinite(pattern.cell_m) && pattern.cell_m > 0.0 && std::isfinite(pattern.x0_m) &&
        std::isfinite(pattern.y0_m))) {
    throw std::invalid_argument("write_ground_pattern_png: cell_m must be > 0 and the corner finite");
  }
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};

// One pixel per cell, image row 0 = the northmost (largest y) row; empty cells stay white.
std::unique_ptr<cairo_surface_t, SurfaceDeleter> cells_image(const metrics::GroundPattern& pattern,
                                                             double max_density_kg_m2) {
  std::unique_ptr<cairo_surface_t, SurfaceDeleter> image(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, pattern.nx, pattern.ny));
  if (cairo_surface_status(image.get()) != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error("write_ground_pattern_png: cannot create the cell image");
  }
  cairo_surface_flush(image.get());
  unsigned char* data = cairo_image_surface_get_data(image.get());
  const int stride = cairo_image_surface_get_stride(image.get());
  for (int row = 0; row < pattern.ny; ++row) {
    auto* pixels = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(row) * stride);
    const int iy = pattern.ny - 1 - row;
    for (int ix = 0; ix < pattern.nx; ++ix) {
      const double density = pattern.density_kg_m2(ix, iy);
      std::uint32_t r = 255, g = 255, b = 255;
      if (density > 0.0) {
        const detail::Rgb c = detail::colour_at(density / max_density_kg_m2);
        r = static_cast<std::uint32_t>(std::lround(255.0 * c.r));
        g = static_cast<std::uint32_t>(std::lround(255.0 * c.g));
        b = static_cast<std::uint32_t>(std::lround(255.0 * c.b));
      }
      pixels[ix] = (r << 16) | (g << 8) | b;
    }
  }
  cairo_surface_mark_dirty(image.get());
  return image;
}

}  // namespace

void write_ground_pattern_png(const metrics::GroundPattern& pattern, const std::string& path,
                              const std::string& title, const metrics::MachineLayout& machine, MassUnits units) {
  require_drawable(pattern);
  double max_density_kg_m2 = 0.0;
  for (int iy = 0; iy < pattern.ny; ++iy) {
    for (int ix = 0; ix < pattern.nx; ++ix) max_density_kg_m2 = std::max(max_density_kg_m2, pattern.density_kg_m2(ix, iy));
  }
  if (!std::isfinite(max_density_kg_m2)) {
    throw std::invalid_argument("write_ground_pattern_png: the pattern holds a non-finite mass");
  }
  // Field rates are tens of g/m²: show g/m² unless the numbers are large. Fractions show in %/m².
  const bool fraction = units == MassUnits::kFraction;
  const bool grams = !fraction && max_density_kg_m2 < 0.1;
  const double unit_scale = (fraction || grams) ? (fraction ? 100.0 : 1000.0) : 1.0;
  const std::string unit = fraction ? "% of mass / m²" : grams ? "g/m²" : "kg/m²";
  const double colour_top_kg_m2 = max_density_kg_m2 > 0.0 ? max_density_kg_m2 : 1.0;

  detail::Canvas canvas(kImageWidth_px, kImageHeight_px);
  cairo_t* cr = canvas.cr();

  // Disc centres: left disc at -spacing/2, right at +spacing/2 (one disc at 0), both at y = 0.
  const int discs = machine.disc_count == 1 ? 1 : 2;
  const double disc_x_m = discs == 1 ? 0.0 : 0.5 * machine.disc_spacing_m;

  // The shown area covers the grid and the disc centres (a pattern thrown wholly behind the machine has
  // no cell at y = 0; the markers then sat outside the axes, over the title). A margin of 3 % of the
  // larger span keeps each 10 px marker inside the frame.
  const double grid_x_span_m = pattern.nx * pattern.cell_m;
  const double grid_y_span_m = pattern.ny * pattern.cell_m;
  const double margin_m = 0.03 * std::max(grid_x_span_m, grid_y_span_m);
  const double x_lo_m = std::min(pattern.x0_m, -disc_x_m - margin_m);
  const double x_hi_m = std::max(pattern.x0_m + grid_x_span_m, disc_x_m + margin_m);
  const double y_lo_m = std::min(pattern.y0_m, -margin_m);
  const double y_hi_m = std::max(pattern.y0_m + grid_y_span_m, margin_m);

  // Equal scales in x and y, fitted into the space left of the colour bar.
  const double x_span_m = x_hi_m - x_lo_m;
  const double y_span_m = y_hi_m - y_lo_m;
  const double avail_left = 95.0, avail_top = 55.0, avail_w = 720.0, avail_h = 510.0;
  const double px_per_m = std::min(avail_w / x_span_m, avail_h / y_span_m);
  const double w = x_span_m * px_per_m, h = y_span_m * px_per_m;
  const detail::Axes axes(avail_left + 0.5 * (avail_w - w), avail_top + 0.5 * (avail_h - h), w, h, x_lo_m, x_hi_m,
                          y_lo_m, y_hi_m);

  const auto image = cells_image(pattern, colour_top_kg_m2);
  axes.clip(cr);
  cairo_save(cr);
  cairo_translate(cr, axes.px(pattern.x0_m), axes.py(pattern.y0_m + grid_y_span_m));
  cairo_scale(cr, grid_x_span_m * px_per_m / pattern.nx, grid_y_span_m * px_per_m / pattern.ny);
  cairo_set_source_surface(cr, image.get(), 0.0, 0.0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
  cairo_paint(cr);
  cairo_restore(cr);

  // Markers drawn inside the same clip: never over the title or the colour bar.
  for (int d = 0; d < discs; ++d) {
    const double x_m = discs == 1 ? 0.0 : (d == 0 ? -disc_x_m : disc_x_m);
    cairo_arc(cr, axes.px(x_m), axes.py(0.0), 7.0, 0.0, 2.0 * kPi);
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.85, 0.1, 0.1);
    cairo_set_line_width(cr, 3.0);
    cairo_stroke(cr);
  }
  cairo_restore(cr);  // clip
  axes.draw_frame(cr, "x, across the driving direction (m)", "y, driving direction (m)");
  detail::draw_legend(cr, {{discs == 1 ? "disc centre" : "disc centres", {0.85, 0.1, 0.1},
                            detail::LegendEntry::Kind::kMarker}},
                      axes.left() + axes.width() - 6.0, axes.top() + 6.0);

  // Colour bar with ticks in the chosen unit.
  const double bar_left = 860.0, bar_w = 24.0, bar_top = avail_top, bar_h = avail_h;
  for (int i = 0; i < static_cast<int>(bar_h); ++i) {
    const detail::Rgb c = detail::colour_at(1.0 - (i + 0.5) / bar_h);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_rectangle(cr, bar_left, bar_top + i, bar_w, 1.0);
    cairo_fill(cr);
  }
  const detail::Axes bar(bar_left, bar_top, bar_w, bar_h, 0.0, 1.0, 0.0, colour_top_kg_m2 * unit_scale);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, bar_left, bar_top, bar_w, bar_h);
  cairo_stroke(cr);
  detail::set_font(cr, 14.0);
  const std::vector<double> ticks = detail::nice_ticks(0.0, colour_top_kg_m2 * unit_scale, 8);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
  for (double t : ticks) {
    cairo_move_to(cr, bar_left + bar_w, bar.py(t));
    cairo_line_to(cr, bar_left + bar_w + 5.0, bar.py(t));
    cairo_stroke(cr);
    detail::draw_text(cr, detail::tick_label(t, step), bar_left + bar_w + 8.0, bar.py(t), 0.0, 0.5);
  }
  detail::set_font(cr, 16.0);
  detail::draw_text(cr, unit, bar_left + 0.5 * bar_w, bar_top + bar_h + 12.0, 0.5, 0.0);
  detail::draw_text(cr, "(white: none)", bar_left + 0.5 * bar_w, bar_top + bar_h + 34.0, 0.5, 0.0);

  detail::draw_title(cr, title, 0.5 * kImageWidth_px, 14.0);
  canvas.write_png(path);
}

}  // namespace spread::plot
