// The PDF report's pages (report_pdf.hpp). Layout in points on A4: a 40 pt margin, text in the plots'
// sans-serif, the transverse chart drawn by the same code as the PNG (transverse_drawing.hpp), scaled
// to the text width.
#include "libspread/analysis/plot/report_pdf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <cairo-pdf.h>
#include <cairo.h>

#include "libspread/analysis/plot/canvas.hpp"
#include "libspread/analysis/plot/cv_text.hpp"
#include "libspread/analysis/plot/report_date.hpp"
#include "libspread/analysis/plot/transverse_drawing.hpp"

namespace spread::plot {
namespace {

constexpr double kMargin_pt = 40.0;
constexpr double kTextWidth_pt = kPageWidth_pt - 2.0 * kMargin_pt;
constexpr double kBody_pt = 10.0;
constexpr double kLine_pt = 14.0;

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

// A table cell's CV: as the verdicts print it (cv_text.hpp), "none" where missing trays leave no CV.
std::string cv_cell(double cv, double target) { return cv_percent_text(cv, target); }

// "1.00-2.74 m, 3.49-3.50 m", or "none".
std::string bands_text(const std::vector<std::pair<double, double>>& bands) {
  std::string text;
  for (const auto& [lower, upper] : bands) {
    text += (text.empty() ? "" : ", ") + format("%.2f", lower) + format("-%.2f m", upper);
  }
  return text.empty() ? "none" : text;
}

// Writes `text` from (x, y) on, broken at spaces into lines no wider than `width_pt`; returns the y
// below the last line.
// With draw false, only measures: returns the same y without drawing.
double draw_wrapped(cairo_t* cr, const std::string& text, double x, double y, double width_pt,
                    double line_pt = kLine_pt, bool draw = true) {
  std::istringstream words(text);
  std::string word, line;
  auto flush = [&] {
    if (draw) detail::draw_text(cr, line, x, y, 0.0, 0.0);
    y += line_pt;
    line.clear();
  };
  auto width_of = [&](const std::string& t) {
    cairo_text_extents_t extents;
    cairo_text_extents(cr, t.c_str(), &extents);
    return extents.x_advance;
  };
  while (words >> word) {
    // A word longer than the line (a file path without spaces) is cut at UTF-8 character boundaries.
    while (line.empty() && word.size() > 1 && width_of(word) > width_pt) {
      std::size_t cut = word.size() - 1;
      while (cut > 1 && (width_of(word.substr(0, cut)) > width_pt || (static_cast<unsigned char>(word[cut]) & 0xC0) == 0x80)) --cut;
      line = word.substr(0, cut);
      flush();
      word = word.substr(cut);
    }
    const std::string candidate = line.empty() ? word : line + " " + word;
    cairo_text_extents_t extents;
    cairo_text_extents(cr, candidate.c_str(), &extents);
    if (!line.empty() && extents.x_advance > width_pt) flush();
    line = line.empty() ? word : line + " " + word;
  }
  if (!line.empty()) flush();
  return y;
}

void set_black(cairo_t* cr) { cairo_set_source_rgb(cr, 0.0, 0.0, 0.0); }

// The verdicts' colours: green, amber, red (and grey for no verdict), dark enough to print.
void set_level_colour(cairo_t* cr, ReportVerdict::Level level) {
  switch (level) {
    case ReportVerdict::Level::kPass: cairo_set_source_rgb(cr, 0.0, 0.45, 0.0); return;
    case ReportVerdict::Level::kMarginal: cairo_set_source_rgb(cr, 0.80, 0.45, 0.0); return;
    case ReportVerdict::Level::kFail: cairo_set_source_rgb(cr, 0.75, 0.0, 0.0); return;
    case ReportVerdict::Level::kNone: cairo_set_source_rgb(cr, 0.4, 0.4, 0.4); return;
  }
}

// The verdicts, one a line: the word bold in its colour in a column of its own, the grounds beside it.
double draw_verdicts(cairo_t* cr, const std::vector<ReportVerdict>& verdicts, double y) {
  if (verdicts.empty()) return y;
  constexpr double kWord_pt = 84.0;  // "MARGINAL" at 12 pt bold and a gap
  for (const ReportVerdict& v : verdicts) {
    set_level_colour(cr, v.level);
    detail::set_font(cr, 12.0, true);
    detail::draw_text(cr, v.word, kMargin_pt, y, 0.0, 0.0);
    set_black(cr);
    detail::set_font(cr, kBody_pt, true);
    y = draw_wrapped(cr, v.text, kMargin_pt + kWord_pt, y + 1.0, kTextWidth_pt - kWord_pt) + 2.0;
  }
  set_black(cr);
  cairo_set_line_width(cr, 0.5);
  cairo_move_to(cr, kMargin_pt, y);
  cairo_line_to(cr, kPageWidth_pt - kMargin_pt, y);
  cairo_stroke(cr);
  return y + 10.0;
}

// Title, date, and the header fields in two columns; returns the y below them.
double draw_header(cairo_t* cr, const ReportHeader& h) {
  set_black(cr);
  detail::set_font(cr, 18.0, true);
  detail::draw_text(cr, h.title, kMargin_pt, kMargin_pt, 0.0, 0.0);
  detail::set_font(cr, kBody_pt);
  detail::draw_text(cr, "date " + utc_date(h.time_s), kPageWidth_pt - kMargin_pt, kMargin_pt + 4.0, 1.0, 0.0);
  auto or_not_given = [](const std::string& s) { return s.empty() ? std::string("not given") : s; };
  auto number = [](double v, const char* pattern) { return std::isnan(v) ? std::string("not given") : format(pattern, v); };
  const std::pair<std::string, std::string> fields[] = {
      {"Machine", or_not_given(h.machine)},        {"Material", or_not_given(h.material)},
      {"Disc speed", h.rpm_text.empty() ? number(h.rpm, "%.0f rpm") : h.rpm_text},  {"Forward speed", number(h.speed_km_h, "%.1f km/h")},
  };
  double y = kMargin_pt + 32.0;
  double row_bottom = 0.0;
  for (std::size_t i = 0; i < std::size(fields); ++i) {
    const double x = kMargin_pt + (i % 2 == 0 ? 0.0 : 0.5 * kTextWidth_pt);
    detail::set_font(cr, kBody_pt, true);
    const double label_pt = detail::draw_text(cr, fields[i].first + ": ", x, y, 0.0, 0.0);
    detail::set_font(cr, kBody_pt);
    // A long name (a material with its batch) wraps within its half of the line instead of running off
    // the page; the row is as tall as its taller field.
    const double below = draw_wrapped(cr, fields[i].second, x + label_pt, y, 0.5 * kTextWidth_pt - label_pt - 6.0);
    row_bottom = std::max(row_bottom, below);
    if (i % 2 == 1) {
      y = row_bottom;
      row_bottom = 0.0;
    }
  }
  if (!h.source.empty()) {
    detail::set_font(cr, kBody_pt, true);
    const double label_pt = detail::draw_text(cr, "Data: ", kMargin_pt, y, 0.0, 0.0);
    detail::set_font(cr, kBody_pt);
    // The file's name, not where it lay on the computer that made the page: a farmer reads no paths (the
    // footer's command line holds the whole one).
    const std::size_t slash = h.source.find_last_of("/\\");
    y = draw_wrapped(cr, slash == std::string::npos ? h.source : h.source.substr(slash + 1), kMargin_pt + label_pt, y,
                     kTextWidth_pt - label_pt);
  }
  cairo_set_line_width(cr, 0.8);
  cairo_move_to(cr, kMargin_pt, y + 4.0);
  cairo_line_to(cr, kPageWidth_pt - kMargin_pt, y + 4.0);
  cairo_stroke(cr);
  return y + 14.0;
}

void draw_footer(cairo_t* cr, const ReportHeader& h) {
  if (h.made_by.empty()) return;
  cairo_save(cr);
  cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
  detail::set_font(cr, 7.0);
  // Up to three lines of 9 pt in the bottom margin.
  draw_wrapped(cr, "made by: " + h.made_by + " (" + utc_date_time(h.time_s) + ")", kMargin_pt,
               kPageHeight_pt - kMargin_pt - 6.0, kTextWidth_pt, 9.0);
  cairo_restore(cr);
}

// The notes at the bottom of a page. They are drawn at the body size when they fit above the footer, else
// at the largest size down to 6.5 pt that fits; what does not fit even then continues on a page of its
// own (with the footer on both) — a note is never drawn over the footer or off the page.
void draw_notes(cairo_t* cr, const std::vector<std::string>& notes, double y, const ReportHeader& header) {
  if (notes.empty()) return;
  constexpr double kLowest_pt = 6.5;
  const double bottom = kPageHeight_pt - kMargin_pt - 8.0;  // the footer's first line starts below
  auto height_at = [&](double size_pt) {
    detail::set_font(cr, size_pt);
    double end = 0.0;
    for (const std::string& n : notes) end = draw_wrapped(cr, "• " + n, kMargin_pt, end, kTextWidth_pt, 1.4 * size_pt, false);
    return end;
  };
  set_black(cr);
  detail::set_font(cr, 11.0, true);
  detail::draw_text(cr, "Notes", kMargin_pt, y, 0.0, 0.0);
  y += kLine_pt + 2.0;
  double size_pt = kBody_pt;
  while (size_pt > kLowest_pt && y + height_at(size_pt) > bottom) size_pt -= 0.5;
  for (const std::string& n : notes) {
    detail::set_font(cr, size_pt);
    const double below = draw_wrapped(cr, "• " + n, kMargin_pt, y, kTextWidth_pt, 1.4 * size_pt, false);
    if (below > bottom && y > kMargin_pt + 40.0) {  // continue on a page of its own
      draw_footer(cr, header);
      cairo_show_page(cr);
      detail::set_font(cr, 11.0, true);
      detail::draw_text(cr, header.title + ": notes (continued)", kMargin_pt, kMargin_pt, 0.0, 0.0);
      y = kMargin_pt + kLine_pt + 10.0;
      detail::set_font(cr, size_pt);
    }
    y = draw_wrapped(cr, "• " + n, kMargin_pt, y, kTextWidth_pt, 1.4 * size_pt);
  }
}

double draw_lines(cairo_t* cr, const std::vector<std::string>& lines, double y, const std::string& prefix = "") {
  detail::set_font(cr, kBody_pt);
  for (const std::string& l : lines) y = draw_wrapped(cr, prefix + l, kMargin_pt, y, kTextWidth_pt);
  return y;
}

// A table with a bold header row. Each column is as wide as its widest cell (header bold, cells plain),
// the space left over shared between the columns; when the columns need more than the text width the
// font shrinks until they fit (down to 6 pt) — cells never run into each other. The first column is
// left-aligned, the others right-aligned at their column's end (numbers line up). Returns the y below.
double draw_table(cairo_t* cr, const std::string& caption, const std::vector<std::string>& columns,
                  const std::vector<std::vector<std::string>>& rows, double y) {
  set_black(cr);
  detail::set_font(cr, 11.0, true);
  detail::draw_text(cr, caption, kMargin_pt, y, 0.0, 0.0);
  y += kLine_pt + 4.0;
  constexpr double kGap_pt = 10.0;
  auto width_of = [&](const std::string& text, double size_pt, bool bold) {
    detail::set_font(cr, size_pt, bold);
    cairo_text_extents_t extents;
    cairo_text_extents(cr, text.c_str(), &extents);
    return extents.x_advance;
  };
  double size_pt = kBody_pt;
  std::vector<double> widths(columns.size(), 0.0);
  for (;;) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      widths[c] = width_of(columns[c], size_pt, true);
      for (const auto& row : rows) widths[c] = std::max(widths[c], width_of(row[c], size_pt, false));
    }
    double total = kGap_pt * static_cast<double>(columns.size() - 1);
    for (double w : widths) total += w;
    if (total <= kTextWidth_pt || size_pt <= 6.0) {
      // The room left over, shared out: the table spans the text width as before.
      const double extra = std::max(0.0, kTextWidth_pt - total) / static_cast<double>(columns.size());
      for (double& w : widths) w += extra;
      break;
    }
    size_pt -= 0.5;
  }
  std::vector<double> x_left(columns.size(), kMargin_pt);
  for (std::size_t c = 1; c < columns.size(); ++c) x_left[c] = x_left[c - 1] + widths[c - 1] + kGap_pt;
  auto draw_row = [&](const std::vector<std::string>& cells, bool bold) {
    detail::set_font(cr, size_pt, bold);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (c == 0) {
        detail::draw_text(cr, cells[c], x_left[c], y, 0.0, 0.0);
      } else {
        detail::draw_text(cr, cells[c], x_left[c] + widths[c], y, 1.0, 0.0);
      }
    }
  };
  draw_row(columns, true);
  y += kLine_pt;
  cairo_set_line_width(cr, 0.5);
  cairo_move_to(cr, kMargin_pt, y - 2.0);
  cairo_line_to(cr, kPageWidth_pt - kMargin_pt, y - 2.0);
  cairo_stroke(cr);
  for (const auto& row : rows) {
    draw_row(row, false);
    y += kLine_pt;
  }
  detail::set_font(cr, kBody_pt);
  return y + 6.0;
}

