#pragma once
// A result's verdicts — the CV at the bout against the target, EN 13739-2's rate check, a chart's widths —
// computed once and then written alike to the terminal, --json and the report page, so the three cannot
// disagree (the page once said PASS where the terminal printed no verdict and the JSON had none).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/analysis/calibration/cv_verdict.hpp"
#include "libspread/analysis/plot/report_pdf.hpp"

namespace spread::cli {

struct Verdict {
  std::string kind;            // "cv", "rate", "widths"
  plot::ReportVerdict shown;   // its word, colour and text, as every output prints them
  nlohmann::json numbers;      // the numbers its text states (per cent, metres, kg/ha), for --json
};

// The CV `what` names against its target with its 95 % interval (calibration/cv_verdict.hpp).
Verdict cv_verdict(const std::string& what, const calibration::CvVerdict& verdict);
// EN 13739-2's rate check, when the rate was checked (a set rate given).
std::optional<Verdict> rate_verdict(const std::optional<plot::ReportRate>& rate);
// {"verdict": "fail", "cv_percent", "interval_percent": [low, high] or null, "confidence_percent",
// "cv_target_percent"}.
nlohmann::json cv_verdict_json(const calibration::CvVerdict& verdict);

// "pass", "marginal", "fail", "none".
const char* verdict_key(plot::ReportVerdict::Level level);
// [{"kind", "verdict", "word", "text", ...its numbers}], in the page's order.
nlohmann::json verdicts_json(const std::vector<Verdict>& verdicts);
// One line each on stdout, the word first as on the page: "MARGINAL  CV at the 3.50 m bout, ...".
void print_verdicts(const std::vector<Verdict>& verdicts);
// The page's first lines.
std::vector<plot::ReportVerdict> page_verdicts(const std::vector<Verdict>& verdicts);

}  // namespace spread::cli
