#include "libspread/analysis/plot/canvas.hpp"

#include <stdexcept>

namespace spread::plot::detail {

Canvas::Canvas(int width_px, int height_px)
    : surface_(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width_px, height_px)),
      cr_(cairo_create(surface_)),
      width_px_(width_px),
      height_px_(height_px) {
  if (cairo_status(cr_) != CAIRO_STATUS_SUCCESS) {
    const std::string reason = cairo_status_to_string(cairo_status(cr_));
    cairo_destroy(cr_);
    cairo_surface_destroy(surface_);
    throw std::runtime_error("cannot create a " + std::to_string(width_px) + "×" + std::to_string(height_px) +
                             " image: " + reason);
  }
  cairo_set_source_rgb(cr_, 1.0, 1.0, 1.0);
  cairo_paint(cr_);
}

Canvas::~Canvas() {
  cairo_destroy(cr_);
  cairo_surface_destroy(surface_);
}

void Canvas::write_png(const std::string& path) const {
  cairo_surface_flush(surface_);
  const cairo_status_t status = cairo_surface_write_to_png(surface_, path.c_str());
  if (status != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error("cannot write PNG '" + path + "': " + cairo_status_to_string(status));
  }
}

void set_font(cairo_t* cr, double size_px, bool bold) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size_px);
}

double draw_text(cairo_t* cr, const std::string& text, double x, double y, double ax, double ay) {
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  cairo_font_extents_t font;
  cairo_font_extents(cr, &font);
  // Vertical placement from the font's ascent/descent, so labels in a row share a baseline.
  const double height = font.ascent + font.descent;
  cairo_move_to(cr, x - ax * extents.x_advance, y - ay * height + font.ascent);
  cairo_show_text(cr, text.c_str());
  cairo_new_path(cr);
  return extents.x_advance;
}

void draw_text_vertical(cairo_t* cr, const std::string& text, double x, double y) {
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, -1.5707963267948966);
  draw_text(cr, text, 0.0, 0.0, 0.5, 0.5);
  cairo_restore(cr);
}

}  // namespace spread::plot::detail
