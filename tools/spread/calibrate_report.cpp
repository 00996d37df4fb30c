// spread calibrate: the tray-test report's pieces that tray and pattern both print.
#include "tools/spread/calibrate_report.hpp"

namespace spread::cli::calibrate {

namespace {
std::string positions_text(const std::vector<double>& positions_m) {
  std::string text;
  for (std::size_t i = 0; i < positions_m.size() && i < 8; ++i) {
    text += (i > 0 ? ", " : "") + format("%.2f", positions_m[i]);
  }
  if (positions_m.size() > 8) text += ", ...";
  return text + " m";
}
}  // namespace

// The tray test's analysis as --json gives it: every number its page prints.
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

std::string passes_text(std::size_t passes) { return std::to_string(passes) + (passes == 1 ? " pass" : " passes"); }

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

// A CV as printed: NaN is a bout left with less than two trays' weight measured (cv_without_missing.hpp).
std::string cv_text(double cv, double target) {
  return std::isnan(cv) ? std::string("none (missing trays leave under two trays of the bout measured)")
                        : spread::plot::cv_percent_text(cv, target);
}

// --width beyond the trays: the CV would describe the ground no tray covered (tray_plausibility.hpp).
void require_width_within_trays(const cal::TrayTest& t, double width_m) {
  if (width_m == 0.0) return;  // not given
  if (const std::string range = cal::field_range_problem(cal::kBoutWidthRange, "--width", width_m); !range.empty()) {
    throw BadInput(range);
  }
  const std::string problem = cal::bout_width_problem(t.layout, width_m);
  if (!problem.empty()) throw BadInput("--width " + problem);
}

// The rate a tray test caught counts the trays read: a missing tray's share of the bout is not in it.
std::optional<std::string> missing_rate_note(const cal::TrayTest& t, const std::optional<spread::plot::ReportRate>& rate) {
  if (!rate || !t.has_missing_trays()) return std::nullopt;
  return std::string("the caught rate counts the trays read only: missing trays lower it");
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

// The verdicts of a tray test, computed once for the terminal, --json and the page.
std::vector<spread::cli::Verdict> tray_verdicts(const cal::TrayTest& t, const cal::TrayTestAnalysis& a,
                                                double bout_width_m,
                                                const std::optional<spread::plot::ReportRate>& rate) {
  std::vector<spread::cli::Verdict> verdicts;
  if (bout_width_m > 0.0) {
    const std::string what = a.bout_width_m > 0.0
                                 ? "CV at the " + format("%.2f m", bout_width_m) + " bout, to-and-fro"
                                 : "CV at " + format("%.2f m", bout_width_m) + " (no bout width given: the widest "
                                   "whole number of trays within the working width), to-and-fro";
    verdicts.push_back(spread::cli::cv_verdict(what, bout_verdict(t, bout_width_m, a.cv_target)));
    verdicts.back().numbers["bout_width_m"] = bout_width_m;
    verdicts.back().numbers["bout_width_given"] = a.bout_width_m > 0.0;
    if (t.mass_columns.size() < 2) verdicts.back().shown.text += "; one pass shows no repeatability: drive two or more";
  }
  if (auto rate_verdict = spread::cli::rate_verdict(rate)) verdicts.push_back(*rate_verdict);
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
  std::snprintf(text, sizeof text, "%zu trays of %.2f m, %s, %.1f g in the trays (mean of the passes), "
                "throw width %.1f m", t.mass_kg.size(), t.tray_width_m, passes_text(t.mass_columns.size()).c_str(),
                1e3 * a.total_mass_kg, a.throw_width_m);
  r.summary.emplace_back(text);
  r.tray_mass_kg = t.layout_mass_kg;
  r.trays = t.layout;
  r.chart.missing_trays = t.layout_missing;
  r.chart.series_label = t.mass_columns.size() > 1 ? "measured, mean of the passes" : "measured";
  r.chart.bout_width_m = bout_width_m;
  if (bout_width_m > 0.0) {
    r.chart.bout_cv = curve_cv(a, a.cv_to_and_fro_curve, bout_width_m);
    std::snprintf(text, sizeof text, "at W = %.2f m: CV %s to-and-fro, %s racetrack%s", bout_width_m,
                  cv_text(r.chart.bout_cv, a.cv_target).c_str(),
                  cv_text(curve_cv(a, a.cv_racetrack_curve, bout_width_m), a.cv_target).c_str(),
                  a.bout_width_m > 0.0 ? "" : " (no bout width given: the working width, in whole trays)");
    r.summary.emplace_back(text);
  }
  r.chart.cv_target = a.cv_target;
  r.bout_row_mark = a.bout_width_m > 0.0 ? "driven" : "judged";
  r.bands_to_and_fro_m = a.bands_to_and_fro_m;
  r.bands_racetrack_m = a.bands_racetrack_m;
  r.chart_title = "tray test: one pass across the driving direction";
  r.cv_target = a.cv_target;
  r.working_width_to_and_fro_m = a.working_width_to_and_fro_m;
  r.working_width_racetrack_m = a.working_width_racetrack_m;
  r.cv_table = tray_cv_table(a, bout_width_m);
  return r;
}

}  // namespace spread::cli::calibrate
