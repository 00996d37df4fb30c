// spread calibrate tray: tray-test CSV → CV (to-and-fro, racetrack) at a bout width, CV(W), effective working widths; --quick-check for a few trays across one bout.
#include "tools/spread/calibrate_report.hpp"

namespace spread::cli::calibrate {

namespace {

void plot_tray(const cal::TrayTest& t, const cal::TrayTestAnalysis& a, const std::string& prefix, double tray_area_m2,
               json& written) {
  spread::plot::TransverseOptions options;
  options.series_label = "measured";
  if (tray_area_m2 > 0.0) options.tray_area_m2 = tray_area_m2;
  // The bout the page and the verdict judge, with their CV (missing trays left out, not counted as empty).
  options.bout_width_m = report_bout_width_m(t, a);
  if (options.bout_width_m > 0.0) options.bout_cv = curve_cv(a, a.cv_to_and_fro_curve, options.bout_width_m);
  options.cv_target = a.cv_target;
  options.missing_trays = t.layout_missing;
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
                  "the bout width %.3g m is not a whole number of %.2f m trays: the CVs are at W = %.2f m, the nearest "
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
  // Once, for the terminal, --json and the page alike: the rule of every report (cv_verdict.hpp) on
  // McKay's interval, with what it means for so few trays.
  std::vector<spread::cli::Verdict> verdicts{spread::cli::cv_verdict(
      "CV of the bout from " + std::to_string(q.trays) + " trays",
      cal::cv_verdict(q.cv, q.interval.low, q.interval.high, cv_target))};
  verdicts.front().numbers["trays"] = q.trays;
  if (auto rate_verdict = spread::cli::rate_verdict(rate)) verdicts.push_back(*rate_verdict);
  const std::string target = format("%g %%", 100.0 * cv_target);
  std::string meaning;
  switch (verdicts.front().shown.level) {
    case spread::plot::ReportVerdict::Level::kPass:
      meaning = "even the top of the interval is within " + target;
      break;
    case spread::plot::ReportVerdict::Level::kFail:
      meaning = "even the bottom of the interval is above " + target;
      break;
    default:
      meaning = "the target " + target + " lies inside the interval: " + std::to_string(q.trays) +
                " trays cannot tell whether the spread meets it; lay a full tray test across the throw to know";
      break;
  }
  const std::string verdict = verdicts.front().shown.word + ", " + meaning;
  const std::vector<spread::cli::NextStep> steps = spread::cli::tray_next_steps(
      verdicts, q.trays * t.tray_width_m, 0.0, true, static_cast<int>(t.mass_columns.size()), true, t.source);
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
      std::snprintf(text, sizeof text, "%d trays read, %.2f m apart, %s, mean %.2f g per tray", q.trays,
                    t.tray_width_m, passes_text(t.mass_columns.size()).c_str(), 1e3 * q.mean_kg);
      page.summary.emplace_back(text);
      page.summary.push_back(format("CV %.1f %%", 100.0 * q.cv) + "; the bout's CV lies between " +
                             format("%.1f %%", 100.0 * q.interval.low) + " and " + high + " (95 % interval)");
      page.summary.push_back("against the target: " + verdict);
      page.verdicts = spread::cli::page_verdicts(verdicts);
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
      for (const std::string& n : spread::cli::next_steps_notes(steps)) page.notes.push_back(n);
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
             {"tray_positions_m", t.position_m},
             {"tray_mass_g", [&] {
                json masses = json::array();  // mean of the passes read; null for a missing tray
                for (std::size_t i = 0; i < t.mass_kg.size(); ++i) {
                  masses.push_back(t.missing[i] ? json(nullptr) : json(1e3 * t.mass_kg[i]));
                }
                return masses;
              }()},
             {"mean_g", 1e3 * q.mean_kg},
             {"sd_g", 1e3 * q.sd_kg},
             {"cv_percent", 100.0 * q.cv},
             {"cv_interval_percent", {100.0 * q.interval.low, finite_or_null(100.0 * q.interval.high)}},
             {"confidence_percent", 100.0 * q.interval.confidence},
             {"cv_target_percent", 100.0 * cv_target},
             {"verdict", spread::cli::verdict_key(verdicts.front().shown.level)},
             {"verdicts", spread::cli::verdicts_json(verdicts)},
             {"rate", spread::cli::rate_json(rate)},
             {"notes", notes},
             {"next_steps", spread::cli::next_steps_json(steps)}};
    spread::cli::add_report_outcome(out, o.report, report_problem, report_error);
    std::cout << out.dump(2) << "\n";
    spread::cli::throw_report_outcome(report_problem, report_error);
    return;
  }
  std::printf("%s: quick check, %d trays read (%.2f m apart), %zu pass(es), mean %.2f g per tray\n", t.source.c_str(),
              q.trays, t.tray_width_m, t.mass_columns.size(), 1e3 * q.mean_kg);
  spread::cli::print_verdicts(verdicts);
  std::printf("CV %.1f %% over the %d trays; from %d trays the bout's CV lies between %.1f %% and %s (%.0f %% "
              "interval, McKay)\n",
              100.0 * q.cv, q.trays, q.trays, 100.0 * q.interval.low, high.c_str(), 100.0 * q.interval.confidence);
  std::printf("against the target: %s\n", verdict.c_str());
  for (const std::string& n : notes) std::printf("missing: %s\n", n.c_str());
  for (const std::string& line : spread::cli::rate_lines(rate)) std::printf("%s\n", line.c_str());
  if (!o.report.path.empty() && report_problem.empty() && report_error.empty()) {
    std::printf("wrote %s\n", o.report.path.c_str());
  }
  spread::cli::print_next_steps(steps);
  spread::cli::throw_report_outcome(report_problem, report_error);
}

}  // namespace

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
  // Once, for the terminal, --json and the page alike.
  const std::vector<spread::cli::Verdict> verdicts = tray_verdicts(t, a, report_width_m, rate);
  const std::vector<spread::cli::NextStep> steps =
      spread::cli::tray_next_steps(verdicts, report_width_m, a.working_width_to_and_fro_m, a.bout_width_m > 0.0,
                                   static_cast<int>(t.mass_columns.size()), false, t.source);
  json written = json::object();
  const std::string plot_error =
      o.plot_prefix.empty() ? std::string() : plot_or_error([&] { plot_tray(t, a, o.plot_prefix, o.report.tray_area_m2, written); });
  // The page, made whether or not it is written: --json gives its chart's numbers too.
  spread::plot::PatternReport page = tray_report_page(t, a, report_width_m, time_s);
  if (o.report.tray_area_m2 > 0.0) page.chart.tray_area_m2 = o.report.tray_area_m2;
  page.header.machine = o.machine;
  page.header.material = o.material;
  page.header.rpm = o.rpm;
  page.header.speed_km_h = o.report.speed_km_h;
  page.verdicts = spread::cli::page_verdicts(verdicts);
  page.rate = rate;
  page.notes = warnings;
  for (const std::string& n : notes) page.notes.push_back("missing: " + n);
  if (rate_note) page.notes.push_back(*rate_note);
  for (const std::string& n : spread::cli::next_steps_notes(steps)) page.notes.push_back(n);
  std::string report_error;
  if (!o.report.path.empty() && report_problem.empty()) {
    report_error = plot_or_error([&] {
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
    out["verdicts"] = spread::cli::verdicts_json(verdicts);
    out["chart"] = spread::cli::chart_json(page);
    out["next_steps"] = spread::cli::next_steps_json(steps);
    // The CV's verdict at the bout judged: --width's, else the widest whole number of trays within the
    // working width (the page's "judged" row).
    if (report_width_m > 0.0) {
      out["cv_verdict"] = verdicts.front().numbers;
      out["judged_bout_width_m"] = report_width_m;
      out["judged_cv_to_and_fro_percent"] = finite_or_null(100.0 * curve_cv(a, a.cv_to_and_fro_curve, report_width_m));
      out["judged_cv_racetrack_percent"] = finite_or_null(100.0 * curve_cv(a, a.cv_racetrack_curve, report_width_m));
    }
    if (!std::isnan(o.rpm)) out["rpm"] = o.rpm;
    if (!std::isnan(o.report.speed_km_h)) out["speed_km_h"] = o.report.speed_km_h;
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
  spread::cli::print_verdicts(verdicts);
  if (a.bout_width_m > 0.0) {
    std::printf("at W = %.2f m: CV %s to-and-fro, %s racetrack\n", a.bout_width_m,
                cv_text(a.cv_to_and_fro, a.cv_target).c_str(), cv_text(a.cv_racetrack, a.cv_target).c_str());
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
  spread::cli::print_next_steps(steps);
  fail_after_report();
}

}  // namespace spread::cli::calibrate
