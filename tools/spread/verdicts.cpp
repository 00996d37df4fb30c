#include "tools/spread/verdicts.hpp"

#include <cmath>
#include <cstdio>

#include "tools/spread/number_format.hpp"

namespace spread::cli {

Verdict cv_verdict(const std::string& what, const calibration::CvVerdict& verdict) {
  using Level = plot::ReportVerdict::Level;
  Verdict v;
  v.kind = "cv";
  switch (verdict.verdict) {
    case calibration::Verdict::kPass: v.shown.level = Level::kPass; break;
    case calibration::Verdict::kMarginal: v.shown.level = Level::kMarginal; break;
    case calibration::Verdict::kFail: v.shown.level = Level::kFail; break;
    case calibration::Verdict::kNoCv: v.shown.level = Level::kNone; break;
  }
  v.shown.word = calibration::verdict_word(verdict.verdict);
  v.shown.text = what + ": " + calibration::verdict_detail(verdict);
  v.numbers = cv_verdict_json(verdict);
  return v;
}

std::optional<Verdict> rate_verdict(const std::optional<plot::ReportRate>& rate) {
  if (!rate || std::isnan(rate->set_rate_kg_ha)) return std::nullopt;
  Verdict v;
  v.kind = "rate";
  v.shown.level = rate->pass ? plot::ReportVerdict::Level::kPass : plot::ReportVerdict::Level::kFail;
  v.shown.word = rate->pass ? "PASS" : "FAIL";
  v.shown.text = "Rate (EN 13739-2): the trays caught " + format("%.1f kg/ha", rate->rate_kg_ha) + ", " +
                 format("%.1f %%", rate->caught_percent) + " of the set " + format("%.1f kg/ha", rate->set_rate_kg_ha) +
                 " (" + format("%g", rate->lowest_percent) + "-" + format("%g %%", rate->highest_percent) + " required)";
  v.numbers = {{"rate_kg_ha", rate->rate_kg_ha},
               {"caught_percent", rate->caught_percent},
               {"set_rate_kg_ha", rate->set_rate_kg_ha},
               {"lowest_percent", rate->lowest_percent},
               {"highest_percent", rate->highest_percent}};
  return v;
}

nlohmann::json cv_verdict_json(const calibration::CvVerdict& verdict) {
  const auto percent_or_null = [](double v) {
    return std::isfinite(v) ? nlohmann::json(100.0 * v) : nlohmann::json(nullptr);
  };
  return {{"verdict", calibration::verdict_key(verdict.verdict)},
          {"cv_percent", percent_or_null(verdict.cv)},
          {"interval_percent", verdict.has_interval()
                                   ? nlohmann::json::array({percent_or_null(verdict.low), percent_or_null(verdict.high)})
                                   : nlohmann::json(nullptr)},
          {"confidence_percent", verdict.has_interval() ? nlohmann::json(95) : nlohmann::json(nullptr)},
          {"cv_target_percent", 100.0 * verdict.target}};
}

const char* verdict_key(plot::ReportVerdict::Level level) {
  switch (level) {
    case plot::ReportVerdict::Level::kPass: return "pass";
    case plot::ReportVerdict::Level::kMarginal: return "marginal";
    case plot::ReportVerdict::Level::kFail: return "fail";
    case plot::ReportVerdict::Level::kNone: return "none";
  }
  return "none";
}

nlohmann::json verdicts_json(const std::vector<Verdict>& verdicts) {
  nlohmann::json list = nlohmann::json::array();
  for (const Verdict& v : verdicts) {
    nlohmann::json entry = v.numbers.is_object() ? v.numbers : nlohmann::json::object();
    entry["kind"] = v.kind;
    entry["verdict"] = verdict_key(v.shown.level);
    entry["word"] = v.shown.word;
    entry["text"] = v.shown.text;
    list.push_back(entry);
  }
  return list;
}

void print_verdicts(const std::vector<Verdict>& verdicts) {
  for (const Verdict& v : verdicts) std::printf("%-8s  %s\n", v.shown.word.c_str(), v.shown.text.c_str());
}

std::vector<plot::ReportVerdict> page_verdicts(const std::vector<Verdict>& verdicts) {
  std::vector<plot::ReportVerdict> shown;
  for (const Verdict& v : verdicts) shown.push_back(v.shown);
  return shown;
}

}  // namespace spread::cli
