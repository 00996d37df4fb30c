// spread chart --tables FILE --material NAME [--cv-target PCT] [--widths 12,15,18,21,24] [--tray-width W]
//              [--height M] [--json] [--report OUT.pdf] [--speed KM_H]
//              [--wind VX,VY] [--drop-point-range DEG] [--drop-point-step DEG]
// The setting chart of a material: for each tramline width, the setting of both discs — disc speed
// within the table's rpm rows and drop point within ±--drop-point-range of the table's — with the lowest
// predicted to-and-fro CV at that width, the CVs there ± their 95 % intervals and the spans of disc speed
// (at that drop point) that keep the CV within the target (libspread/analysis/predict/setting_chart.hpp;
// docs/field-calibration.md, "Spread chart"). Uses the C++ predictor directly, as `spread plot` does.
// Bad input → a message naming it on stderr, exit code 2.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/analysis/calibration/machine_scales.hpp"
#include "libspread/analysis/calibration/tray_analysis.hpp"
#include "libspread/analysis/plot/report_pdf.hpp"
#include "libspread/analysis/predict/setting_chart.hpp"
#include "libspread/core/strict_number.hpp"
#include "tools/spread/blend_output.hpp"
#include "tools/spread/command_registry.hpp"
#include "tools/spread/prediction_args.hpp"
#include "tools/spread/next_steps.hpp"
#include "tools/spread/report_args.hpp"
#include "tools/spread/verdicts.hpp"
#include "tools/spread/number_format.hpp"
#include "tools/spread/table_session.hpp"

