#pragma once
// --report OUT.pdf and the options only the report and the rate check use, shared by `calibrate tray`,
// `calibrate pattern`, `predict` and `chart` (docs/field-calibration.md, "Report"): the same names,
// checks and wording in every command.
//
// A --report whose folder does not exist is named before any work, but the command still computes and
// prints its text (or JSON) report — a technician in the field keeps the numbers — and then exits 2.
// A PDF that fails later (a full disc) leaves the report printed and exits 1, as --plot does.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/analysis/calibration/cv_verdict.hpp"
#include "libspread/core/error.hpp"
#include "libspread/analysis/plot/report_pdf.hpp"

namespace spread::cli {

struct ReportArgs {
  std::string path;                                                    // --report; "" = none
  double speed_km_h = std::numeric_limits<double>::quiet_NaN();        // --speed; NaN = not given
  double tray_area_m2 = std::numeric_limits<double>::quiet_NaN();      // --tray-area; NaN = no rate
  double set_rate_kg_ha = std::numeric_limits<double>::quiet_NaN();    // --rate-kg-ha; NaN = no check
};

// Adds --report and --speed; with `rate` also --tray-area and --rate-kg-ha (tray tests only: a prediction
// has no caught mass).
void add_report_args(CLI::App& sub, ReportArgs& args, bool rate);

// The checks made before any work. Throws std::invalid_argument naming the option for a value out of
// range, --rate-kg-ha without --tray-area, or a malformed SOURCE_DATE_EPOCH; returns the problem with
// the --report path (its folder missing or not a folder; "" when fine or no report is asked), which the
// command reports after its text and exits 2 with.
std::string check_report_args(const ReportArgs& args);

// The time the report is stamped with (the clock, or SOURCE_DATE_EPOCH).
std::int64_t report_time_s();

// The command line as typed (for the report's footer); main() records it.
void remember_command_line(int argc, char** argv);
std::string command_line();

// The rate caught in a tray test at `bout_width_m` (whole trays) and its check, when --tray-area is
// given and the bout width is > 0; nullopt otherwise.
std::optional<plot::ReportRate> report_rate(const ReportArgs& args, double mass_per_pass_kg, double bout_width_m,
                                            double tray_width_m);
nlohmann::json rate_json(const std::optional<plot::ReportRate>& rate);
// The --report outcome in a command's JSON: "report" (the path written, null when it was not) when a
// report was asked, and "report_error" (the folder problem, else the write error) when there was one.
void add_report_outcome(nlohmann::json& out, const ReportArgs& args, const std::string& problem,
                        const std::string& write_error);
// After the report is printed: throws ReportUsageError for the folder problem (exit 2), else
// ReportWriteError for the write error (exit 1); nothing when both are empty.
void throw_report_outcome(const std::string& problem, const std::string& write_error);
// The text report's lines for it (none without a rate).
std::vector<std::string> rate_lines(const std::optional<plot::ReportRate>& rate);

// After the text or JSON report: the folder problem found before the work (exit 2), or the error of
// writing the PDF (exit 1). Thrown as ReportUsageError / ReportWriteError; the commands map them.
class ReportUsageError : public Error {
 public:
  explicit ReportUsageError(const std::string& message) : Error(ErrorKind::kArgument, "--report", message) {}
};
class ReportWriteError : public Error {
 public:
  explicit ReportWriteError(const std::string& message) : Error(ErrorKind::kIo, "--report", message) {}
};

}  // namespace spread::cli
