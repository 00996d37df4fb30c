#pragma once
// The guidance `spread predict` and `spread calibrate pattern` print when the predicted CV at the bout
// width is above the target: each setting the table predicts, moved on its own, with its predicted CV
// (libspread/analysis/predict/setting_adjustment.hpp), as text lines (also the PDF report's notes) and JSON.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/analysis/predict/setting_adjustment.hpp"

namespace spread::cli {

struct SettingGuidance {
  std::optional<predict::SettingAdjustments> adjustments;  // none: the CV meets the target
  std::vector<std::string> lines;  // the terminal's
  std::vector<std::string> notes;  // the page's: the same without the commands to run
};

// With the table's Predictor and the present settings `request` (bout width > 0): nothing when the
// predicted to-and-fro CV there meets the request's target, else the adjustments. Throws as
// predict::setting_adjustments.
SettingGuidance setting_guidance(predict::Predictor& predictor, const predict::PredictionRequest& request);

// `adjustments` of a command's JSON: a list, or null when there is none.
nlohmann::json setting_guidance_json(const SettingGuidance& guidance);
// `adjusted_from` of a command's JSON: the predicted present CV the adjustments start from, or null.
nlohmann::json setting_guidance_present_json(const SettingGuidance& guidance);

}  // namespace spread::cli
