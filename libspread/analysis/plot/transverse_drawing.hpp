#pragma once
// The transverse-distribution plot drawn onto any cairo context (an image for the PNG, a scaled region
// of a PDF page for the report): a kImageWidth_px × kImageHeight_px drawing in the context's current
// user space. write_transverse_png and the PDF report share it, so the two cannot show different things.
#include <span>
#include <string>

#include <cairo.h>

#include "libspread/analysis/plot/plot.hpp"

namespace spread::plot::detail {

// Same inputs and checks as write_transverse_png (std::invalid_argument naming the offending input).
void draw_transverse(cairo_t* cr, std::span<const double> tray_mass_kg, const metrics::TrayLayout& trays,
                     const std::string& title, const TransverseOptions& options);

}  // namespace spread::plot::detail
