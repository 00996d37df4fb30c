// spread calibrate rate|tray|pattern — the technician's field tools (docs/field-calibration.md).
//   rate     catch test → flow factor → gate opening for a target rate; the rate error of the current opening
//   tray     tray-test CSV → CV (to-and-fro, racetrack) at a bout width, CV(W), effective working widths
//   synth    a synthetic tray test from the pattern model at known parameters, with seeded noise
//   pattern  fit friction, drag-diameter factor and launch-angle offset of a material to a tray test and
//            write the calibrated material into a NEW table file (the original is only read)
// Every command prints a short report, or JSON with --json. Bad input → a message naming it on stderr,
// exit code 2 (for a CSV: file and line). A run that cannot complete (a refused fit, a plot that cannot
// be written) → exit code 1, after the report.
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
#include "libspread/analysis/plot/plot.hpp"
#include "libspread/analysis/plot/report_date.hpp"
#include "libspread/analysis/plot/report_pdf.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "tools/spread/command_registry.hpp"
#include "tools/spread/error_exit.hpp"
#include "tools/spread/output_paths.hpp"
#include "tools/spread/report_args.hpp"
#include "tools/spread/setting_guidance.hpp"
#include "tools/spread/number_format.hpp"

namespace spread::cli::cmd_calibrate {
namespace {

using nlohmann::json;
namespace cal = spread::calibration;

using spread::cli::BadInput;

constexpr double kDegPerRad = 180.0 / spread::kPi;

// JSON has no infinity: an empty bout's CV (+inf) is written as null.
json finite_or_null(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

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

void run_rate(const RateOptions& o) {
  const cal::CatchTest first{o.mass_kg, o.time_s, o.gate};
  const int second_given = !std::isnan(o.mass2_kg) + !std::isnan(o.time2_s) + !std::isnan(o.gate2);
  if (second_given != 0 && second_given != 3) {
    throw BadInput("a second catch needs all of --mass2, --time2 and --gate2");
  }
  const bool two_point = second_given == 3;
  const std::optional<cal::CatchTest> second =
      two_point ? std::optional<cal::CatchTest>(cal::CatchTest{o.mass2_kg, o.time2_s, o.gate2}) : std::nullopt;
  const cal::MeteringModel model = two_point ? cal::metering_from_two_catches(first, *second) : cal::metering_from_catch(first);
  const double current = std::isnan(o.current_gate) ? o.gate : o.current_gate;
  const cal::RateSetting s = cal::rate_setting(model, o.target_rate_kg_ha, o.width_m, o.speed_km_h, current);
  const std::vector<std::string> warnings = cal::rate_warnings(first, second, s);
  if (o.json) {
    json out{{"model", two_point ? "two-point line" : "line through zero"},
             {"flow_factor_kg_s_per_unit", model.flow_factor_kg_s_per_unit},
             {"zero_opening", model.zero_opening},
             {"catch_mass_flow_kg_s", cal::catch_mass_flow_kg_s(first)},
             {"target_rate_kg_ha", o.target_rate_kg_ha},
             {"bout_width_m", o.width_m},
             {"speed_km_h", o.speed_km_h},
             {"required_mass_flow_kg_s", s.required_mass_flow_kg_s},
             {"required_gate_opening", s.required_gate_opening},
             {"current_gate_opening", s.current_gate_opening},
             {"current_mass_flow_kg_s", s.current_mass_flow_kg_s},
             {"current_rate_kg_ha", s.current_rate_kg_ha},
             {"rate_error_percent", 100.0 * s.rate_error},
             {"warnings", warnings}};
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::printf("metering: %s, flow factor %.6g kg/s per gate unit, zero at %.4g\n",
              two_point ? "two-point line" : "line through zero", model.flow_factor_kg_s_per_unit, model.zero_opening);
  std::printf("target %.1f kg/ha at %.2f m, %.2f km/h: mass flow %.4f kg/s → set the gate to %.2f\n",
              o.target_rate_kg_ha, o.width_m, o.speed_km_h, s.required_mass_flow_kg_s, s.required_gate_opening);
  std::printf("gate at %.2f spreads %.1f kg/ha: %+.1f %% against the target\n", s.current_gate_opening,
              s.current_rate_kg_ha, 100.0 * s.rate_error);
  for (const std::string& w : warnings) std::printf("warning: %s\n", w.c_str());
}

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

std::string positions_text(const std::vector<double>& positions_m) {
  std::string text;
  for (std::size_t i = 0; i < positions_m.size() && i < 8; ++i) {
    text += (i > 0 ? ", " : "") + format("%.2f", positions_m[i]);
  }
  if (positions_m.size() > 8) text += ", ...";
  return text + " m";
}

// What the report says about missing readings (empty when there are none).
std::vector<std::string> missing_notes(const cal::TrayTest& t) {
  const std::vector<double> missing = t.missing_positions_m(), partly = t.partly_missing_positions_m();
  std::vector<std::string> notes;
  if (!missing.empty()) {
    notes.push_back(std::to_string(missing.size()) + " tray(s) missing (NA or empty in every pass) at " +
                    positions_text(missing) + ": left out of the CVs and the fit, not counted as empty");
  }
  if (!partly.empty()) {
    notes.push_back(std::to_string(partly.size()) + " tray(s) missing in some passes at " +
                    positions_text(partly) + ": the mean of the passes read");
  }
  return notes;
}

json pass_scatter_json(const cal::PassScatter& p) {
  if (!p.available) return nullptr;
  return {{"passes", p.passes},
          {"trays", p.trays},
          {"rms_one_pass_g", p.rms_one_pass_g},
          {"rms_one_pass_fraction", p.rms_one_pass_fraction},
          {"rms_mean_fraction", p.rms_mean_fraction}};
}

json tray_json(const cal::TrayTest& t, const cal::TrayTestAnalysis& a) {
  json curve = json::array();
  for (std::size_t i = 0; i < a.widths_m.size(); ++i) {
    curve.push_back({{"bout_width_m", a.widths_m[i]},
                     {"cv_to_and_fro_percent", finite_or_null(100.0 * a.cv_to_and_fro_curve[i])},
                     {"cv_racetrack_percent", finite_or_null(100.0 * a.cv_racetrack_curve[i])}});
  }
  json out{{"tray_test", t.source},
           {"trays", t.mass_kg.size()},
           {"tray_width_m", t.tray_width_m},
           {"passes", t.mass_columns.size()},
           {"pass_columns", t.mass_columns},
           {"padded_trays", t.padded_trays},
           {"missing_trays_m", t.missing_positions_m()},
           {"partly_missing_trays_m", t.partly_missing_positions_m()},
           {"pass_scatter", pass_scatter_json(cal::pass_scatter(t))},
           {"total_mass_g", 1e3 * a.total_mass_kg},
           {"throw_width_m", a.throw_width_m},
           {"cv_target_percent", 100.0 * a.cv_target},
           {"working_width_to_and_fro_m", a.working_width_to_and_fro_m},
           {"working_width_racetrack_m", a.working_width_racetrack_m},
           {"bands_m", {{"to_and_fro", a.bands_to_and_fro_m}, {"racetrack", a.bands_racetrack_m}}},
           {"cv_curve", curve}};
  if (a.bout_width_m > 0.0) {
    out["bout_width_m"] = a.bout_width_m;
    out["bout_width_requested_m"] = a.requested_bout_width_m;
    out["cv_to_and_fro_percent"] = finite_or_null(100.0 * a.cv_to_and_fro);
    out["cv_racetrack_percent"] = finite_or_null(100.0 * a.cv_racetrack);
  }
  return out;
}

void plot_tray(const cal::TrayTest& t, const cal::TrayTestAnalysis& a, const std::string& prefix, double tray_area_m2,
               json& written) {
  spread::plot::TransverseOptions options;
  options.series_label = "measured";
  if (tray_area_m2 > 0.0) options.tray_area_m2 = tray_area_m2;
  options.bout_width_m = a.bout_width_m > 0.0 ? a.bout_width_m : a.working_width_to_and_fro_m;
  const std::string transverse = prefix + "_transverse.png";
  spread::plot::write_transverse_png(t.layout_mass_kg, t.layout, transverse, "tray test " + t.source, options);
  written["transverse"] = transverse;
  const std::string cv = prefix + "_cv.png";
  spread::plot::write_cv_curve_png(a.widths_m, a.cv_to_and_fro_curve, a.cv_racetrack_curve, a.cv_target, cv,
                                   "tray test " + t.source + ": CV(W)");
  written["cv"] = cv;
}

std::vector<std::string> tray_warnings(const cal::TrayTest& t, const cal::TrayTestAnalysis& a) {
  std::vector<std::string> warnings;
  if (a.bout_width_m > 0.0 && a.bout_width_rounded()) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "--width %.3g m is not a whole number of %.2f m trays: the CVs are at W = %.2f m, the nearest "
                  "width the tray test resolves",
                  a.requested_bout_width_m, t.tray_width_m, a.bout_width_m);
    warnings.emplace_back(text);
  }
  if (t.padded_trays > 0) {
    // The overlap needs the pattern on both sides of the centre line; what was not measured is taken
    // as empty, which is only true when the throw does not reach there.
    const int right = t.padded_trays - t.padded_left;
    std::string sides;
    if (t.padded_left > 0) sides = std::to_string(t.padded_left) + " on the left";
    if (right > 0) sides += (sides.empty() ? "" : ", ") + std::to_string(right) + " on the right";
    warnings.push_back("the trays do not cover both sides alike: " + std::to_string(t.padded_trays) +
                       " empty tray(s) were added (" + sides +
                       ") to centre the layout on the tractor; if the spread reaches there, the CVs and working "
                       "widths are wrong — lay trays across the whole throw on both sides");
  }
  return warnings;
}

// A CV as printed: NaN is a bout left with less than two trays' weight measured (cv_without_missing.hpp).
std::string cv_text(double cv) {
  return std::isnan(cv) ? std::string("none (missing trays leave under two trays of the bout measured)")
                        : format("%.1f %%", 100.0 * cv);
}

// --width beyond the trays: the CV would describe the ground no tray covered (tray_plausibility.hpp).
void require_width_within_trays(const cal::TrayTest& t, double width_m) {
  if (width_m <= 0.0) return;
  const std::string problem = cal::bout_width_problem(t.layout, width_m);
  if (!problem.empty()) throw BadInput("--width " + problem);
}

// The rate a tray test caught counts the trays read: a missing tray's share of the bout is not in it.
std::optional<std::string> missing_rate_note(const cal::TrayTest& t, const std::optional<spread::plot::ReportRate>& rate) {
  if (!rate || !t.has_missing_trays()) return std::nullopt;
  return std::string("the caught rate counts the trays read only: missing trays lower it");
}

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

// The bout width of the report's chart and rate: --width (whole trays), else the largest whole-tray width
// within the to-and-fro working width (rounding up would show a bout beyond the target). 0: none.
double report_bout_width_m(const cal::TrayTest& t, const cal::TrayTestAnalysis& a) {
  if (a.bout_width_m > 0.0) return a.bout_width_m;
  const int trays = static_cast<int>(std::floor(a.working_width_to_and_fro_m / t.layout.tray_width_m + 1e-9));
  return trays >= 2 ? trays * t.layout.tray_width_m : 0.0;
}

// The CV at a whole-tray width, read off the analysis' curve (which leaves missing trays out).
double curve_cv(const cal::TrayTestAnalysis& a, const std::vector<double>& curve, double width_m) {
  for (std::size_t i = 0; i < a.widths_m.size(); ++i) {
    if (std::abs(a.widths_m[i] - width_m) < 1e-6) return curve[i];
  }
  return NAN;
}

// The table's widths fitting the pattern, and the bout driven among them.
std::vector<spread::plot::CvTableRow> tray_cv_table(const cal::TrayTestAnalysis& a, double bout_width_m) {
  const std::vector<double> widths = spread::plot::with_bout_width_m(
      spread::plot::cv_table_widths_m(a.throw_width_m, a.widths_m), bout_width_m, a.widths_m);
  return spread::plot::cv_table(widths, a.widths_m, a.cv_to_and_fro_curve, a.cv_racetrack_curve);
}

// The to-and-fro CV at a whole-tray bout against the target, with the 95 % interval of the test's own
// repeatability (tray_cv_interval.hpp; none from one pass).
cal::CvVerdict bout_verdict(const cal::TrayTest& t, double bout_width_m, double cv_target) {
  const int n = spread::metrics::bout_tray_count(t.layout, bout_width_m);
  const cal::TrayCvInterval interval = cal::tray_cv_interval(t, n, spread::metrics::Overlap::kToAndFro);
  return interval.available ? cal::cv_verdict(interval.cv, interval.low, interval.high, cv_target)
                            : cal::cv_verdict(interval.cv, NAN, NAN, cv_target);
}

// The verdicts a tray test's page opens with: the CV at the bout, then the rate check.
std::vector<spread::plot::ReportVerdict> tray_verdicts(const cal::TrayTest& t, const cal::TrayTestAnalysis& a,
                                                       double bout_width_m,
                                                       const std::optional<spread::plot::ReportRate>& rate) {
  std::vector<spread::plot::ReportVerdict> verdicts;
  if (bout_width_m > 0.0) {
    const std::string what = a.bout_width_m > 0.0
                                 ? "CV at the " + format("%.2f m", bout_width_m) + " bout, to-and-fro"
                                 : "CV at " + format("%.2f m", bout_width_m) + " (no bout width given: the working "
                                   "width in whole trays), to-and-fro";
    verdicts.push_back(spread::cli::cv_report_verdict(what, bout_verdict(t, bout_width_m, a.cv_target)));
    if (t.mass_columns.size() < 2) verdicts.back().text += "; one pass shows no repeatability: drive two or more";
  }
  if (const auto rate_verdict = spread::cli::rate_report_verdict(rate)) verdicts.push_back(*rate_verdict);
  return verdicts;
}

// The report's pattern page of a tray test: its trays as the chart, the CVs of the analysis.
spread::plot::PatternReport tray_report_page(const cal::TrayTest& t, const cal::TrayTestAnalysis& a,
                                             double bout_width_m, std::int64_t time_s) {
  spread::plot::PatternReport r;
  r.header.source = t.source;
  r.header.time_s = time_s;
  r.header.made_by = spread::cli::command_line();
  char text[256];
  std::snprintf(text, sizeof text, "%zu trays of %.2f m, %zu pass(es), %.1f g in the trays (mean of the passes), "
                "throw width %.1f m", t.mass_kg.size(), t.tray_width_m, t.mass_columns.size(), 1e3 * a.total_mass_kg,
                a.throw_width_m);
  r.summary.emplace_back(text);
  r.tray_mass_kg = t.layout_mass_kg;
  r.trays = t.layout;
  r.chart.missing_trays = t.layout_missing;
  r.chart.series_label = t.mass_columns.size() > 1 ? "measured, mean of the passes" : "measured";
  r.chart.bout_width_m = bout_width_m;
  if (bout_width_m > 0.0) {
    r.chart.bout_cv = curve_cv(a, a.cv_to_and_fro_curve, bout_width_m);
    std::snprintf(text, sizeof text, "at W = %.2f m: CV %s to-and-fro, %s racetrack%s", bout_width_m,
                  cv_text(r.chart.bout_cv).c_str(), cv_text(curve_cv(a, a.cv_racetrack_curve, bout_width_m)).c_str(),
                  a.bout_width_m > 0.0 ? "" : " (no --width: the working width, in whole trays)");
    r.summary.emplace_back(text);
  }
  r.chart_title = "tray test: one pass across the driving direction";
  r.cv_target = a.cv_target;
  r.working_width_to_and_fro_m = a.working_width_to_and_fro_m;
  r.working_width_racetrack_m = a.working_width_racetrack_m;
  r.cv_table = tray_cv_table(a, bout_width_m);
  return r;
}

// --quick-check: 4–8 trays across one bout of the field as driven; the CV of the trays themselves and how
// uncertain it is from so few trays.
void run_quick_check(const TrayOptions& o, double cv_target) {
  const char* not_with = !o.plot_prefix.empty() ? "--plot" : o.width_m > 0.0 ? "--width" : nullptr;
  if (not_with != nullptr) {
    throw BadInput(std::string(not_with) + " does not go with --quick-check: the quick check's trays already hold the "
                   "overlapped spread of the bout as driven; for a chart or the CV at other widths lay a "
                   "full tray test across the throw (without --quick-check)");
  }
  const std::string report_problem = spread::cli::check_report_args(o.report);
  const std::int64_t report_time_s = o.report.path.empty() ? 0 : spread::cli::report_time_s();
  const cal::TrayTest t = cal::read_tray_csv(o.file, cal::quick_check_csv_options());
  const cal::QuickCheck q = cal::quick_check(t, cv_target);
  // The trays caught the overlapped spread itself: each stands for mean / A. As a bout of n trays of the
  // spacing w holding n · mean (tray_rate_check.hpp: M · w / (W · A) with W = n · w) this is the same rate.
  const std::optional<spread::plot::ReportRate> rate =
      spread::cli::report_rate(o.report, q.mean_kg * q.trays, q.trays * t.tray_width_m, t.tray_width_m);
  const std::vector<std::string> notes = missing_notes(t);
  const std::string high = std::isfinite(q.interval.high) ? format("%.1f %%", 100.0 * q.interval.high) : "unbounded";
  std::string verdict;
  switch (q.verdict) {
    case cal::QuickCheckVerdict::kMeetsTarget:
      verdict = "meets the target: even the top of the interval is within " + format("%g %%", 100.0 * cv_target);
      break;
    case cal::QuickCheckVerdict::kFailsTarget:
      verdict = "fails the target: even the bottom of the interval is above " + format("%g %%", 100.0 * cv_target);
      break;
    case cal::QuickCheckVerdict::kUndecided:
      verdict = "undecided: the target " + format("%g %%", 100.0 * cv_target) + " lies inside the interval, " +
                std::to_string(q.trays) + " trays cannot tell whether the spread meets it; lay a full tray test "
                "across the throw to know";
      break;
  }
  std::string report_error;
  if (!o.report.path.empty() && report_problem.empty()) {
    report_error = plot_or_error([&] {
      spread::plot::TablePage page;
      page.header.title = "Quick check of a spread in the field";
      page.header.source = t.source;
      page.header.machine = o.machine;
      page.header.material = o.material;
      page.header.rpm = o.rpm > 0.0 ? o.rpm : std::numeric_limits<double>::quiet_NaN();
      page.header.speed_km_h = o.report.speed_km_h;
      page.header.time_s = report_time_s;
      page.header.made_by = spread::cli::command_line();
      char text[160];
      std::snprintf(text, sizeof text, "%d trays read, %.2f m apart, %zu pass(es), mean %.2f g per tray", q.trays,
                    t.tray_width_m, t.mass_columns.size(), 1e3 * q.mean_kg);
      page.summary.emplace_back(text);
      page.summary.push_back(format("CV %.1f %%", 100.0 * q.cv) + "; the bout's CV lies between " +
                             format("%.1f %%", 100.0 * q.interval.low) + " and " + high + " (95 % interval, McKay)");
      page.summary.push_back("against the target: " + verdict);
      // First on the page: the quick check's meets / undecided / fails as the verdict every report states
      // (cv_verdict.hpp: the same rule on McKay's interval).
      page.verdicts.push_back(spread::cli::cv_report_verdict(
          "CV of the bout from " + std::to_string(q.trays) + " trays",
          cal::cv_verdict(q.cv, q.interval.low, q.interval.high, cv_target)));
      if (const auto rate_verdict = spread::cli::rate_report_verdict(rate)) page.verdicts.push_back(*rate_verdict);
      for (const std::string& line : spread::cli::rate_lines(rate)) page.summary.push_back(line);
      page.caption = "Trays (mean of the passes)";
      page.columns = {"tray", "position", "mass"};
      for (std::size_t i = 0; i < t.position_m.size(); ++i) {
        page.rows.push_back({std::to_string(i + 1), format("%.2f m", t.position_m[i]),
                             t.missing[i] ? std::string("missing") : format("%.2f g", 1e3 * t.mass_kg[i])});
      }
      for (const std::string& n : notes) page.notes.push_back("missing: " + n);
      page.notes.push_back("a CV from a few trays is itself uncertain: the 95 % interval says how much; MARGINAL "
                           "means these trays cannot tell, a full tray test across the throw can");
      spread::plot::write_report_pdf(o.report.path, nullptr, &page);
    });
  }
  if (o.json) {
    json out{{"tray_test", t.source},
             {"quick_check", true},
             {"trays", q.trays},
             {"tray_spacing_m", t.tray_width_m},
             {"passes", t.mass_columns.size()},
             {"missing_trays_m", t.missing_positions_m()},
             {"mean_g", 1e3 * q.mean_kg},
             {"sd_g", 1e3 * q.sd_kg},
             {"cv_percent", 100.0 * q.cv},
             {"cv_interval_percent", {100.0 * q.interval.low, finite_or_null(100.0 * q.interval.high)}},
             {"confidence_percent", 100.0 * q.interval.confidence},
             {"cv_target_percent", 100.0 * cv_target},
             {"verdict", cal::to_string(q.verdict)},
             {"rate", spread::cli::rate_json(rate)},
             {"notes", notes}};
    spread::cli::add_report_outcome(out, o.report, report_problem, report_error);
    std::cout << out.dump(2) << "\n";
    spread::cli::throw_report_outcome(report_problem, report_error);
    return;
  }
  std::printf("%s: quick check, %d trays read (%.2f m apart), %zu pass(es), mean %.2f g per tray\n", t.source.c_str(),
              q.trays, t.tray_width_m, t.mass_columns.size(), 1e3 * q.mean_kg);
  std::printf("CV %.1f %% over the %d trays; from %d trays the bout's CV lies between %.1f %% and %s (%.0f %% "
              "interval, McKay)\n",
              100.0 * q.cv, q.trays, q.trays, 100.0 * q.interval.low, high.c_str(), 100.0 * q.interval.confidence);
  std::printf("against the target: %s\n", verdict.c_str());
  for (const std::string& n : notes) std::printf("missing: %s\n", n.c_str());
  for (const std::string& line : spread::cli::rate_lines(rate)) std::printf("%s\n", line.c_str());
  if (!o.report.path.empty() && report_problem.empty() && report_error.empty()) {
    std::printf("wrote %s\n", o.report.path.c_str());
  }
  spread::cli::throw_report_outcome(report_problem, report_error);
}

void run_tray(const TrayOptions& o) {
  const double cv_target = cal::cv_target_from_percent(o.cv_target_percent, "--cv-target");
  if (o.quick_check) {
    run_quick_check(o, cv_target);
    return;
  }
  if (!o.plot_prefix.empty()) spread::cli::require_output_folder("--plot", o.plot_prefix);
  const std::string report_problem = spread::cli::check_report_args(o.report);
  const std::int64_t time_s = o.report.path.empty() ? 0 : spread::cli::report_time_s();
  const cal::TrayTest t = cal::read_tray_csv(o.file);
  require_width_within_trays(t, o.width_m);
  const cal::TrayTestAnalysis a = cal::analyse_tray_test(t, cv_target, o.width_m);
  const std::vector<std::string> warnings = tray_warnings(t, a);
  std::vector<std::string> notes = missing_notes(t);
  const cal::PassScatter scatter = cal::pass_scatter(t);
  const double report_width_m = report_bout_width_m(t, a);
  const std::optional<spread::plot::ReportRate> rate =
      spread::cli::report_rate(o.report, a.total_mass_kg, report_width_m, t.layout.tray_width_m);
  const std::optional<std::string> rate_note = missing_rate_note(t, rate);
  json written = json::object();
  const std::string plot_error =
      o.plot_prefix.empty() ? std::string() : plot_or_error([&] { plot_tray(t, a, o.plot_prefix, o.report.tray_area_m2, written); });
  std::string report_error;
  if (!o.report.path.empty() && report_problem.empty()) {
    report_error = plot_or_error([&] {
      spread::plot::PatternReport page = tray_report_page(t, a, report_width_m, time_s);
      if (o.report.tray_area_m2 > 0.0) page.chart.tray_area_m2 = o.report.tray_area_m2;
      page.header.machine = o.machine;
      page.header.material = o.material;
      page.header.rpm = o.rpm;
      page.header.speed_km_h = o.report.speed_km_h;
      page.verdicts = tray_verdicts(t, a, report_width_m, rate);
      page.rate = rate;
      page.notes = warnings;
      for (const std::string& n : notes) page.notes.push_back("missing: " + n);
      if (rate_note) page.notes.push_back(*rate_note);
      spread::plot::write_report_pdf(o.report.path, &page);
      written["report"] = o.report.path;
    });
  }
  auto fail_after_report = [&] {
    spread::cli::throw_report_outcome(report_problem, report_error);
    if (!plot_error.empty()) throw FailedAfterReport("--plot: " + plot_error);
  };
  if (o.json) {
    json out = tray_json(t, a);
    if (a.bout_width_m > 0.0) out["cv_verdict"] = spread::cli::cv_verdict_json(bout_verdict(t, a.bout_width_m, a.cv_target));
    out["warnings"] = warnings;
    out["notes"] = notes;
    if (rate_note) out["notes"].push_back(*rate_note);
    out["written"] = written;
    out["rate"] = spread::cli::rate_json(rate);
    if (!plot_error.empty()) out["plot_error"] = plot_error;
    if (!report_problem.empty() || !report_error.empty()) {
      out["report_error"] = report_problem.empty() ? report_error : report_problem;
    }
    std::cout << out.dump(2) << "\n";
    fail_after_report();
    return;
  }
  std::printf("%s: %zu trays of %.2f m, %zu pass(es), %.1f g in total, throw width %.1f m\n", t.source.c_str(),
              t.mass_kg.size(), t.tray_width_m, t.mass_columns.size(), 1e3 * a.total_mass_kg, a.throw_width_m);
  if (a.bout_width_m > 0.0) {
    std::printf("at W = %.2f m: CV %s to-and-fro, %s racetrack\n", a.bout_width_m, cv_text(a.cv_to_and_fro).c_str(),
                cv_text(a.cv_racetrack).c_str());
  }
  for (const std::string& w : warnings) std::printf("warning: %s\n", w.c_str());
  for (const std::string& n : notes) std::printf("missing: %s\n", n.c_str());
  std::printf("effective working width (CV <= %.3g %%): %.2f m to-and-fro, %.2f m racetrack\n", 100.0 * a.cv_target,
              a.working_width_to_and_fro_m, a.working_width_racetrack_m);
  if (a.bands_to_and_fro_m.size() > 1 || a.bands_racetrack_m.size() > 1) {
    const auto list = [](const std::vector<std::pair<double, double>>& bands) {
      std::string text;
      for (const auto& [lower, upper] : bands) {
        char band[48];
        std::snprintf(band, sizeof band, "%s%.2f-%.2f m", text.empty() ? "" : ", ", lower, upper);
        text += band;
      }
      return text;
    };
    std::printf("bands within the target: to-and-fro %s; racetrack %s (the working width ends the widest)\n",
                list(a.bands_to_and_fro_m).c_str(), list(a.bands_racetrack_m).c_str());
  }
  if (scatter.available) {
    std::printf("pass-to-pass scatter: rms %.2f g per tray between the %d passes (%.3f %% of a pass per tray; "
                "%.3f %% for their mean)\n",
                scatter.rms_one_pass_g, scatter.passes, 100.0 * scatter.rms_one_pass_fraction,
                100.0 * scatter.rms_mean_fraction);
  }
  for (const std::string& line : spread::cli::rate_lines(rate)) std::printf("%s\n", line.c_str());
  if (rate_note) std::printf("note: %s\n", rate_note->c_str());
  if (!std::isnan(o.report.tray_area_m2) && !rate) {
    std::printf("note: no rate: --tray-area needs a bout width (--width, or a working width of two trays or more)\n");
  }
  for (const auto& [kind, path] : written.items()) std::printf("wrote %s\n", path.get<std::string>().c_str());
  fail_after_report();
}

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

// The parameters of a fit as --fit names them, in PatternParameterIndex order.
constexpr std::array<const char*, cal::kPatternParameterCount> kFitNames{"friction", "drag", "offset", "speed",
                                                                        "elevation"};

// "" = the default of the table's rows: friction, drag and offset for analytic rows; the launch speed
// factor and offset for DEM rows, whose launches have no friction to refit.
void parse_fit_list(const std::string& text, bool table_samples, cal::PatternFitOptions& options) {
  const std::string list = !text.empty() ? text : table_samples ? "speed,offset" : "friction,drag,offset";
  std::array<bool, cal::kPatternParameterCount> mask{};
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto* found = std::find(kFitNames.begin(), kFitNames.end(), item);
    if (found == kFitNames.end()) {
      throw BadInput("--fit: unknown parameter '" + item + "' (known: friction, drag, offset, speed, elevation)");
    }
    mask[static_cast<std::size_t>(found - kFitNames.begin())] = true;
  }
  if (std::none_of(mask.begin(), mask.end(), [](bool b) { return b; })) {
    throw BadInput("--fit: name at least one of friction, drag, offset, speed, elevation");
  }
  if (table_samples && mask[cal::kFriction]) {
    throw BadInput("--fit friction: the table's rows of this material came from the DEM, whose launches do not "
                   "depend on a friction the fit could change; fit their launch correction (--fit speed,offset, "
                   "with drag or elevation if needed), or --allow-analytic to fit the analytic model instead");
  }
  options.fit_friction = mask[cal::kFriction];
  options.fit_drag_diameter = mask[cal::kDragDiameter];
  options.fit_angle_offset = mask[cal::kAngleOffset];
  options.fit_launch_speed = mask[cal::kLaunchSpeed];
  options.fit_elevation_offset = mask[cal::kElevationOffset];
}

json fit_json_parameters(const cal::PatternFitResult& f) {
  static const char* names[cal::kPatternParameterCount] = {"friction_wall", "drag_diameter_factor",
                                                           "launch_angle_offset_deg", "launch_speed_factor",
                                                           "launch_elevation_offset_deg"};
  // Angles in degrees.
  const std::array<double, cal::kPatternParameterCount> unit{1.0, 1.0, kDegPerRad, 1.0, kDegPerRad};
  const auto values = cal::as_array(f.fitted), errors = cal::as_array(f.standard_error),
             initial = cal::as_array(f.initial), robust = cal::as_array(f.robust_standard_error);
  json parameters = json::object();
  for (std::size_t i = 0; i < cal::kPatternParameterCount; ++i) {
    parameters[names[i]] = {{"value", values[i] * unit[i]},
                            {"standard_error", f.fitted_mask[i] ? finite_or_null(errors[i] * unit[i]) : json(nullptr)},
                            {"robust_standard_error", f.fitted_mask[i] ? finite_or_null(robust[i] * unit[i]) : json(nullptr)},
                            {"initial", initial[i] * unit[i]},
                            {"fitted", f.fitted_mask[i]}};
  }
  json correlation = json::array();
  for (const auto& row : f.correlation) correlation.push_back(row);
  return {{"parameters", parameters},
          {"launch_model", f.table_samples ? "table_samples" : "analytic"},
          {"correlation", correlation},
          {"residual_rms_fraction", f.residual_rms_fraction},
          {"residual_rms_g", 1e3 * f.residual_rms_kg},
          {"initial_residual_rms_fraction", f.initial_residual_rms_fraction},
          {"iterations", f.iterations},
          {"model_evaluations", f.model_evaluations},
          {"converged", f.converged},
          {"stop_reason", f.stop_reason}};
}

json fit_json(const cal::PatternFitResult& f) {
  json fit = fit_json_parameters(f);
  fit["weighted"] = f.weighted;
  fit["variance_model"] = {{"floor_sd_fraction", std::sqrt(f.variance_model.floor_variance)},
                           {"counting_fraction", f.variance_model.counting},
                           {"relative_sd", std::sqrt(f.variance_model.relative)}};
  fit["reduced_chi_square"] = f.reduced_chi_square;
  fit["informative_trays"] = f.informative_trays;
  return fit;
}

// The report's line of fitted values: each fitted one with its standard error, the others marked fixed
// (a value the fit did not move is the table's, not a measurement).
std::string fitted_values_line(const cal::PatternFitResult& f) {
  const auto values = cal::as_array(f.fitted), errors = cal::as_array(f.standard_error);
  struct Shown {
    std::size_t index;
    const char* name;
    double unit;
    const char* pattern;  // of the value and its error
    const char* suffix;
  };
  std::vector<Shown> shown;
  if (!f.table_samples) shown.push_back({cal::kFriction, "friction on vanes", 1.0, "%.4f", ""});
  shown.push_back({cal::kDragDiameter, "drag diameter factor", 1.0, "%.4f", ""});
  shown.push_back({cal::kAngleOffset, "launch-angle offset", kDegPerRad, "%.2f", " deg"});
  if (f.table_samples || f.fitted_mask[cal::kLaunchSpeed] || f.fitted_mask[cal::kElevationOffset]) {
    shown.push_back({cal::kLaunchSpeed, "launch speed factor", 1.0, "%.4f", ""});
    shown.push_back({cal::kElevationOffset, "launch elevation offset", kDegPerRad, "%.2f", " deg"});
  }
  std::string fitted, fixed;
  for (const Shown& p : shown) {
    const std::string value = format(p.pattern, values[p.index] * p.unit);
    if (f.fitted_mask[p.index]) {
      fitted += (fitted.empty() ? "" : ", ") + std::string(p.name) + " " + value + " ± " +
                format(p.pattern, errors[p.index] * p.unit) + p.suffix;
    } else {
      fixed += (fixed.empty() ? "" : ", ") + std::string(p.name) + " " + value + p.suffix;
    }
  }
  return std::string(f.table_samples ? "fitted to the table's DEM launches: " : "fitted: ") + fitted +
         " (± one standard error)" + (fixed.empty() ? "" : "; fixed at the table's values: " + fixed) +
         "; residual rms " + format("%.2f g per tray", 1e3 * f.residual_rms_kg);
}

std::vector<std::string> fit_warnings(const cal::PatternFitResult& f) {
  const auto& names = kFitNames;
  std::vector<std::string> warnings;
  for (std::size_t i = 0; i < cal::kPatternParameterCount; ++i) {
    for (std::size_t j = i + 1; j < cal::kPatternParameterCount; ++j) {
      if (f.fitted_mask[i] && f.fitted_mask[j] && std::abs(f.correlation[i][j]) > 0.95) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "%s and %s are correlated (r = %.3f): this tray test cannot tell them apart; their standard "
                      "errors are large — fix one (e.g. --fit friction,drag, or on a DEM table --fit speed,offset) for a "
                      "usable value of the other",
                      names[i], names[j], f.correlation[i][j]);
        warnings.emplace_back(text);
      }
    }
  }
  return warnings;
}

