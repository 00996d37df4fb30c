#pragma once
// spread calibrate: what its four subcommands share (docs/field-calibration.md). The subcommands are one file
// each — cmd_calibrate_rate.cpp, cmd_calibrate_tray.cpp, cmd_calibrate_pattern.cpp, cmd_calibrate_synth.cpp —
// registered together in cmd_calibrate.cpp; the tray-test report's pieces, which tray and pattern both print,
// are calibrate_report.cpp's.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/analysis/calibration/calibrated_table.hpp"
#include "libspread/analysis/calibration/cv_verdict.hpp"
#include "libspread/analysis/calibration/disc_speed_check.hpp"
#include "libspread/analysis/calibration/field_ranges.hpp"
#include "libspread/analysis/calibration/fit_acceptance.hpp"
#include "libspread/analysis/calibration/pass_scatter.hpp"
#include "libspread/analysis/calibration/pattern_fit.hpp"
#include "libspread/analysis/calibration/quick_check.hpp"
#include "libspread/analysis/calibration/rate_calibration.hpp"
#include "libspread/analysis/calibration/rate_plausibility.hpp"
#include "libspread/analysis/calibration/synthetic_tray_test.hpp"
#include "libspread/analysis/calibration/tray_analysis.hpp"
#include "libspread/analysis/calibration/tray_csv.hpp"
#include "libspread/analysis/calibration/tray_cv_interval.hpp"
#include "libspread/analysis/calibration/tray_plausibility.hpp"
#include "libspread/analysis/plot/cv_text.hpp"
#include "libspread/analysis/plot/plot.hpp"
#include "libspread/analysis/plot/report_date.hpp"
#include "libspread/analysis/plot/report_pdf.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "tools/spread/chart_json.hpp"
#include "tools/spread/command_registry.hpp"
#include "tools/spread/error_exit.hpp"
#include "tools/spread/output_paths.hpp"
#include "tools/spread/report_args.hpp"
#include "tools/spread/setting_guidance.hpp"
#include "tools/spread/table_session.hpp"
#include "tools/spread/next_steps.hpp"
#include "tools/spread/verdicts.hpp"
#include "tools/spread/number_format.hpp"

namespace spread::cli::calibrate {

using nlohmann::json;
namespace cal = spread::calibration;

using spread::cli::BadInput;

constexpr double kDegPerRad = 180.0 / spread::kPi;

// JSON has no infinity: an empty bout's CV (+inf) is written as null.
inline json finite_or_null(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

// The report is printed, then the command fails: a refused fit, plots that could not be written.
class FailedAfterReport : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// ---------------------------------------------------------------------------------------------- rate

struct RateOptions {
  double mass_kg = NAN, time_s = NAN, gate = NAN;
  double mass2_kg = NAN, time2_s = NAN, gate2 = NAN;
  double target_rate_kg_ha = NAN, width_m = NAN, speed_km_h = NAN;
  double current_gate = NAN;
  bool json = false;
};

// ---------------------------------------------------------------------------------------------- tray

struct TrayOptions {
  std::string file;
  double width_m = 0.0;
  double cv_target_percent = 15.0;
  std::string plot_prefix;
  bool json = false;
  // For the report's header only: the tray test file does not say what was spread, how.
  std::string machine, material;
  double rpm = NAN;
  spread::cli::ReportArgs report;
  bool quick_check = false;
};

// ------------------------------------------------------------------------------------------- pattern

struct PatternOptions {
  std::string tables, material, trays, output, name, fit, plot_prefix;  // fit "": by the table's rows
  double rpm = 0.0;
  int samples = 1024;
  double kernel_m = 0.0;
  double cv_target_percent = 15.0;
  double width_m = 0.0;  // bout width of the report and the guidance; 0: none
  bool allow_analytic = false;
  bool json = false;
  spread::cli::ReportArgs report;
};

// --------------------------------------------------------------------------------------------- synth

struct SynthOptions {
  std::string tables, material, output;
  double rpm = 0.0;
  double friction = NAN, drag = 1.0, offset_deg = 0.0, speed_factor = 1.0, elevation_deg = 0.0;
  double half_width_m = 18.0, tray_width_m = 0.5;
  int passes = 3;
  double mass_g = 400.0;
  double relative_noise_percent = 8.0, granule_mass_g = 0.0, floor_g = 0.0, resolution_g = 0.001;
  int samples = 1024;
  std::uint64_t seed = 1;
  bool force = false;
  bool json = false;
};

// The subcommands (cmd_calibrate_<name>.cpp).
void run_rate(const RateOptions& o);
void run_tray(const TrayOptions& o);
void run_pattern(const PatternOptions& o);
void run_synth(const SynthOptions& o);

// ------------------------------------------------------------- the tray-test report (calibrate_report.cpp)

// What the report says about missing readings (empty when there are none).
std::vector<std::string> missing_notes(const cal::TrayTest& t);

json pass_scatter_json(const cal::PassScatter& p);

// "1 pass", "3 passes" (the page's words; the terminal's "pass(es)" is quoted by scripts).
std::string passes_text(std::size_t passes);

// The tray test's analysis as --json gives it (calibrate tray's output, calibrate pattern's
// "tray_test_analysis"): every number of its page.
json tray_json(const cal::TrayTest& t, const cal::TrayTestAnalysis& a);

// A CV as printed: NaN is a bout left with less than two trays' weight measured (cv_without_missing.hpp).
// Above the target it is never rounded onto it (plot/cv_text.hpp).
std::string cv_text(double cv, double target);

// --width beyond the trays: the CV would describe the ground no tray covered (tray_plausibility.hpp).
void require_width_within_trays(const cal::TrayTest& t, double width_m);

// The rate a tray test caught counts the trays read: a missing tray's share of the bout is not in it.
std::optional<std::string> missing_rate_note(const cal::TrayTest& t, const std::optional<spread::plot::ReportRate>& rate);

// The bout width of the report's chart and rate: --width (whole trays), else the largest whole-tray width
// within the to-and-fro working width (rounding up would show a bout beyond the target). 0: none.
double report_bout_width_m(const cal::TrayTest& t, const cal::TrayTestAnalysis& a);

// The CV at a whole-tray width, read off the analysis' curve (which leaves missing trays out).
double curve_cv(const cal::TrayTestAnalysis& a, const std::vector<double>& curve, double width_m);

// The table's widths fitting the pattern, and the bout driven among them.
std::vector<spread::plot::CvTableRow> tray_cv_table(const cal::TrayTestAnalysis& a, double bout_width_m);

// The to-and-fro CV at a whole-tray bout against the target, with the 95 % interval of the test's own
// repeatability (tray_cv_interval.hpp; none from one pass).
cal::CvVerdict bout_verdict(const cal::TrayTest& t, double bout_width_m, double cv_target);

// The verdicts of a tray test, computed once for the terminal, --json and the page: the CV at the bout
// (`bout_width_m` > 0), then the rate check.
std::vector<spread::cli::Verdict> tray_verdicts(const cal::TrayTest& t, const cal::TrayTestAnalysis& a,
                                                       double bout_width_m,
                                                       const std::optional<spread::plot::ReportRate>& rate);

// The report's pattern page of a tray test: its trays as the chart, the CVs of the analysis.
spread::plot::PatternReport tray_report_page(const cal::TrayTest& t, const cal::TrayTestAnalysis& a,
                                             double bout_width_m, std::int64_t time_s);

// Runs the plots; a failure is kept (the report is printed first) rather than thrown.
template <typename Plot>
std::string plot_or_error(Plot plot) {
  try {
    plot();
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

}  // namespace spread::cli::calibrate
