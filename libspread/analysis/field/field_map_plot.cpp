// The as-applied map's PNG (field_map_plot.hpp), on the plot module's canvas and colour map.
#include "libspread/analysis/field/field_map_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "libspread/analysis/field/field_summary.hpp"
#include "libspread/analysis/plot/canvas.hpp"
#include "libspread/analysis/plot/colour_map.hpp"

namespace spread::field {
namespace {

namespace pd = spread::plot::detail;

constexpr double kTopShare = 1.5;  // the colour map's top: 150 % of the target
constexpr int kMargin = 60, kLegend = 110;

struct Frame {
  int block = 1;            // cells per pixel
  int width = 0, height = 0;  // the map's pixels
  double px_per_m = 1.0;
  double left = kMargin, top = kMargin;  // the map's corner on the canvas
  const RateGrid* grid = nullptr;
  double x(double x_m) const { return left + (x_m - grid->x0_m) * px_per_m; }
  double y(double y_m) const { return top + height - (y_m - grid->y0_m) * px_per_m; }  // north up
};

// A grid's frame at most max_pixels a side.
Frame frame_of(const RateGrid& grid, int max_pixels) {
  Frame f;
  f.grid = &grid;
  f.block = std::max(1, (std::max(grid.nx, grid.ny) + max_pixels - 1) / max_pixels);
  f.width = (grid.nx + f.block - 1) / f.block;
  f.height = (grid.ny + f.block - 1) / f.block;
  f.px_per_m = 1.0 / (grid.cell_m * f.block);
  return f;
}

void draw_scale(cairo_t* cr, const Frame& f) {
  cairo_set_source_rgb(cr, 0, 0, 0);
  pd::set_font(cr, 12);
  pd::draw_text(cr, "north up; 100 m", f.left, f.top + f.height + 25, 0.0, 0.5);
  cairo_move_to(cr, f.left + 110, f.top + f.height + 25);
  cairo_line_to(cr, f.left + 110 + 100.0 * f.px_per_m, f.top + f.height + 25);
  cairo_stroke(cr);
}

pd::Rgb cell_colour(double share, bool inside) {
  const pd::Rgb c = pd::colour_at(std::clamp(share / kTopShare, 0.0, 1.0));
  if (inside) return c;
  return {0.55 + 0.45 * c.r * 0.5, 0.55 + 0.45 * c.g * 0.5, 0.55 + 0.45 * c.b * 0.5};  // faded towards grey
}

// The cells, a block per pixel, into an image surface painted onto the canvas.
void draw_cells(cairo_t* cr, const Frame& f, const std::vector<std::uint8_t>& inside, double target_rate_kg_ha) {
  const RateGrid& g = *f.grid;
  cairo_surface_t* image = cairo_image_surface_create(CAIRO_FORMAT_RGB24, f.width, f.height);
  unsigned char* data = cairo_image_surface_get_data(image);
  const int stride = cairo_image_surface_get_stride(image);
  const double to_share = 1e4 / g.cell_area_m2() / target_rate_kg_ha;
  for (int py = 0; py < f.height; ++py) {
    for (int px = 0; px < f.width; ++px) {
      double mass = 0.0;
      int cells = 0, in = 0;
      for (int by = 0; by < f.block; ++by) {
        const int iy = (f.height - 1 - py) * f.block + by;
        for (int bx = 0; bx < f.block; ++bx) {
          const int ix = px * f.block + bx;
          if (ix >= g.nx || iy >= g.ny) continue;
          const std::size_t i = static_cast<std::size_t>(iy) * g.nx + ix;
          mass += g.mass_kg[i];
          in += inside[i];
          ++cells;
        }
      }
      const pd::Rgb c = cell_colour(cells ? mass / cells * to_share : 0.0, 2 * in >= cells && cells > 0);
      auto* pixel = reinterpret_cast<std::uint32_t*>(data + py * stride) + px;
      *pixel = (static_cast<std::uint32_t>(c.r * 255.0) << 16) | (static_cast<std::uint32_t>(c.g * 255.0) << 8) |
               static_cast<std::uint32_t>(c.b * 255.0);
    }
  }
  cairo_surface_mark_dirty(image);
  cairo_save(cr);
  cairo_translate(cr, f.left, f.top);
  cairo_set_source_surface(cr, image, 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
  cairo_paint(cr);
  cairo_restore(cr);
  cairo_surface_destroy(image);
}

void draw_lines(cairo_t* cr, const Frame& f, const Boundary& boundary, const std::vector<Pass>& passes) {
  cairo_set_source_rgba(cr, 0.3, 0.3, 0.3, 0.6);
  cairo_set_line_width(cr, 0.8);
  for (const Pass& pass : passes) {
    for (std::size_t k = 0; k < pass.path.size(); ++k) {
      const double x = f.x(pass.path[k].x_m), y = f.y(pass.path[k].y_m);
      k == 0 ? cairo_move_to(cr, x, y) : cairo_line_to(cr, x, y);
    }
    cairo_stroke(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 2.0);
  for (std::size_t k = 0; k < boundary.ring.size(); ++k) {
    const double x = f.x(boundary.ring[k].x_m), y = f.y(boundary.ring[k].y_m);
    k == 0 ? cairo_move_to(cr, x, y) : cairo_line_to(cr, x, y);
  }
  cairo_close_path(cr);
  cairo_stroke(cr);
}

// A vertical colour bar, 0–150 % of the target, with the 80 % and 120 % marks.
void draw_legend(cairo_t* cr, const Frame& f, double target_rate_kg_ha) {
  const double left = f.left + f.width + 30, top = f.top, bar_h = std::max(200, f.height / 2), bar_w = 20;
  for (int k = 0; k < static_cast<int>(bar_h); ++k) {
    const pd::Rgb c = pd::colour_at(1.0 - k / bar_h);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_rectangle(cr, left, top + k, bar_w, 1.0);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  pd::set_font(cr, 12);
  for (const double share : {0.0, 0.5, kUnderFraction, 1.0, kOverFraction, kTopShare}) {
    const double y = top + bar_h * (1.0 - share / kTopShare);
    cairo_move_to(cr, left + bar_w, y);
    cairo_line_to(cr, left + bar_w + 5, y);
    cairo_stroke(cr);
    pd::draw_text(cr, std::to_string(static_cast<int>(std::lround(100 * share))) + " %", left + bar_w + 8, y, 0.0, 0.5);
  }
  pd::draw_text(cr, "of " + std::to_string(static_cast<int>(std::lround(target_rate_kg_ha))) + " kg/ha", left,
                top + bar_h + 18, 0.0, 0.5);
}

}  // namespace

void write_field_map_png(const std::string& path, const RateGrid& grid, const Boundary& boundary,
                         const std::vector<Pass>& passes, double target_rate_kg_ha, const std::string& title) {
  const Frame f = frame_of(grid, kMapMaxPixels);
  pd::Canvas canvas(f.width + 2 * kMargin + kLegend, f.height + 2 * kMargin);
  cairo_t* cr = canvas.cr();
  draw_cells(cr, f, inside_mask(grid, boundary.ring), target_rate_kg_ha);
  draw_lines(cr, f, boundary, passes);
  draw_legend(cr, f, target_rate_kg_ha);
  cairo_set_source_rgb(cr, 0, 0, 0);
  pd::set_font(cr, 15, true);
  pd::draw_text(cr, title, kMargin, kMargin / 2.0, 0.0, 0.5);
  draw_scale(cr, f);
  canvas.write_png(path);
}

void write_field_maps_png(const std::string& path, const std::vector<MapPanel>& panels, const Boundary& boundary,
                          double target_rate_kg_ha, const std::string& title) {
  if (panels.empty()) return;
  const int columns = std::min<int>(2, static_cast<int>(panels.size()));
  const int rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
  // One scale for every panel (the largest grid's), so that the panels compare at a glance.
  int widest = 0, tallest = 0, block = 1;
  for (const MapPanel& p : panels) block = std::max(block, frame_of(*p.grid, kPanelMaxPixels).block);
  for (const MapPanel& p : panels) {
    widest = std::max(widest, (p.grid->nx + block - 1) / block);
    tallest = std::max(tallest, (p.grid->ny + block - 1) / block);
  }
  const int cell_w = widest + kMargin / 2, cell_h = tallest + kMargin + 20;
  pd::Canvas canvas(columns * cell_w + kMargin + kLegend, rows * cell_h + kMargin + 20);
  cairo_t* cr = canvas.cr();
  Frame last;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const MapPanel& p = panels[i];
    Frame f;
    f.grid = p.grid;
    f.block = block;
    f.width = (p.grid->nx + block - 1) / block;
    f.height = (p.grid->ny + block - 1) / block;
    f.px_per_m = 1.0 / (p.grid->cell_m * block);
    f.left = kMargin + static_cast<double>(static_cast<int>(i) % columns) * cell_w;
    f.top = kMargin + 20 + static_cast<double>(static_cast<int>(i) / columns) * cell_h;
    draw_cells(cr, f, inside_mask(*p.grid, boundary.ring), target_rate_kg_ha);
    draw_lines(cr, f, boundary, *p.passes);
    // The title's lines above the panel, the last one nearest.
    cairo_set_source_rgb(cr, 0, 0, 0);
    pd::set_font(cr, 12, true);
    std::vector<std::string> lines;
    for (std::size_t from = 0;;) {
      const std::size_t end = p.title.find('\n', from);
      lines.push_back(p.title.substr(from, end == std::string::npos ? std::string::npos : end - from));
      if (end == std::string::npos) break;
      from = end + 1;
    }
    for (std::size_t k = 0; k < lines.size(); ++k) {
      pd::draw_text(cr, lines[k], f.left, f.top - 10 - 16.0 * static_cast<double>(lines.size() - 1 - k), 0.0, 0.5);
    }
    last = f;
  }
  draw_scale(cr, last);
  Frame legend = last;
  legend.left = kMargin + (columns - 1) * cell_w;
  legend.top = kMargin + 20;
  draw_legend(cr, legend, target_rate_kg_ha);
  cairo_set_source_rgb(cr, 0, 0, 0);
  pd::set_font(cr, 15, true);
  pd::draw_text(cr, title, kMargin, kMargin / 2.0, 0.0, 0.5);
  canvas.write_png(path);
}

}  // namespace spread::field