void plot_pattern(const PatternOptions& o, const cal::TrayTest& test, const cal::PatternFitResult& fit,
                  const std::string& material_name, double cv_target, json& written) {
  // Both series in grams of the tray test: the fitted fractions scaled to the measured total.
  std::vector<double> predicted_kg(fit.fitted_fraction.size());
  const double total_kg = test.total_mass_kg();
  for (std::size_t i = 0; i < predicted_kg.size(); ++i) predicted_kg[i] = fit.fitted_fraction[i] * total_kg;
  spread::plot::TransverseOptions plot_options;
  plot_options.series_label = "predicted (calibrated)";
  plot_options.second_tray_mass_kg = test.layout_mass_kg;
  plot_options.second_label = "measured";
  const std::string transverse = o.plot_prefix + "_transverse.png";
  spread::plot::write_transverse_png(predicted_kg, test.layout, transverse,
                                     material_name + " at " + std::to_string(static_cast<int>(o.rpm)) +
                                         " rpm: measured vs predicted",
                                     plot_options);
  written["transverse"] = transverse;
  const cal::TrayTestAnalysis measured = cal::analyse_tray_test(test, cv_target, 0.0);
  std::vector<double> tf(measured.widths_m.size()), rt(measured.widths_m.size());
  spread::metrics::cv_curve(predicted_kg, test.layout, measured.widths_m, spread::metrics::Overlap::kToAndFro, tf);
  spread::metrics::cv_curve(predicted_kg, test.layout, measured.widths_m, spread::metrics::Overlap::kRacetrack, rt);
  const std::string cv = o.plot_prefix + "_cv.png";
  spread::plot::CvCurveOptions cv_options;
  cv_options.series_label = "calibrated";
  cv_options.second_to_and_fro = measured.cv_to_and_fro_curve;
  cv_options.second_label = "tray test";
  spread::plot::write_cv_curve_png(measured.widths_m, tf, rt, measured.cv_target, cv,
                                   material_name + ": CV(W) calibrated and measured", cv_options);
  written["cv"] = cv;
  const std::string cv_measured = o.plot_prefix + "_cv_measured.png";
  spread::plot::write_cv_curve_png(measured.widths_m, measured.cv_to_and_fro_curve, measured.cv_racetrack_curve,
                                   measured.cv_target, cv_measured, "tray test: CV(W) measured");
  written["cv_measured"] = cv_measured;
}