namespace spread::cli::cmd_chart {
namespace {

using nlohmann::json;
using spread::cli::BadInput;
namespace pr = spread::predict;

// The machine's drop-point scale, when --scales gives one (calibration/machine_scales.hpp).
std::optional<spread::calibration::DropPointScale>& drop_point_scale() {
  static std::optional<spread::calibration::DropPointScale> scale;
  return scale;
}

// "620 rpm, +15.0 deg" — the setting of both discs; with the machine's scale "620 rpm, scale E (+15.0 deg)".
std::string setting_text(const pr::SettingChartRow& row) {
  const double turn_deg = row.drop_point_turn_rad / kRadPerDeg;
  if (drop_point_scale()) {
    return format("%.0f rpm", row.rpm) + ", scale " + spread::calibration::drop_point_mark(*drop_point_scale(), turn_deg) +
           format(" (%+.1f deg)", turn_deg);
  }
  return format("%.0f rpm", row.rpm) + format(", %+.1f deg", turn_deg);
}

struct Options {
  std::string tables, material;
  double cv_target_percent = 15.0;
  std::string widths = "12,15,18,21,24";
  double tray_width_m = 0.5;
  double height_m = std::numeric_limits<double>::quiet_NaN();
  std::string wind = "0,0";  // "VX,VY", m/s
  double drop_point_range_deg = 90.0;  // the drop points searched: turns within ± this of the table's
  double drop_point_step_deg = 5.0;    // their grid step
  bool json = false;
  spread::cli::ReportArgs report;
  std::string scales;  // the machine's scales file; "" = none
};

std::vector<double> parse_widths(const std::string& text) {
  std::vector<double> widths;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const std::optional<double> w = parse_finite_number(item);
    if (!w || !(*w > 0.0)) {
      throw BadInput("--widths: '" + item + "' is not a width in metres > 0 (e.g. --widths 12,15,18)");
    }
    widths.push_back(*w);
  }
  if (widths.empty()) throw BadInput("--widths: give at least one width in metres");
  return widths;
}

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// "14.9 % ± 2.1" with the 95 % half-interval (1.96 standard errors); without it when undefined.
std::string cv_text(double cv, double se) {
  if (!std::isfinite(cv)) return "-";
  std::string text = format("%.1f %%", 100.0 * cv);
  if (std::isfinite(se)) text += format(" ± %.1f", 196.0 * se);
  return text;
}

// "left 506 rpm, +18.4 deg; right 694 rpm, -18.4 deg: CV 4.8 % ± 3.3" — a row's discs set apart in the wind.
std::string compensation_text(const pr::SettingChartRow& row) {
  const auto disc = [&](int d) {
    return format("%.0f rpm", row.compensated_discs[d].rpm) +
           format(", %+.1f deg", row.compensated_discs[d].drop_point_turn_rad / kRadPerDeg);
  };
  return "left " + disc(pr::kLeftDisc) + "; right " + disc(pr::kRightDisc) + ": CV " +
         cv_text(row.compensated_cv, row.compensated_cv_se);
}

std::string spans_text(const pr::SettingChartRow& row) {
  std::string list;
  for (const auto& [low, high] : row.within_target_rpm) {
    list += (list.empty() ? "" : ", ") + format("%.0f", low) + "-" + format("%.0f rpm", high);
  }
  return list.empty() ? "-" : list;
}

std::string reach_note(const pr::SettingChartRow& row, const pr::SettingChart& chart, double cv_target_percent) {
  switch (row.reach) {
    case pr::ChartReach::kNotReached:
      return format("%.1f m", row.width_m) + " is not reachable: no disc speed of " + format("%.0f", chart.min_rpm) +
             "-" + format("%.0f rpm", chart.max_rpm) + " and drop point searched keeps the CV within " +
             format("%g %%", cv_target_percent) + " (lowest " + format("%.1f %%", 100.0 * row.cv_to_and_fro) + " at " +
             setting_text(row) + ")";
    case pr::ChartReach::kMarginal:
      return format("%.1f m", row.width_m) + " is marginal: the best setting's 95 % interval reaches over " +
             format("%g %%", cv_target_percent) + " (a field test should confirm it)";
    case pr::ChartReach::kReached: break;
  }
  return {};
}

// The chart page's first lines: the widths by the verdict of their best setting, by the rule of every
// report (calibration/cv_verdict.hpp) — reached: its 95 % interval within the target (PASS); marginal:
// the interval reaches over it (MARGINAL); not reachable: no setting meets it (FAIL).
std::vector<spread::cli::Verdict> chart_verdicts(const pr::SettingChart& chart, double cv_target_percent) {
  using Level = spread::plot::ReportVerdict::Level;
  struct Group {
    pr::ChartReach reach;
    Level level;
    const char* word;
    std::string meaning;
  };
  const std::string target = format("%g %%", cv_target_percent);
  const Group groups[] = {
      {pr::ChartReach::kReached, Level::kPass, "PASS", "the best setting keeps the CV within " + target + " at 95 % confidence"},
      {pr::ChartReach::kMarginal, Level::kMarginal, "MARGINAL",
       "the best setting's 95 % interval reaches over " + target + ": confirm with a tray test"},
      {pr::ChartReach::kNotReached, Level::kFail, "FAIL", "no setting searched keeps the CV within " + target},
  };
  std::vector<spread::cli::Verdict> verdicts;
  for (const Group& g : groups) {
    std::string widths;
    json widths_m = json::array();
    for (const pr::SettingChartRow& row : chart.rows) {
      if (row.reach != g.reach) continue;
      widths += (widths.empty() ? "" : ", ") + format("%.1f m", row.width_m);
      widths_m.push_back(row.width_m);
    }
    if (widths.empty()) continue;
    verdicts.push_back({"widths", {g.level, g.word, widths + ": " + g.meaning},
                        {{"widths_m", widths_m}, {"cv_target_percent", cv_target_percent}, {"confidence_percent", 95}}});
  }
  return verdicts;
}

// The calibrated versions of `material` in the table: a calibration keeps the product's name and adds
// its tag in parentheses ("Urea (calibrated 2026-12-07)", calibration/calibrated_table.hpp). Charting the
// product itself then is charting the table's uncalibrated pattern, not this spreader's.
std::vector<std::string> calibrated_versions(const pr::Predictor& predictor, const std::string& material) {
  std::vector<std::string> names;
  const std::string prefix = material + " (";
  for (std::size_t i = 0; i < predictor.material_count(); ++i) {
    const std::string& name = predictor.material(i).name;
    if (name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0 && name.back() == ')') {
      names.push_back(name);
    }
  }
  return names;
}

std::string calibrated_note(const std::string& name) {
  return "this table also holds '" + name + "', calibrated to a tray test of this spreader: this chart is of "
         "the uncalibrated material; chart the calibrated one for the settings to use";
}

// A blend's chart: at each disc speed of its rows (the table's drop point and height), the widest bout at
// which every component meets the target, the component that limits it, and there the blend's CV, each
// nutrient's and the separation index (libspread/analysis/blends).
void run_blend_chart(const Options& o, const spread::tables::Blend& blend, double cv_target, spread::cli::TableSession& session) {
  if (!o.report.path.empty() || !o.scales.empty())
    throw BadInput("--material " + o.material + " is a blend: --report and --scales chart a single material");
  pr::Predictor& predictor = session.predictor();
  const std::optional<std::size_t> first = predictor.find_material(blend.components.front().material);
  if (!first) throw BadInput("blend " + blend.name + ": the table has no row \"" + blend.components.front().material + "\"");
  const spread::cli::WindXY wind = spread::cli::parse_wind(o.wind);
  json rows = json::array();
  if (!o.json) std::cout << "blend '" << blend.name << "' of " << o.tables << format(": at CV <= %g %%, per disc speed of its rows", 100.0 * cv_target) << "\n";
  for (const double rpm : predictor.row_rpm(*first)) {
    pr::PredictionRequest request;
    request.material = blend.components.front().material;  // each component's own, in blend_patterns
    request.rpm = rpm;
    request.disc_height_m = o.height_m;
    request.wind_x_m_s = wind.x_m_s;
    request.wind_y_m_s = wind.y_m_s;
    request.cv_target = cv_target;
    request.tray_width_m = o.tray_width_m;
    const spread::blends::BlendPatterns b = spread::blends::blend_patterns(predictor, blend, request);
    if (b.status != pr::PredictStatus::kOk) {
      if (!o.json) std::cout << format("  %.0f rpm: ", rpm) << pr::to_string(b.status) << "\n";
      rows.push_back({{"rpm", rpm}, {"status", pr::to_string(b.status)}});
      continue;
    }
    if (o.json) {
      json row = spread::cli::blend_json(b, cv_target);
      row["rpm"] = rpm;
      row.erase("tray_mass_fraction");
      for (json& c : row["components"]) c.erase("tray_mass_fraction");
      rows.push_back(row);
      continue;
    }
    std::cout << format("  %.0f rpm: widest bout ", rpm) << spread::cli::widest_common_bout_text(b, cv_target)
              << format("; at the %.2f m bout", b.bout_width_m) << format(" blend CV %.1f %%", 100.0 * b.cv_to_and_fro);
    for (const spread::blends::NutrientPattern& n : b.nutrients)
      if (n.carried) std::cout << ", " << n.name << format(" %.1f %%", 100.0 * n.cv_to_and_fro);
    std::cout << format(", separation index %.3f", b.separation_index) << "\n";
  }
  if (o.json) std::cout << json{{"material", o.material}, {"blend_chart", rows}}.dump(2) << "\n";
}

void run(const Options& o, int& exit_code) {
  const double cv_target = spread::calibration::cv_target_from_percent(o.cv_target_percent, "--cv-target");
  if (!o.scales.empty()) drop_point_scale() = spread::calibration::read_machine_scales(o.scales).drop_point;
  const std::vector<double> widths = parse_widths(o.widths);
  const std::string report_problem = spread::cli::check_report_args(o.report);
  const std::int64_t report_time_s = o.report.path.empty() ? 0 : spread::cli::report_time_s();

  spread::cli::TableSession session(o.tables);
  if (const spread::tables::Blend* blend = session.contents().find_blend(o.material)) {
    run_blend_chart(o, *blend, cv_target, session);
    return;
  }
  pr::Predictor& predictor = session.predictor();
  if (!predictor.find_material(o.material)) {
    std::string known;
    for (std::size_t i = 0; i < predictor.material_count(); ++i) known += " " + predictor.material(i).name;
    throw BadInput("--material '" + o.material + "' is not in " + o.tables + "; materials:" + known);
  }
  pr::SettingChartOptions options;
  options.cv_target = cv_target;
  options.tray_width_m = o.tray_width_m;
  options.disc_height_m = o.height_m;
  const spread::cli::WindXY wind = spread::cli::parse_wind(o.wind);
  options.wind_x_m_s = wind.x_m_s;
  options.wind_y_m_s = wind.y_m_s;
  if (!(o.drop_point_range_deg >= 0.0 && o.drop_point_range_deg <= 180.0)) {
    throw BadInput("--drop-point-range " + format("%g", o.drop_point_range_deg) + ": within 0..180 degrees");
  }
  if (!(o.drop_point_step_deg >= 0.5 && o.drop_point_step_deg <= 90.0)) {
    throw BadInput("--drop-point-step " + format("%g", o.drop_point_step_deg) + ": within 0.5..90 degrees");
  }
  options.max_drop_point_turn_rad = o.drop_point_range_deg * kRadPerDeg;
  options.drop_point_step_rad = o.drop_point_step_deg * kRadPerDeg;
  const pr::SettingChart chart = pr::setting_chart(predictor, o.material, widths, options);

  // The drop points searched: ±--drop-point-range, within the turns the table validates (where narrower).
  const pr::TurnRange valid = predictor.drop_point_turn_range();
  const double range_rad = o.drop_point_range_deg * kRadPerDeg;
  const std::string turns_text = valid.low_rad <= -range_rad && valid.high_rad >= range_rad
                                ? format("±%g deg", o.drop_point_range_deg)
                                : format("%+g", std::max(valid.low_rad, -range_rad) / kRadPerDeg) +
                                      format(" to %+g deg (validated against DEM rows)",
                                             std::min(valid.high_rad, range_rad) / kRadPerDeg);
  const std::string range_line = "'" + o.material + "' of " + o.tables + ": the disc speed of " +
                                 format("%.0f", chart.min_rpm) + "-" + format("%.0f rpm", chart.max_rpm) +
                                 " and drop point within " + turns_text +
                                 " of the table's (both discs alike) with the lowest to-and-fro CV at each width (target " +
                                 format("%g %%", o.cv_target_percent) + ")";
  // The page's: the same in the farmer's words (the table is named in its header).
  std::string page_turns = turns_text;
  if (const auto at = page_turns.find(" (validated against DEM rows)"); at != std::string::npos) {
    page_turns.replace(at, std::string(" (validated against DEM rows)").size(), " (where the simulation checked it)");
  }
  const std::string page_range_line = "'" + o.material + "': the disc speed of " + format("%.0f", chart.min_rpm) + "-" +
                                      format("%.0f rpm", chart.max_rpm) + " and drop point within " + page_turns +
                                      " of the table's (both discs alike) with the lowest to-and-fro CV at each width "
                                      "(target " + format("%g %%", o.cv_target_percent) + ")";

  // Once, for the terminal, --json and the page alike.
  const std::vector<spread::cli::Verdict> verdicts = chart_verdicts(chart, o.cv_target_percent);
  const std::vector<spread::cli::NextStep> steps = spread::cli::chart_next_steps();
  const std::vector<std::string> calibrated = calibrated_versions(predictor, o.material);
  std::string report_error;
  if (!o.report.path.empty() && report_problem.empty()) {
    try {
      spread::plot::TablePage page;
      page.header.title = "Spread chart";
      page.header.source = o.tables;
      page.header.machine = predictor.machine().name;
      page.header.material = o.material;
      page.header.rpm_text = "per working width, below";
      page.header.speed_km_h = o.report.speed_km_h;
      page.header.time_s = report_time_s;
      page.header.made_by = spread::cli::command_line();
      page.summary.push_back(page_range_line);
      page.verdicts = spread::cli::page_verdicts(verdicts);
      page.caption = "Disc speed per working width (CV target " + format("%g %%", o.cv_target_percent) + ")";
      page.columns = {"width", "speed, drop point", "CV to-and-fro", "CV racetrack", "CV within target at"};
      for (const pr::SettingChartRow& row : chart.rows) {
        if (row.reach == pr::ChartReach::kNotReached) {
          page.rows.push_back({format("%.1f m", row.width_m), "not reachable", cv_text(row.cv_to_and_fro, row.cv_to_and_fro_se),
                               "-", "-"});
        } else {
          page.rows.push_back({format("%.1f m", row.width_m), setting_text(row),
                               cv_text(row.cv_to_and_fro, row.cv_to_and_fro_se),
                               cv_text(row.cv_racetrack, row.cv_racetrack_se), spans_text(row)});
        }
        const std::string note = reach_note(row, chart, o.cv_target_percent);
        if (!note.empty()) page.notes.push_back(note);
        if (row.compensated) {
          page.notes.push_back(format("%.1f m", row.width_m) + " in this wind, each disc set apart: " +
                               compensation_text(row));
        }
      }
      page.notes.push_back("± = 95 % interval over the table's simulated granules; the setting is "
                           "the one with the lowest predicted to-and-fro CV at the width; the drop point is turned "
                           "from the table's (+ counter-clockwise from above on the left disc, mirrored on the "
                           "right), and the speed spans are at that drop point");
      for (const std::string& name : calibrated) page.notes.push_back(calibrated_note(name));
      for (const std::string& n : spread::cli::next_steps_notes(steps)) page.notes.push_back(n);
      spread::plot::write_report_pdf(o.report.path, nullptr, &page);
    } catch (const std::exception& e) {
      report_error = e.what();
    }
  }

  if (o.json) {
    json rows = json::array();
    for (const pr::SettingChartRow& row : chart.rows) {
      rows.push_back({{"width_m", row.width_m},
                      {"reachable", row.reach != pr::ChartReach::kNotReached},
                      {"reach", pr::to_string(row.reach)},
                      {"rpm", number_or_null(row.rpm)},
                      {"drop_point_turn_deg", number_or_null(row.drop_point_turn_rad / kRadPerDeg)},
                      {"drop_point_mark", drop_point_scale() && std::isfinite(row.drop_point_turn_rad)
                                              ? json(spread::calibration::drop_point_mark(*drop_point_scale(),
                                                                                          row.drop_point_turn_rad / kRadPerDeg))
                                              : json(nullptr)},
                      {"bout_width_m", number_or_null(row.bout_width_m)},
                      {"cv_to_and_fro_percent", number_or_null(100.0 * row.cv_to_and_fro)},
                      {"cv_to_and_fro_se_percent", number_or_null(100.0 * row.cv_to_and_fro_se)},
                      {"cv_racetrack_percent", number_or_null(100.0 * row.cv_racetrack)},
                      {"cv_racetrack_se_percent", number_or_null(100.0 * row.cv_racetrack_se)},
                      {"working_width_to_and_fro_m", number_or_null(row.working_width_to_and_fro_m)},
                      {"working_width_to_and_fro_se_m", number_or_null(row.working_width_to_and_fro_se_m)},
                      {"sample_count", row.sample_count},
                      {"lowest_cv", {{"rpm", number_or_null(row.lowest_cv_rpm)},
                                     {"drop_point_turn_deg", number_or_null(row.lowest_cv_drop_point_turn_rad / kRadPerDeg)},
                                     {"cv_to_and_fro_percent", number_or_null(100.0 * row.lowest_cv)},
                                     {"cv_to_and_fro_se_percent", number_or_null(100.0 * row.lowest_cv_se)}}},
                      {"within_target_rpm", row.within_target_rpm},
                      {"wind_compensation",
                       row.compensated
                           ? json{{"left", {{"rpm", row.compensated_discs[pr::kLeftDisc].rpm},
                                            {"drop_point_turn_deg",
                                             row.compensated_discs[pr::kLeftDisc].drop_point_turn_rad / kRadPerDeg}}},
                                  {"right", {{"rpm", row.compensated_discs[pr::kRightDisc].rpm},
                                             {"drop_point_turn_deg",
                                              row.compensated_discs[pr::kRightDisc].drop_point_turn_rad / kRadPerDeg}}},
                                  {"cv_to_and_fro_percent", number_or_null(100.0 * row.compensated_cv)},
                                  {"cv_to_and_fro_se_percent", number_or_null(100.0 * row.compensated_cv_se)}}
                           : json(nullptr)}});
    }
    json scan = json::array();
    for (std::size_t k = 0; k < chart.scan_rpm.size(); ++k) {
      json cvs = json::array();
      for (std::size_t w = 0; w < chart.rows.size(); ++w) {
        cvs.push_back(number_or_null(100.0 * chart.scan_cv_to_and_fro[w * chart.scan_rpm.size() + k]));
      }
      scan.push_back({{"rpm", chart.scan_rpm[k]}, {"cv_to_and_fro_percent", cvs}});
    }
    json out{{"tables", o.tables},
             {"material", o.material},
             {"cv_target_percent", o.cv_target_percent},
             {"rpm_range", {chart.min_rpm, chart.max_rpm}},
             {"drop_point_range_deg", o.drop_point_range_deg},
             {"grid", {{"rpm", chart.grid_rpm}, {"drop_point_turn_deg", [&] {
                          json turns = json::array();
                          for (double t : chart.grid_drop_point_turn_rad) turns.push_back(t / kRadPerDeg);
                          return turns;
                        }()}}},
             {"rows", rows},
             {"scan", scan},
             {"predictions", chart.predictions},
             {"verdicts", spread::cli::verdicts_json(verdicts)},
             {"calibrated_versions", calibrated},
             {"next_steps", spread::cli::next_steps_json(steps)}};
    if (!std::isnan(o.report.speed_km_h)) out["speed_km_h"] = o.report.speed_km_h;
    spread::cli::add_report_outcome(out, o.report, report_problem, report_error);
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("%s\n", range_line.c_str());
    spread::cli::print_verdicts(verdicts);
    // The setting column as wide as its widest cell (a drop point on the machine's scale is longer).
    int setting_width = 20;
    for (const pr::SettingChartRow& row : chart.rows) {
      if (row.reach != pr::ChartReach::kNotReached) {
        setting_width = std::max(setting_width, static_cast<int>(setting_text(row).size()));
      }
    }
    std::printf("  %-8s %-*s %-18s %-18s %s\n", "width", setting_width, "speed, drop point", "CV to-and-fro",
                "CV racetrack", "CV within target at");
    for (const pr::SettingChartRow& row : chart.rows) {
      if (row.reach == pr::ChartReach::kNotReached) {
        std::printf("  %-8s %s\n", format("%.1f m", row.width_m).c_str(), "not reachable");
        continue;
      }
      std::printf("  %-8s %-*s %-18s %-18s %s\n", format("%.1f m", row.width_m).c_str(), setting_width,
                  setting_text(row).c_str(), cv_text(row.cv_to_and_fro, row.cv_to_and_fro_se).c_str(),
                  cv_text(row.cv_racetrack, row.cv_racetrack_se).c_str(), spans_text(row).c_str());
    }
    std::printf("  (± = 95 %% interval, 1.96 standard errors over the launch samples and, between DEM rows, the "
                "interpolation's own error; %d predictions)\n",
                chart.predictions);
    for (const pr::SettingChartRow& row : chart.rows) {
      const std::string note = reach_note(row, chart, o.cv_target_percent);
      if (!note.empty()) std::printf("  note: %s\n", note.c_str());
    }
    for (const pr::SettingChartRow& row : chart.rows) {
      if (row.reach == pr::ChartReach::kNotReached) continue;
      if (row.lowest_cv_rpm == row.rpm && row.lowest_cv_drop_point_turn_rad == row.drop_point_turn_rad) continue;
      std::printf("  note: %s: the lowest CV found, %s at %s, is less sure than the setting shown (its 95 %% "
                  "interval reaches higher)\n",
                  format("%.1f m", row.width_m).c_str(), cv_text(row.lowest_cv, row.lowest_cv_se).c_str(),
                  (format("%.0f rpm", row.lowest_cv_rpm) +
                   format(", %+.1f deg", row.lowest_cv_drop_point_turn_rad / kRadPerDeg)).c_str());
    }
    bool heading = false;
    for (const pr::SettingChartRow& row : chart.rows) {
      if (!row.compensated) continue;
      if (!heading) std::printf("  in this wind, each disc set apart from the setting above (wind compensation):\n");
      heading = true;
      std::printf("  %-8s %s\n", format("%.1f m", row.width_m).c_str(), compensation_text(row).c_str());
    }
    for (const std::string& name : calibrated) std::printf("note: %s\n", calibrated_note(name).c_str());
    if (!o.report.path.empty() && report_problem.empty() && report_error.empty()) {
      std::printf("wrote %s\n", o.report.path.c_str());
    }
    spread::cli::print_next_steps(steps);
  }
  spread::cli::throw_report_outcome(report_problem, report_error);
  exit_code = spread::cli::kExitOk;
}

spread::cli::CommandRegistration reg{"chart", [](CLI::App& app, int& exit_code) {
  static Options options;
  auto* sub = app.add_subcommand("chart", "setting chart: the disc speed and drop point with the lowest CV at each tramline width");
  sub->add_option("--tables", options.tables, "launch-table file (SQLite) written by lookup_builder")->required();
  sub->add_option("--material", options.material, "material name as in the table")->required();
  sub->add_option("--cv-target", options.cv_target_percent, "CV target of the working width (%)")->capture_default_str();
  sub->add_option("--widths", options.widths, "working widths (m), comma-separated")->capture_default_str();
  sub->add_option("--tray-width", options.tray_width_m, "collecting tray width (m)")->capture_default_str();
  sub->add_option("--height", options.height_m, "disc height above the ground (m); default: the table's");
  sub->add_option("--wind", options.wind, "wind of the day VX,VY (m/s): lateral (+ to the right), along (+ forward)")
      ->capture_default_str();
  sub->add_option("--drop-point-range", options.drop_point_range_deg,
                  "drop points searched: turns within ± this of the table's (degrees; 0 = the table's only)")
      ->capture_default_str();
  sub->add_option("--drop-point-step", options.drop_point_step_deg, "grid step of the drop points searched (degrees)")
      ->capture_default_str();
  sub->add_flag("--json", options.json, "machine-readable output on stdout");
  sub->add_option("--scales", options.scales,
                  "the machine's scales file (TOML): each drop point also on its drop-point scale, e.g. "
                  "scenes/field/default_scales.toml");
  spread::cli::add_report_args(*sub, options.report, false);
  sub->callback([&exit_code] { run(options, exit_code); });
}};

}  // namespace
}  // namespace spread::cli::cmd_chart