void draw_pattern_page(cairo_t* cr, const PatternReport& r) {
  double y = draw_header(cr, r.header);
  y = draw_verdicts(cr, r.verdicts, y);
  y = draw_lines(cr, r.summary, y) + 4.0;

  // The chart, drawn in the PNG's pixel space scaled to the text width.
  // 0.7 of the text width, centred: the verdicts above it need the room, and the page holds the notes
  // (a calibration's guidance and the next steps among them) too.
  const double scale = 0.7 * kTextWidth_pt / kImageWidth_px;
  cairo_save(cr);
  cairo_translate(cr, kMargin_pt + 0.15 * kTextWidth_pt, y);
  cairo_scale(cr, scale, scale);
  TransverseOptions chart = r.chart;
  chart.mean_band = true;
  detail::draw_transverse(cr, r.tray_mass_kg, r.trays, r.chart_title, chart);
  cairo_restore(cr);
  y += kImageHeight_px * scale + 10.0;

  std::vector<std::vector<std::string>> rows;
  for (const CvTableRow& row : r.cv_table) {
    const bool driven = r.chart.bout_width_m > 0.0 && std::abs(row.bout_width_m - r.chart.bout_width_m) < 1e-3;
    rows.push_back({format("%.1f m", row.bout_width_m) + (driven ? " (" + r.bout_row_mark + ")" : ""),
                    cv_cell(row.cv_to_and_fro, r.cv_target), cv_cell(row.cv_racetrack, r.cv_target)});
  }
  y = draw_table(cr, "CV per working width (target " + format("%g %%", 100.0 * r.cv_target) + ")",
                 {"working width", "CV to-and-fro", "CV racetrack"}, rows, y);
  detail::set_font(cr, kBody_pt);
  // With the bands within the target: the working width ends the widest, and a row of the table between
  // two bands is above the target however wide the working width.
  const bool bands = !r.bands_to_and_fro_m.empty() || !r.bands_racetrack_m.empty();
  y = draw_wrapped(cr,
                   "Effective working width (CV <= " + format("%g %%", 100.0 * r.cv_target) + "): " +
                       format("%.2f m", r.working_width_to_and_fro_m) + " to-and-fro, " +
                       format("%.2f m", r.working_width_racetrack_m) + " racetrack" +
                       (bands ? "; within the target at " + bands_text(r.bands_to_and_fro_m) + " to-and-fro, " +
                                    bands_text(r.bands_racetrack_m) + " racetrack, above it between"
                              : std::string()),
                   kMargin_pt, y, kTextWidth_pt);
  y += 6.0;

  if (r.rate) {
    const ReportRate& rate = *r.rate;
    detail::set_font(cr, 11.0, true);
    detail::draw_text(cr, "Application rate", kMargin_pt, y, 0.0, 0.0);
    y += kLine_pt + 2.0;
    detail::set_font(cr, kBody_pt);
    y = draw_wrapped(cr,
                     "Caught in the trays at W = " + format("%.2f m", rate.bout_width_m) + ": " +
                         format("%.1f kg/ha", rate.rate_kg_ha) + " (tray area " + format("%.4g m²", rate.tray_area_m2) +
                         ")",
                     kMargin_pt, y, kTextWidth_pt);
    // EN 13739-2's check is stated with the verdicts at the top of the page (ReportVerdict), not again here.
    y += 6.0;
  }
  draw_notes(cr, r.notes, y, r.header);
  draw_footer(cr, r.header);
}