void run_pattern(const PatternOptions& o) {
  if (o.output.empty()) throw BadInput("--output: give the path of the new table file");
  if (o.samples < 16 || o.samples > 100000) throw BadInput("--samples must be in [16, 100000]");
  if (!(o.kernel_m >= 0.0)) throw BadInput("--kernel must be >= 0 m");
  if (!(o.width_m >= 0.0) || !std::isfinite(o.width_m)) throw BadInput("--width must be a bout width >= 0 m");
  const double cv_target = cal::cv_target_from_percent(o.cv_target_percent, "--cv-target");
  // Before the fit (which takes seconds): the folders the results go to.
  spread::cli::require_output_folder("--output", o.output);
  if (std::filesystem::exists(o.output)) {
    throw BadInput("--output " + o.output + ": the file exists; the calibrated table is always a new file — choose "
                   "another name");
  }
  if (!o.plot_prefix.empty()) spread::cli::require_output_folder("--plot", o.plot_prefix);
  const std::string report_problem = spread::cli::check_report_args(o.report);
  const std::int64_t report_time_s = o.report.path.empty() ? 0 : spread::cli::report_time_s();
  // Before the fit: the name's date is SOURCE_DATE_EPOCH's when set (a malformed one is refused here).
  const std::string material_name =
      o.name.empty() ? cal::calibrated_material_name(o.material, spread::plot::utc_date(spread::cli::report_time_s()))
                     : o.name;
  const cal::TrayTest test = cal::read_tray_csv(o.trays);
  require_width_within_trays(test, o.width_m);
  const spread::tables::TableContents contents = spread::tables::read_table_file(o.tables);
  const std::vector<double> dem_rpm = cal::non_analytic_rows(contents, o.material);
  const cal::PatternSetup setup = cal::pattern_setup_from_table(contents, o.material, o.rpm, o.allow_analytic);
  cal::PatternFitOptions options;
  parse_fit_list(o.fit, !setup.table_samples.empty(), options);
  options.model.sample_count = o.samples;
  options.model.kernel_sigma_m = o.kernel_m;
  const cal::PatternFitResult fit = cal::fit_pattern(setup, test, options);
  const cal::PassScatter scatter = cal::pass_scatter(test);
  const cal::FitAcceptance acceptance = cal::assess_fit(fit, scatter);
  std::vector<std::string> warnings = fit_warnings(fit);
  warnings.insert(warnings.end(), acceptance.warnings.begin(), acceptance.warnings.end());
  for (const std::string& w : cal::disc_speed_warnings(fit, o.rpm)) warnings.push_back(w);
  if (!dem_rpm.empty() && o.allow_analytic) {
    warnings.push_back("the table's rows of '" + o.material + "' came from the DEM; the fit used the analytic "
                       "launch model and the calibrated material's rows are analytic (--allow-analytic)");
  }
  const std::vector<std::string> notes = missing_notes(test);

  json report = fit_json(fit);
  report["tray_test"] = o.trays;
  report["rpm"] = o.rpm;
  report["material"] = o.material;
  report["sample_count"] = o.samples;
  if (!setup.table_samples.empty()) {
    report["table_row_rpm"] = setup.table_row_rpm;
    report["table_row_samples"] = setup.table_samples.size();
  }
  report["kernel_sigma_m"] = o.kernel_m > 0.0 ? o.kernel_m : 0.5 * test.tray_width_m;
  report["pass_scatter"] = pass_scatter_json(scatter);
  report["residual_to_scatter"] = scatter.available ? json(acceptance.residual_to_scatter) : json(nullptr);
  report["missing_trays_m"] = test.missing_positions_m();
  report["partly_missing_trays_m"] = test.partly_missing_positions_m();
  report["accepted"] = acceptance.accepted();
  report["refusals"] = acceptance.refusals;

  std::optional<cal::CalibratedTableSummary> summary;
  json written = json::object();
  std::string plot_error;
  // A refused fit writes nothing: neither the table nor plots that would look like a calibration.
  if (acceptance.accepted()) {
    cal::CalibratedTableRequest request;
    request.original_path = o.tables;
    request.output_path = o.output;
    request.material = o.material;
    request.new_material_name = material_name;
    request.parameters = fit.fitted;
    request.calibration_json = report.dump();
    request.allow_analytic_for_dem = o.allow_analytic;
    summary = cal::write_calibrated_table(request);
    if (!o.plot_prefix.empty()) {
      plot_error = plot_or_error([&] { plot_pattern(o, test, fit, material_name, cv_target, written); });
    }
  }
  // The report, as the plots, only for an accepted fit: the measured trays with the calibrated
  // prediction beside them, the CVs and rate of the tray test.
  const cal::TrayTestAnalysis measured = cal::analyse_tray_test(test, cv_target, o.width_m);
  const double report_width_m = report_bout_width_m(test, measured);
  // What to change when the calibrated material's CV at --width is above the target: predicted from the
  // new table (setting_guidance.hpp).
  spread::cli::SettingGuidance guidance;
  if (summary && o.width_m > 0.0) {
    spread::predict::PredictionRequest request;
    request.material = material_name;
    request.rpm = o.rpm;
    request.cv_target = cv_target;
    request.bout_width_m = o.width_m;
    request.tray_width_m = test.tray_width_m;
    guidance = spread::cli::setting_guidance(summary->output_path, request);
  }
  const std::optional<spread::plot::ReportRate> rate =
      spread::cli::report_rate(o.report, measured.total_mass_kg, report_width_m, test.layout.tray_width_m);
  const std::optional<std::string> rate_note = missing_rate_note(test, rate);
  std::string report_error;
  if (acceptance.accepted() && !o.report.path.empty() && report_problem.empty()) {
    report_error = plot_or_error([&] {
      spread::plot::PatternReport page = tray_report_page(test, measured, report_width_m, report_time_s);
      if (o.report.tray_area_m2 > 0.0) page.chart.tray_area_m2 = o.report.tray_area_m2;
      std::vector<double> predicted_kg(fit.fitted_fraction.size());
      for (std::size_t i = 0; i < predicted_kg.size(); ++i) predicted_kg[i] = fit.fitted_fraction[i] * test.total_mass_kg();
      page.header.title = "Spread pattern report: calibration";
      page.header.machine = contents.machine.name;
      page.header.material = material_name;
      page.header.rpm = o.rpm;
      page.header.speed_km_h = o.report.speed_km_h;
      page.chart.second_tray_mass_kg = predicted_kg;
      page.chart.second_label = "predicted, calibrated";
      page.summary.push_back(fitted_values_line(fit));
      page.verdicts = tray_verdicts(test, measured, report_width_m, rate);
      page.rate = rate;
      page.notes = warnings;
      for (const std::string& n : notes) page.notes.push_back("missing: " + n);
      if (rate_note) page.notes.push_back(*rate_note);
      for (const std::string& line : guidance.lines) page.notes.push_back(line);
      spread::plot::write_report_pdf(o.report.path, &page);
      written["report"] = o.report.path;
    });
  }

  if (o.json) {
    report["warnings"] = warnings;
    report["notes"] = notes;
    if (rate_note) report["notes"].push_back(*rate_note);
    if (summary) {
      report["output"] = {{"path", summary->output_path},
                          {"material", summary->material},
                          {"rpm_rows", summary->rpm_rows},
                          {"samples_per_run", summary->samples_per_run}};
    } else {
      report["output"] = nullptr;
    }
    report["written"] = written;
    report["rate"] = spread::cli::rate_json(rate);
    report["adjustments"] = spread::cli::setting_guidance_json(guidance);
    if (!plot_error.empty()) report["plot_error"] = plot_error;
    if (!report_problem.empty() || !report_error.empty()) {
      report["report_error"] = report_problem.empty() ? report_error : report_problem;
    }
    std::cout << report.dump(2) << "\n";
  } else {
    std::printf("fit of '%s' at %g rpm to %s (%d iterations, %s):\n", o.material.c_str(), o.rpm, o.trays.c_str(),
                fit.iterations, fit.converged ? "converged" : "NOT converged");
    if (fit.table_samples) {
      std::printf("  launches: the table's DEM row at %g rpm (%zu samples, %d per evaluation), corrected\n",
                  setup.table_row_rpm, setup.table_samples.size(), o.samples);
    }
    auto line = [&](const char* label, double value, double error, bool fitted, const char* unit) {
      if (fitted) std::printf("  %-22s %8.4f ± %.4f%s\n", label, value, error, unit);
      else std::printf("  %-22s %8.4f (fixed)%s\n", label, value, unit);
    };
    if (!fit.table_samples) {
      line("friction on vanes", fit.fitted.friction_wall, fit.standard_error.friction_wall, fit.fitted_mask[0], "");
    }
    line("drag diameter factor", fit.fitted.drag_diameter_factor, fit.standard_error.drag_diameter_factor,
         fit.fitted_mask[1], "");
    line("launch angle offset", fit.fitted.launch_angle_offset_rad * kDegPerRad,
         fit.standard_error.launch_angle_offset_rad * kDegPerRad, fit.fitted_mask[2], " °");
    if (fit.table_samples || fit.fitted_mask[cal::kLaunchSpeed] || fit.fitted_mask[cal::kElevationOffset]) {
      line("launch speed factor", fit.fitted.launch_speed_factor, fit.standard_error.launch_speed_factor,
           fit.fitted_mask[cal::kLaunchSpeed], "");
      line("launch elevation offset", fit.fitted.launch_elevation_offset_rad * kDegPerRad,
           fit.standard_error.launch_elevation_offset_rad * kDegPerRad, fit.fitted_mask[cal::kElevationOffset], " °");
    }
    std::printf("  residual: rms %.2f g per tray (%.3f %% of the mass per tray; %.3f %% before the fit)\n",
                1e3 * fit.residual_rms_kg, 100.0 * fit.residual_rms_fraction, 100.0 * fit.initial_residual_rms_fraction);
    if (scatter.available) {
      std::printf("  pass-to-pass scatter of the tray test: %.3f %% of the mass per tray for the mean of %d passes; "
                  "residual / scatter %.2f (warning above %.0f)\n",
                  100.0 * scatter.rms_mean_fraction, scatter.passes, acceptance.residual_to_scatter,
                  cal::kResidualToScatterLimit);
    }
    for (const std::string& n : notes) std::printf("  missing: %s\n", n.c_str());
    for (const std::string& w : warnings) std::printf("  warning: %s\n", w.c_str());
    for (const std::string& r : acceptance.refusals) std::printf("  refused: %s\n", r.c_str());
    if (summary) {
      std::printf("wrote '%s' (%zu rpm rows) into %s\n", summary->material.c_str(), summary->rpm_rows.size(),
                  summary->output_path.c_str());
    } else {
      std::printf("nothing written: %s was not created\n", o.output.c_str());
    }
    for (const std::string& rate_line : spread::cli::rate_lines(rate)) std::printf("%s\n", rate_line.c_str());
    if (rate_note) std::printf("note: %s\n", rate_note->c_str());
    for (const std::string& advice : guidance.lines) std::printf("%s\n", advice.c_str());
    for (const auto& [kind, path] : written.items()) std::printf("wrote %s\n", path.get<std::string>().c_str());
  }
  if (!report_problem.empty()) throw spread::cli::ReportUsageError(report_problem);
  if (!acceptance.accepted()) {
    throw FailedAfterReport("the fit is refused (" + std::to_string(acceptance.refusals.size()) +
                            " reason(s) in the report above); nothing written");
  }
  if (!report_error.empty()) throw spread::cli::ReportWriteError("--report: " + report_error);
  if (!plot_error.empty()) throw FailedAfterReport("--plot: " + plot_error);
}

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

