// Transverse distribution: one bar per tray, an optional second series (e.g. a tray test), and
// optionally the overlapped profile of one bout at width W (metrics::overlapped_profile).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/analysis/plot/axes.hpp"
#include "libspread/analysis/plot/canvas.hpp"
#include "libspread/analysis/plot/cv_text.hpp"
#include "libspread/analysis/plot/mass_unit.hpp"
#include "libspread/analysis/plot/plot.hpp"
#include "libspread/analysis/plot/transverse_bout.hpp"
#include "libspread/analysis/plot/transverse_drawing.hpp"

namespace spread::plot {
namespace {

constexpr detail::Rgb kMainColour{0.25, 0.45, 0.75};
constexpr detail::Rgb kSecondColour{0.90, 0.50, 0.10};
constexpr detail::Rgb kOverlapColour{0.10, 0.60, 0.25};
constexpr detail::Rgb kMeanColour{0.15, 0.15, 0.15};
constexpr detail::Rgb kMissingColour{0.80, 0.10, 0.10};

void require_series(std::span<const double> mass_kg, const metrics::TrayLayout& trays, const char* name) {
  if (mass_kg.size() != static_cast<std::size_t>(trays.tray_count)) {
    throw std::invalid_argument(std::string("write_transverse_png: ") + name + " has " +
                                std::to_string(mass_kg.size()) + " trays, the layout " +
                                std::to_string(trays.tray_count));
  }
  for (double m : mass_kg) {
    if (!std::isfinite(m)) throw std::invalid_argument(std::string("write_transverse_png: ") + name + " holds a non-finite mass");
  }
}

}  // namespace

void write_transverse_png(std::span<const double> tray_mass_kg, const metrics::TrayLayout& trays,
                          const std::string& path, const std::string& title, const TransverseOptions& options) {
  detail::Canvas canvas(kImageWidth_px, kImageHeight_px);
  detail::draw_transverse(canvas.cr(), tray_mass_kg, trays, title, options);
  canvas.write_png(path);
}

namespace detail {

void draw_transverse(cairo_t* cr, std::span<const double> tray_mass_kg, const metrics::TrayLayout& trays,
                     const std::string& title, const TransverseOptions& options) {
  if (trays.tray_count <= 0 || !(trays.tray_width_m > 0.0) || !std::isfinite(trays.tray_width_m)) {
    throw std::invalid_argument("write_transverse_png: the tray layout is empty or its tray width is not > 0");
  }
  require_series(tray_mass_kg, trays, "tray_mass_kg");
  const bool second = !options.second_tray_mass_kg.empty();
  if (second) require_series(options.second_tray_mass_kg, trays, "second_tray_mass_kg");
  const bool overlapped = options.bout_width_m > 0.0;
  if (!std::isfinite(options.bout_width_m)) {
    throw std::invalid_argument("write_transverse_png: bout_width_m is not finite");
  }

  const bool any_missing = std::find(options.missing_trays.begin(), options.missing_trays.end(), true) !=
                           options.missing_trays.end();
  if (!options.missing_trays.empty() && options.missing_trays.size() != static_cast<std::size_t>(trays.tray_count)) {
    throw std::invalid_argument("write_transverse_png: missing_trays has " + std::to_string(options.missing_trays.size()) +
                                " flags, the layout " + std::to_string(trays.tray_count) + " trays");
  }
  // The bout as the legend states it (transverse_bout.hpp): the same numbers a command's --json gives.
  const detail::OverlappedBout ob = detail::overlapped_bout(tray_mass_kg, trays, options, any_missing);
  const std::vector<double>& bout_kg = ob.kg;
  const std::vector<bool>& bout_gap = ob.gap;
  const metrics::BoutTrays& bout = ob.trays;
  const double bout_half_m = ob.half_m, bout_cv = ob.cv, bout_mean_kg = ob.mean_kg;
  const bool band = overlapped && options.mean_band && std::isfinite(bout_cv) && bout_mean_kg > 0.0;

  if (!(options.tray_area_m2 >= 0.0) || !std::isfinite(options.tray_area_m2)) {
    throw std::invalid_argument("write_transverse_png: tray_area_m2 must be finite and >= 0");
  }
  const bool fraction = options.units == MassUnits::kFraction;
  const bool rate = !fraction && options.tray_area_m2 > 0.0;
  const detail::MassUnit unit = detail::chart_unit(tray_mass_kg, options, ob, band);
  const double max_kg = detail::chart_max_kg(tray_mass_kg, options, ob, band);

  double x_lo = trays.left_edge_m(), x_hi = -trays.left_edge_m();
  x_lo = std::min(x_lo, -bout_half_m);
  x_hi = std::max(x_hi, bout_half_m);
  detail::nice_range(x_lo, x_hi, 10);
  // Headroom so the legend (22 px a row in a 510 px plot) sits above the tallest bar.
  const int legend_rows = 1 + (second ? 1 : 0) + (overlapped ? 1 : 0) + (band ? 2 : 0) + (any_missing ? 1 : 0);
  const double headroom = 1.0 / (1.0 - (30.0 + 22.0 * legend_rows) / 510.0);
  double y_lo = 0.0, y_hi = (max_kg > 0.0 ? max_kg : 1e-3) * unit.per_kg * headroom;
  detail::nice_range(y_lo, y_hi, 8);

  cairo_save(cr);
  const detail::Axes axes(110.0, 55.0, 850.0, 510.0, x_lo, x_hi, y_lo, y_hi);
  axes.draw_grid(cr);
  axes.clip(cr);

  // Bars: the main series full tray width; the second series as narrower bars inside, so both show.
  const double w_m = trays.tray_width_m;
  for (int k = 0; k < trays.tray_count; ++k) {
    const double left_m = trays.left_edge_m() + k * w_m;
    const double main = tray_mass_kg[static_cast<std::size_t>(k)] * unit.per_kg;
    cairo_set_source_rgb(cr, kMainColour.r, kMainColour.g, kMainColour.b);
    const double inset_m = second ? 0.04 * w_m : 0.06 * w_m;
    const double right_m = second ? left_m + 0.5 * w_m : left_m + w_m - inset_m;
    cairo_rectangle(cr, axes.px(left_m + inset_m), axes.py(main), axes.px(right_m) - axes.px(left_m + inset_m),
                    axes.py(0.0) - axes.py(main));
    cairo_fill(cr);
    if (second) {
      const double other = options.second_tray_mass_kg[static_cast<std::size_t>(k)] * unit.per_kg;
      cairo_set_source_rgb(cr, kSecondColour.r, kSecondColour.g, kSecondColour.b);
      cairo_rectangle(cr, axes.px(left_m + 0.5 * w_m), axes.py(other),
                      axes.px(left_m + w_m - inset_m) - axes.px(left_m + 0.5 * w_m), axes.py(0.0) - axes.py(other));
      cairo_fill(cr);
    }
  }

  std::vector<detail::LegendEntry> legend;
  legend.push_back({options.series_label, kMainColour, detail::LegendEntry::Kind::kBox});
  if (second) legend.push_back({options.second_label, kSecondColour, detail::LegendEntry::Kind::kBox});
  if (any_missing) {
    // A cross on the axis where a tray has no reading.
    cairo_set_source_rgb(cr, kMissingColour.r, kMissingColour.g, kMissingColour.b);
    cairo_set_line_width(cr, 2.5);
    for (int k = 0; k < trays.tray_count; ++k) {
      if (!options.missing_trays[static_cast<std::size_t>(k)]) continue;
      const double x = axes.px(trays.left_edge_m() + (k + 0.5) * w_m), y = axes.py(0.0) - 9.0;
      cairo_move_to(cr, x - 6.0, y - 6.0);
      cairo_line_to(cr, x + 6.0, y + 6.0);
      cairo_move_to(cr, x - 6.0, y + 6.0);
      cairo_line_to(cr, x + 6.0, y - 6.0);
    }
    cairo_stroke(cr);
    legend.push_back({overlapped ? "missing tray (x); the profile has a gap where it would count"
                                 : "missing tray (x)",
                      kMissingColour, detail::LegendEntry::Kind::kLine});
  }

  if (band) {
    // Under the profile: the band mean × (1 ± CV) over the bout, then the mean itself (dashed).
    const double lo = axes.py(bout_mean_kg * (1.0 - bout_cv) * unit.per_kg);
    const double hi = axes.py(bout_mean_kg * (1.0 + bout_cv) * unit.per_kg);
    cairo_set_source_rgba(cr, kOverlapColour.r, kOverlapColour.g, kOverlapColour.b, 0.18);
    cairo_rectangle(cr, axes.px(-bout_half_m), hi, axes.px(bout_half_m) - axes.px(-bout_half_m), lo - hi);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, kMeanColour.r, kMeanColour.g, kMeanColour.b);
    cairo_set_line_width(cr, 2.0);
    const double dash[] = {10.0, 5.0};
    cairo_set_dash(cr, dash, 2, 0.0);
    const double y = axes.py(bout_mean_kg * unit.per_kg);
    cairo_move_to(cr, axes.px(-bout_half_m), y);
    cairo_line_to(cr, axes.px(bout_half_m), y);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0.0);
  }

