#include "tools/spread/report_args.hpp"

#include <cmath>
#include <stdexcept>

#include "libspread/analysis/calibration/field_ranges.hpp"
#include "libspread/analysis/calibration/tray_rate_check.hpp"
#include "libspread/analysis/plot/report_date.hpp"
#include "tools/spread/output_paths.hpp"
#include "tools/spread/number_format.hpp"

namespace spread::cli {
namespace {

std::string& recorded_command_line() {
  static std::string line;
  return line;
}

}  // namespace

void add_report_args(CLI::App& sub, ReportArgs& args, bool rate) {
  sub.add_option("--report", args.path, "write a PDF report to this file (A4; its folder must exist)");
  sub.add_option("--speed", args.speed_km_h, "forward speed (km/h), for the report's header");
  if (rate) {
    sub.add_option("--tray-area", args.tray_area_m2,
                   "catching area of one tray (m²): report the rate caught in kg/ha at the bout width");
    sub.add_option("--rate-kg-ha", args.set_rate_kg_ha,
                   "rate set from the catch test (kg/ha): check the trays caught 90-110 % of it (EN 13739-2)");
  }
}

std::string check_report_args(const ReportArgs& args) {
  // Before any arithmetic: a number no field holds is a unit or typing slip (calibration/field_ranges.hpp).
  const auto require = [](const calibration::FieldRange& range, const char* option, double value) {
    if (std::isnan(value)) return;  // not given
    if (const std::string problem = calibration::field_range_problem(range, option, value); !problem.empty()) {
      throw std::invalid_argument(problem);
    }
  };
  require(calibration::kSpeedRange, "--speed", args.speed_km_h);
  require(calibration::kTrayAreaRange, "--tray-area", args.tray_area_m2);
  require(calibration::kRateRange, "--rate-kg-ha", args.set_rate_kg_ha);
  if (!std::isnan(args.set_rate_kg_ha) && std::isnan(args.tray_area_m2)) {
    throw std::invalid_argument("--rate-kg-ha needs --tray-area (m²): the caught rate is mass per tray area");
  }
  if (args.path.empty()) return {};
  (void)report_time_s();  // a malformed SOURCE_DATE_EPOCH is refused before the work
  try {
    require_output_folder("--report", args.path);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

std::int64_t report_time_s() { return plot::report_time_s(); }

void remember_command_line(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    std::string arg = argv[i];
    if (i == 0) {
      const auto slash = arg.find_last_of('/');
      if (slash != std::string::npos) arg = arg.substr(slash + 1);
    }
    const bool quote = arg.empty() || arg.find_first_of(" \t'\"") != std::string::npos;
    line += (i > 0 ? " " : "") + (quote ? "'" + arg + "'" : arg);
  }
  recorded_command_line() = line;
}

std::string command_line() { return recorded_command_line(); }

std::optional<plot::ReportRate> report_rate(const ReportArgs& args, double mass_per_pass_kg, double bout_width_m,
                                            double tray_width_m) {
  if (std::isnan(args.tray_area_m2) || !(bout_width_m > 0.0)) return std::nullopt;
  const calibration::TrayRateCheck check =
      calibration::tray_rate_check(mass_per_pass_kg, bout_width_m, tray_width_m, args.tray_area_m2, args.set_rate_kg_ha);
  plot::ReportRate rate;
  rate.tray_area_m2 = args.tray_area_m2;
  rate.bout_width_m = bout_width_m;
  rate.rate_kg_ha = check.rate_kg_ha;
  rate.set_rate_kg_ha = check.set_rate_kg_ha;
  rate.caught_percent = check.caught_percent;
  rate.lowest_percent = calibration::kRateCheckLowestPercent;
  rate.highest_percent = calibration::kRateCheckHighestPercent;
  rate.pass = check.pass;
  return rate;
}

nlohmann::json rate_json(const std::optional<plot::ReportRate>& rate) {
  if (!rate) return nullptr;
  nlohmann::json out{{"tray_area_m2", rate->tray_area_m2},
                     {"bout_width_m", rate->bout_width_m},
                     {"rate_kg_ha", rate->rate_kg_ha}};
  if (std::isnan(rate->set_rate_kg_ha)) {
    out["rate_check"] = nullptr;
  } else {
    out["rate_check"] = {{"set_rate_kg_ha", rate->set_rate_kg_ha},
                         {"caught_percent", rate->caught_percent},
                         {"lowest_percent", rate->lowest_percent},
                         {"highest_percent", rate->highest_percent},
                         {"pass", rate->pass}};
  }
  return out;
}

std::vector<std::string> rate_lines(const std::optional<plot::ReportRate>& rate) {
  std::vector<std::string> lines;
  if (!rate) return lines;
  lines.push_back("rate caught at W = " + format("%.2f m", rate->bout_width_m) + ": " +
                  format("%.1f kg/ha", rate->rate_kg_ha) + " (tray area " + format("%g m²", rate->tray_area_m2) + ")");
  if (!std::isnan(rate->set_rate_kg_ha)) {
    lines.push_back(std::string("EN 13739-2 rate check: ") + (rate->pass ? "PASS" : "FAIL") + ", the trays caught " +
                    format("%.1f %%", rate->caught_percent) + " of the set " + format("%.1f kg/ha", rate->set_rate_kg_ha) +
                    " (" + format("%g", rate->lowest_percent) + "-" + format("%g %%", rate->highest_percent) + " required)");
  }
  return lines;
}

void add_report_outcome(nlohmann::json& out, const ReportArgs& args, const std::string& problem,
                        const std::string& write_error) {
  const bool failed = !problem.empty() || !write_error.empty();
  if (!args.path.empty()) out["report"] = failed ? nlohmann::json(nullptr) : nlohmann::json(args.path);
  if (failed) out["report_error"] = problem.empty() ? write_error : problem;
}

void throw_report_outcome(const std::string& problem, const std::string& write_error) {
  if (!problem.empty()) throw ReportUsageError(problem);
  if (!write_error.empty()) throw ReportWriteError("--report: " + write_error);
}

}  // namespace spread::cli