void run_synth(const SynthOptions& o) {
  if (o.output.empty()) throw BadInput("--output: give the path of the CSV to write");
  spread::cli::require_output_folder("--output", o.output);
  spread::cli::refuse_existing_file("--output", o.output, o.force, "--force");
  if (o.samples < 16 || o.samples > 100000) throw BadInput("--samples must be in [16, 100000]");
  if (!(o.tray_width_m > 0.0) || !(o.half_width_m >= 2.5 * o.tray_width_m)) {
    throw BadInput("--tray-width must be > 0 and --half-width at least 2.5 tray widths");
  }
  const spread::tables::TableContents contents = spread::tables::read_table_file(o.tables);
  const cal::PatternSetup setup = cal::pattern_setup_from_table(contents, o.material, o.rpm);
  cal::PatternParameters truth = cal::parameters_of(setup.material);
  if (!std::isnan(o.friction)) {
    if (!setup.table_samples.empty()) {
      throw BadInput("--friction: the table's rows of '" + o.material + "' came from the DEM: their launches do not "
                     "depend on a friction; give --speed-factor, --offset, --elevation, --drag");
    }
    truth.friction_wall = o.friction;
  }
  truth.drag_diameter_factor = o.drag;
  truth.launch_angle_offset_rad = o.offset_deg / kDegPerRad;
  truth.launch_speed_factor = o.speed_factor;
  truth.launch_elevation_offset_rad = o.elevation_deg / kDegPerRad;
  cal::check_parameters(truth);
  cal::PatternModelOptions model_options;
  model_options.sample_count = o.samples;
  const spread::metrics::TrayLayout layout = spread::metrics::tray_layout_covering(o.half_width_m, o.tray_width_m);
  const cal::PatternModel model(setup, layout, model_options);
  cal::TrayNoise noise;
  noise.relative_sd = o.relative_noise_percent / 100.0;
  noise.granule_mass_g = o.granule_mass_g;
  noise.floor_sd_g = o.floor_g;
  noise.resolution_g = o.resolution_g;
  const cal::SyntheticTrayTest test = cal::synthetic_tray_test(model, truth, o.mass_g, o.passes, noise, o.seed);
  char text[512];
  std::vector<std::string> comments;
  std::snprintf(text, sizeof text,
                "Synthetic tray test: %d trays of %.2f m, %d pass(es), grams; position_m = tray centre from the "
                "tractor centre line (left negative).",
                layout.tray_count, layout.tray_width_m, o.passes);
  comments.emplace_back(text);
  std::snprintf(text, sizeof text,
                "Made by spread calibrate synth: '%s' of %s at %g rpm, %d samples, friction %.4g, drag diameter "
                "factor %.4g, launch-angle offset %.4g deg, %.4g g per pass in the trays.",
                o.material.c_str(), o.tables.c_str(), o.rpm, o.samples, truth.friction_wall,
                truth.drag_diameter_factor, o.offset_deg, o.mass_g);
  comments.emplace_back(text);
  std::snprintf(text, sizeof text, "Launches: %s, launch speed factor %.4g, launch elevation offset %.4g deg.",
                setup.table_samples.empty() ? "the analytic model"
                                            : ("the table's DEM row at " + std::to_string(static_cast<int>(setup.table_row_rpm)) + " rpm").c_str(),
                o.speed_factor, o.elevation_deg);
  comments.emplace_back(text);
  std::snprintf(text, sizeof text,
                "Noise per tray and pass: Poisson count of %.4g g granules, plus normal with sd^2 = (%.4g %% of the "
                "tray)^2 + (%.4g g)^2, readings below 0 written as 0, rounded to %.4g g; seed %llu.",
                o.granule_mass_g, o.relative_noise_percent, o.floor_g, o.resolution_g,
                static_cast<unsigned long long>(o.seed));
  comments.emplace_back(text);
  cal::write_tray_csv(o.output, test.position_m, test.pass_mass_g, comments);
  if (o.json) {
    json out{{"output", o.output},
             {"trays", layout.tray_count},
             {"tray_width_m", layout.tray_width_m},
             {"passes", o.passes},
             {"truth", {{"friction_wall", truth.friction_wall},
                        {"drag_diameter_factor", truth.drag_diameter_factor},
                        {"launch_angle_offset_deg", o.offset_deg},
                        {"launch_speed_factor", o.speed_factor},
                        {"launch_elevation_offset_deg", o.elevation_deg}}},
             {"seed", o.seed}};
    std::cout << out.dump(2) << "\n";
    return;
  }
  if (setup.table_samples.empty()) {
    std::printf("wrote %s: %d trays of %.2f m, %d pass(es), friction %.4g, drag %.4g, offset %.4g deg\n",
                o.output.c_str(), layout.tray_count, layout.tray_width_m, o.passes, truth.friction_wall,
                truth.drag_diameter_factor, o.offset_deg);
  } else {
    std::printf("wrote %s: %d trays of %.2f m, %d pass(es), the DEM row at %g rpm with launch speed factor %.4g, "
                "offset %.4g deg, elevation %.4g deg, drag %.4g\n",
                o.output.c_str(), layout.tray_count, layout.tray_width_m, o.passes, setup.table_row_rpm,
                o.speed_factor, o.offset_deg, o.elevation_deg, truth.drag_diameter_factor);
  }
}

