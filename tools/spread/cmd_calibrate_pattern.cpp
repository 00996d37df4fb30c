// spread calibrate pattern: fit friction, drag-diameter factor and launch-angle offset of a material to a tray
// test and write the calibrated material into a NEW table file (the original is only read).
#include "tools/spread/calibrate_report.hpp"

namespace spread::cli::calibrate {

namespace {

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
  return std::string(f.table_samples ? "fitted to the machine's simulated throw: " : "fitted: ") + fitted +
         " (± how closely this tray test fixes each value)" +
         (fixed.empty() ? "" : "; fixed at the table's values: " + fixed) +
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

}  // namespace

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
                     : cal::tagged_material_name(o.material, o.name);
  const cal::TrayTest test = cal::read_tray_csv(o.trays);
  require_width_within_trays(test, o.width_m);
  const spread::cli::TableSession session(o.tables);
  const spread::tables::TableContents& contents = session.contents();
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
    // The calibrated table just written: its own file, read once.
    spread::cli::TableSession calibrated(summary->output_path);
    guidance = spread::cli::setting_guidance(calibrated.predictor(), request);
  }
  const std::optional<spread::plot::ReportRate> rate =
      spread::cli::report_rate(o.report, measured.total_mass_kg, report_width_m, test.layout.tray_width_m);
  const std::optional<std::string> rate_note = missing_rate_note(test, rate);
  // Once, for the terminal, --json and the page alike (a refused fit has no page; its verdicts still print).
  const std::vector<spread::cli::Verdict> verdicts = tray_verdicts(test, measured, report_width_m, rate);
  const std::vector<spread::cli::NextStep> steps = spread::cli::pattern_next_steps(
      summary.has_value(), summary ? summary->output_path : o.output, material_name, o.width_m);
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
      page.verdicts = spread::cli::page_verdicts(verdicts);
      page.rate = rate;
      page.notes = warnings;
      for (const std::string& n : notes) page.notes.push_back("missing: " + n);
      if (rate_note) page.notes.push_back(*rate_note);
      for (const std::string& line : guidance.notes) page.notes.push_back(line);
      for (const std::string& n : spread::cli::next_steps_notes(steps)) page.notes.push_back(n);
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
    report["adjusted_from"] = spread::cli::setting_guidance_present_json(guidance);
    report["verdicts"] = spread::cli::verdicts_json(verdicts);
    report["next_steps"] = spread::cli::next_steps_json(steps);
    {
      // The page's chart overlaps the measured trays, as the tray test's page does.
      spread::plot::PatternReport chart_page = tray_report_page(test, measured, report_width_m, 0);
      if (o.report.tray_area_m2 > 0.0) chart_page.chart.tray_area_m2 = o.report.tray_area_m2;
      report["chart"] = spread::cli::chart_json(chart_page);
    }
    if (report_width_m > 0.0) {
      report["cv_verdict"] = verdicts.front().numbers;
      report["judged_bout_width_m"] = report_width_m;
      report["judged_cv_to_and_fro_percent"] =
          finite_or_null(100.0 * curve_cv(measured, measured.cv_to_and_fro_curve, report_width_m));
      report["judged_cv_racetrack_percent"] =
          finite_or_null(100.0 * curve_cv(measured, measured.cv_racetrack_curve, report_width_m));
    }
    report["tray_test_analysis"] = tray_json(test, measured);
    if (!std::isnan(o.report.speed_km_h)) report["speed_km_h"] = o.report.speed_km_h;
    if (!plot_error.empty()) report["plot_error"] = plot_error;
    if (!report_problem.empty() || !report_error.empty()) {
      report["report_error"] = report_problem.empty() ? report_error : report_problem;
    }
    std::cout << report.dump(2) << "\n";
  } else {
    std::printf("fit of '%s' at %g rpm to %s (%d iterations, %s):\n", o.material.c_str(), o.rpm, o.trays.c_str(),
                fit.iterations, fit.converged ? "converged" : "NOT converged");
    spread::cli::print_verdicts(verdicts);
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
    spread::cli::print_next_steps(steps);
  }
  if (!report_problem.empty()) throw spread::cli::ReportUsageError(report_problem);
  if (!acceptance.accepted()) {
    throw FailedAfterReport("the fit is refused (" + std::to_string(acceptance.refusals.size()) +
                            " reason(s) in the report above); nothing written");
  }
  if (!report_error.empty()) throw spread::cli::ReportWriteError("--report: " + report_error);
  if (!plot_error.empty()) throw FailedAfterReport("--plot: " + plot_error);
}

}  // namespace spread::cli::calibrate
