#pragma once
// A white image surface with its cairo context, written to PNG on request (RAII: the surface and
// context are released however the drawing code leaves).
#include <string>

#include <cairo.h>

namespace spread::plot::detail {

class Canvas {
 public:
  Canvas(int width_px, int height_px);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cairo_t* cr() const { return cr_; }
  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }

  // Throws std::runtime_error naming the path (and cairo's reason) when the PNG cannot be written.
  void write_png(const std::string& path) const;

 private:
  cairo_surface_t* surface_;
  cairo_t* cr_;
  int width_px_;
  int height_px_;
};

// Text helpers in the plots' one font (sans-serif), size in pixels.
void set_font(cairo_t* cr, double size_px, bool bold = false);
// Draws `text` so that the point (x, y) sits at fraction (ax, ay) of its extents: (0.5, 0.5) centres it,
// (1, 0.5) right-aligns it. Returns the text width (px).
double draw_text(cairo_t* cr, const std::string& text, double x, double y, double ax, double ay);
// Same, rotated 90° counter-clockwise about (x, y) (for y-axis labels).
void draw_text_vertical(cairo_t* cr, const std::string& text, double x, double y);

}  // namespace spread::plot::detail