void draw_table_page(cairo_t* cr, const TablePage& t) {
  double y = draw_header(cr, t.header);
  y = draw_verdicts(cr, t.verdicts, y);
  y = draw_lines(cr, t.summary, y) + 8.0;
  y = draw_table(cr, t.caption, t.columns, t.rows, y);
  draw_notes(cr, t.notes, y, t.header);
  draw_footer(cr, t.header);
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};

// PDF dates as cairo takes them (ISO 8601, UTC).
std::string pdf_date(std::int64_t time_s) {
  std::string d = utc_date_time(time_s);  // "YYYY-MM-DD HH:MM UTC"
  return d.substr(0, 10) + "T" + d.substr(11, 5) + ":00Z";
}

}  // namespace

void write_report_pdf(const std::string& path, const PatternReport* pattern, const TablePage* table) {
  if (pattern == nullptr && table == nullptr) throw std::invalid_argument("write_report_pdf: no page to write");
  if (table != nullptr) {
    for (const auto& row : table->rows) {
      if (row.size() != table->columns.size()) {
        throw std::invalid_argument("write_report_pdf: a table row has " + std::to_string(row.size()) +
                                    " cells for " + std::to_string(table->columns.size()) + " columns");
      }
    }
  }
  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(
      cairo_pdf_surface_create(path.c_str(), kPageWidth_pt, kPageHeight_pt));
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error("cannot write PDF '" + path + "': " + cairo_status_to_string(cairo_surface_status(surface.get())));
  }
  const ReportHeader& first = pattern != nullptr ? pattern->header : table->header;
  // Fixed metadata: the same report from the same data (and SOURCE_DATE_EPOCH) is the same file.
  const std::string date = pdf_date(first.time_s);
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, date.c_str());
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_MOD_DATE, date.c_str());
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, first.title.c_str());
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "libspread");
  std::unique_ptr<cairo_t, ContextDeleter> context(cairo_create(surface.get()));
  cairo_t* cr = context.get();
  if (pattern != nullptr) {
    draw_pattern_page(cr, *pattern);
    cairo_show_page(cr);
  }
  if (table != nullptr) {
    draw_table_page(cr, *table);
    cairo_show_page(cr);
  }
  const cairo_status_t drawn = cairo_status(cr);
  context.reset();
  cairo_surface_finish(surface.get());
  const cairo_status_t status = drawn != CAIRO_STATUS_SUCCESS ? drawn : cairo_surface_status(surface.get());
  if (status != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error("cannot write PDF '" + path + "': " + cairo_status_to_string(status));
  }
}

}  // namespace spread::plot
