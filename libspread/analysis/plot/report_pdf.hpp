#pragma once
// A report to hand over, as PDF (cairo's PDF surface, A4 portrait): the pattern page — a header (machine,
// material, disc speed, forward speed, date), the single-pass transverse bar chart with the overlapped
// profile at the set working width, the bout's mean and the band mean × (1 ± CV), the table of CV per
// working width for both driving modes, the effective working widths and, when the tray area is known,
// the rate in kg/ha with the check against the catch test — and/or a page of settings per working width
// (`spread chart`). The numbers are computed by the caller (the metrics and calibration code the text
// and JSON reports use); this file only lays them out. docs/field-calibration.md, "Report".
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/plot/cv_table.hpp"
#include "libspread/analysis/plot/plot.hpp"

namespace spread::plot {

// A4 portrait in PostScript points (1/72 inch).
inline constexpr double kPageWidth_pt = 595.276;
inline constexpr double kPageHeight_pt = 841.890;

struct ReportHeader {
  std::string title = "Spread pattern report";
  std::string source;                  // the tray-test file or the table file the numbers come from
  std::string machine;                 // "" = not given
  std::string material;                // "" = not given
  double rpm = std::numeric_limits<double>::quiet_NaN();         // disc speed, r/min; NaN = not given
  std::string rpm_text;                // printed instead of the rpm when set (e.g. "per width, below")
  double speed_km_h = std::numeric_limits<double>::quiet_NaN();  // forward speed; NaN = not given
  std::int64_t time_s = 0;             // seconds since 1970 (report_time_s()): the date printed
  std::string made_by;                 // the footer: the command that made the report
};

// The rate the trays caught at the bout width, and EN 13739-2's check that it is 90–110 % of the rate
// set from the catch test (the page prints the rate; the check's PASS/FAIL is one of the caller's
// verdicts, stated first).
struct ReportRate {
  double tray_area_m2 = 0.0;
  double bout_width_m = 0.0;
  double rate_kg_ha = 0.0;                                          // caught in the trays
  double set_rate_kg_ha = std::numeric_limits<double>::quiet_NaN();  // NaN: no check
  double caught_percent = std::numeric_limits<double>::quiet_NaN();  // rate_kg_ha / set_rate_kg_ha, %
  double lowest_percent = 90.0, highest_percent = 110.0;
  bool pass = false;
};

// A verdict stated on a page's first lines: its word (PASS, MARGINAL, FAIL) in its colour, then what was
// judged and on what grounds. The numbers and the rule are the caller's (calibration/cv_verdict.hpp,
// tray_rate_check.hpp); the page only shows them first, so a farmer reads the outcome before the detail.
struct ReportVerdict {
  enum class Level { kPass, kMarginal, kFail, kNone };
  Level level = Level::kNone;
  std::string word;  // "PASS"
  std::string text;  // "CV at the 8.00 m bout, to-and-fro: 22.0 % ..., above the target 15 %"
};

struct PatternReport {
  ReportHeader header;
  std::vector<ReportVerdict> verdicts;  // drawn first, under the header
  std::vector<std::string> summary;    // lines under the header (trays, passes, mass, throw width)
  // The chart: one pass's trays, with the overlapped profile at chart.bout_width_m (> 0) and, when
  // chart.bout_cv is finite or computable, the mean line and the ±CV band.
  std::vector<double> tray_mass_kg;
  metrics::TrayLayout trays;
  TransverseOptions chart;             // its second_tray_mass_kg must outlive the write
  std::string chart_title;
  double cv_target = 0.15;             // fraction
  double working_width_to_and_fro_m = 0.0;
  double working_width_racetrack_m = 0.0;
  // The bands of bout widths within the target (lower, upper m), printed under the working widths: the
  // working width ends the widest, and a table row between two bands is above the target.
  std::vector<std::pair<double, double>> bands_to_and_fro_m, bands_racetrack_m;
  std::vector<CvTableRow> cv_table;      // the row at chart.bout_width_m is marked "(driven)"
  // How that row is marked: "driven" for the bout width given, "judged" for one the command chose.
  std::string bout_row_mark = "driven";
  std::optional<ReportRate> rate;
  std::vector<std::string> notes;      // warnings and remarks, printed in full at the bottom
};

// A page holding one table of text cells under a header (the setting chart).
struct TablePage {
  ReportHeader header;
  std::vector<ReportVerdict> verdicts;  // drawn first, under the header
  std::vector<std::string> summary;
  std::string caption;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;  // each the size of `columns`
  std::vector<std::string> notes;
};

// Writes the pages given (non-null), the pattern page first. Throws std::invalid_argument for data that
// cannot be drawn (as write_transverse_png; a table row of the wrong size) and std::runtime_error naming
// the path when the file cannot be written.
void write_report_pdf(const std::string& path, const PatternReport* pattern, const TablePage* table = nullptr);

}  // namespace spread::plot