spread::cli::CommandRegistration reg{"calibrate", [](CLI::App& app, int& /*exit_code: failures are thrown, see error_exit.hpp*/) {
  auto* sub = app.add_subcommand("calibrate", "field calibration: catch test (rate), tray test, pattern fit");
  sub->require_subcommand(1);

  static RateOptions rate;
  auto* r = sub->add_subcommand("rate", "flow factor from a catch test; gate opening for a target rate");
  r->add_option("--mass", rate.mass_kg, "mass caught from all outlets (kg)")->required();
  r->add_option("--time", rate.time_s, "catch duration (s)")->required();
  r->add_option("--gate", rate.gate, "gate opening of the catch (the gate scale's unit: mm, %, ...)")->required();
  r->add_option("--mass2", rate.mass2_kg, "second catch: mass (kg) — two catches fit the gate's dead zone");
  r->add_option("--time2", rate.time2_s, "second catch: duration (s)");
  r->add_option("--gate2", rate.gate2, "second catch: gate opening");
  r->add_option("--target-rate", rate.target_rate_kg_ha, "target application rate (kg/ha)")->required();
  r->add_option("--width", rate.width_m, "working (bout) width (m)")->required();
  r->add_option("--speed", rate.speed_km_h, "forward speed (km/h)")->required();
  r->add_option("--current-gate", rate.current_gate, "gate opening to check (default: the catch's)");
  r->add_flag("--json", rate.json, "machine-readable output on stdout");
  r->callback([] { run_rate(rate); });

  static TrayOptions tray;
  auto* t = sub->add_subcommand("tray", "tray test: CV at a bout width, CV(W), effective working widths");
  t->add_option("file", tray.file, "tray-test CSV (position_m and one *_g or *_kg column per pass)")->required();
  t->add_option("--width", tray.width_m, "bout width W (m) for the CVs (default: none)");
  t->add_option("--cv-target", tray.cv_target_percent, "CV target (%) of the effective working width")->capture_default_str();
  t->add_option("--plot", tray.plot_prefix, "write PREFIX_transverse.png and PREFIX_cv.png");
  t->add_flag("--json", tray.json, "machine-readable output on stdout");
  t->add_option("--machine", tray.machine, "machine name, for the report's header");
  t->add_option("--material", tray.material, "material spread, for the report's header");
  t->add_option("--rpm", tray.rpm, "disc speed of the test (r/min), for the report's header");
  spread::cli::add_report_args(*t, tray.report, true);
  t->add_flag("--quick-check", tray.quick_check,
              "4-8 trays across one bout of the field as driven: their CV and how uncertain it is from so few trays");
  t->callback([] { run_tray(tray); });

  static PatternOptions pattern;
  auto* p = sub->add_subcommand("pattern", "fit a material to a tray test; write it into a new table file");
  p->add_option("--tables", pattern.tables, "launch-table file (read only)")->required();
  p->add_option("--material", pattern.material, "material name in the table")->required();
  p->add_option("--rpm", pattern.rpm, "disc speed of the tray test (r/min)")->required();
  p->add_option("--trays", pattern.trays, "tray-test CSV")->required();
  p->add_option("--output", pattern.output, "NEW table file: a copy of --tables plus the calibrated material")->required();
  p->add_option("--name", pattern.name, "name of the calibrated material (default: 'NAME (calibrated YYYY-MM-DD)')");
  p->add_option("--fit", pattern.fit,
                "parameters to fit, of friction, drag, offset, speed, elevation (the others keep the table's values); "
                "default friction,drag,offset on analytic rows, speed,offset on DEM rows");
  p->add_option("--samples", pattern.samples, "trajectories per model evaluation")->capture_default_str();
  p->add_option("--kernel", pattern.kernel_m, "landing kernel sd (m); default half the tray width");
  p->add_option("--cv-target", pattern.cv_target_percent, "CV target (%) of the plots")->capture_default_str();
  p->add_option("--width", pattern.width_m,
                "bout width (m): the report's, and the calibrated material's CV there with what to change "
                "when it is above the target");
  p->add_flag("--allow-analytic", pattern.allow_analytic,
              "on a material whose table rows came from the DEM: fit the analytic model and write analytic rows "
              "(default: correct the DEM rows' own launches)");
  p->add_option("--plot", pattern.plot_prefix, "write PREFIX_transverse.png, PREFIX_cv.png, PREFIX_cv_measured.png");
  p->add_flag("--json", pattern.json, "machine-readable output on stdout");
  spread::cli::add_report_args(*p, pattern.report, true);
  p->callback([] { run_pattern(pattern); });

  static SynthOptions synth;
  auto* y = sub->add_subcommand("synth", "write a synthetic tray test made by the pattern model (known answers)");
  y->add_option("--tables", synth.tables, "launch-table file (read only)")->required();
  y->add_option("--material", synth.material, "material name in the table")->required();
  y->add_option("--rpm", synth.rpm, "disc speed (r/min)")->required();
  y->add_option("--output", synth.output, "CSV to write")->required();
  y->add_option("--friction", synth.friction, "friction on the vanes (default: the table's)");
  y->add_option("--drag", synth.drag, "drag diameter factor k")->capture_default_str();
  y->add_option("--offset", synth.offset_deg, "launch-angle offset (deg)")->capture_default_str();
  y->add_option("--speed-factor", synth.speed_factor, "launch speed factor s")->capture_default_str();
  y->add_option("--elevation", synth.elevation_deg, "launch elevation offset (deg)")->capture_default_str();
  y->add_option("--half-width", synth.half_width_m, "trays cover [-this, this] m")->capture_default_str();
  y->add_option("--tray-width", synth.tray_width_m, "tray width (m)")->capture_default_str();
  y->add_option("--passes", synth.passes, "passes (one mass column each)")->capture_default_str();
  y->add_option("--mass", synth.mass_g, "expected mass in all trays per pass (g)")->capture_default_str();
  y->add_option("--relative-noise", synth.relative_noise_percent, "noise sd, % of each tray's mass")->capture_default_str();
  y->add_option("--granule-mass", synth.granule_mass_g, "counting noise: mass of one granule (g); 0 = none")->capture_default_str();
  y->add_option("--floor", synth.floor_g, "additive noise sd (g); readings below 0 are written as 0")->capture_default_str();
  y->add_option("--resolution", synth.resolution_g, "readings rounded to this (g)")->capture_default_str();
  y->add_option("--samples", synth.samples, "trajectories of the model")->capture_default_str();
  y->add_option("--seed", synth.seed, "noise seed")->capture_default_str();
  y->add_flag("--force", synth.force, "replace --output when it exists");
  y->add_flag("--json", synth.json, "machine-readable output on stdout");
  y->callback([] { run_synth(synth); });
}};

}  // namespace
}  // namespace spread::cli::cmd_calibrate