  if (overlapped) {
    // The overlapped profile as a step line over the bout (grid trays, the cut edge trays clipped at the
    // bout edges), the bout edges dashed.
    cairo_set_source_rgb(cr, kOverlapColour.r, kOverlapColour.g, kOverlapColour.b);
    cairo_set_line_width(cr, 3.0);
    bool pen_down = false;
    for (std::size_t j = 0; j < bout_kg.size(); ++j) {
      if (bout_gap[j]) {  // no value there: the line stops and starts again after it
        pen_down = false;
        continue;
      }
      const double a_m = std::max(-bout_half_m, trays.left_edge_m() + (bout.first_tray + static_cast<double>(j)) * w_m);
      const double b_m = std::min(bout_half_m, trays.left_edge_m() + (bout.first_tray + static_cast<double>(j) + 1.0) * w_m);
      const double y = axes.py(bout_kg[j] * unit.per_kg);
      if (!pen_down) {
        pen_down = true;
        cairo_move_to(cr, axes.px(a_m), y);
      } else {
        cairo_line_to(cr, axes.px(a_m), y);
      }
      cairo_line_to(cr, axes.px(b_m), y);
    }
    cairo_stroke(cr);
    const double dash[] = {6.0, 4.0};
    cairo_set_dash(cr, dash, 2, 0.0);
    cairo_set_line_width(cr, 1.5);
    for (double edge_m : {-bout_half_m, bout_half_m}) {
      cairo_move_to(cr, axes.px(edge_m), axes.top());
      cairo_line_to(cr, axes.px(edge_m), axes.top() + axes.height());
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0.0);
    char label[160];
    std::snprintf(label, sizeof label, "overlapped, %s, W = %.2f m: CV %s",
                  options.overlap == metrics::Overlap::kToAndFro ? "to-and-fro" : "racetrack", 2.0 * bout_half_m,
                  std::isnan(bout_cv) ? "none (too few trays of the bout read)"
                                      : cv_percent_text(bout_cv, options.cv_target).c_str());
    legend.push_back({label, kOverlapColour, detail::LegendEntry::Kind::kLine});
  }
  if (band) {
    char label[160];
    std::snprintf(label, sizeof label, "mean of the bout: %.3g %s%s", bout_mean_kg * unit.per_kg, unit.name.c_str(),
                  rate ? "" : " per tray");
    legend.push_back({label, kMeanColour, detail::LegendEntry::Kind::kDashedLine});
    std::snprintf(label, sizeof label, "mean ± CV (%s)", cv_percent_text(bout_cv, options.cv_target).c_str());
    legend.push_back({label, Rgb{0.70, 0.85, 0.74}, detail::LegendEntry::Kind::kBox});
  }
  cairo_restore(cr);  // clip

  axes.draw_frame(cr, "x, across the driving direction (m)",
                  rate ? "rate: tray mass / tray area (kg/ha)"
                       : (fraction ? "share per " : "mass per ") + detail::tick_label(w_m, 0.1) + " m tray (" + unit.name + ")");
  detail::draw_legend(cr, legend, axes.left() + axes.width() - 8.0, axes.top() + 8.0);
  detail::draw_title(cr, title, 0.5 * kImageWidth_px, 14.0);
  cairo_restore(cr);
}

}  // namespace detail
}  // namespace spread::plot
