#include "firmware_sim/ecu/capi_spread_predictor.hpp"

#include <cmath>
#include <stdexcept>

#include "spread/spread.h"

namespace spread::firmware {

CapiSpreadPredictor::CapiSpreadPredictor(const std::string& table_path, double cv_target_percent)
    : cv_target_percent_(cv_target_percent) {
  if (!(cv_target_percent > 0.0) || !std::isfinite(cv_target_percent)) {
    throw std::invalid_argument("CapiSpreadPredictor: CV target must be > 0 %");
  }
  spread_status status = spread_open(table_path.c_str(), &tables_);
  if (status != SPREAD_OK) {
    throw std::runtime_error("spread tables '" + table_path + "': " + spread_status_str(status));
  }
  std::int32_t count = 0;
  status = spread_material_count(tables_, &count);
  for (std::int32_t i = 0; status == SPREAD_OK && i < count; ++i) {
    const char* name = nullptr;
    RpmRange range;
    status = spread_material_name(tables_, i, &name);
    if (status == SPREAD_OK) status = spread_material_rpm_range(tables_, i, &range.min_rpm, &range.max_rpm);
    if (status == SPREAD_OK) {
      names_.emplace_back(name);
      ranges_.push_back(range);
    }
  }
  if (status != SPREAD_OK) {
    spread_close(tables_);
    throw std::runtime_error("spread tables '" + table_path + "': listing materials: " + spread_status_str(status));
  }
}

CapiSpreadPredictor::~CapiSpreadPredictor() { spread_close(tables_); }

int CapiSpreadPredictor::find(std::string_view material) const {
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (names_[i] == material) return static_cast<int>(i);
  }
  return -1;
}

bool CapiSpreadPredictor::has_material(std::string_view material) const { return find(material) >= 0; }

RpmRange CapiSpreadPredictor::rpm_range(std::string_view material) const {
  const int i = find(material);
  return i < 0 ? RpmRange{} : ranges_[static_cast<std::size_t>(i)];
}

PredictionOutcome CapiSpreadPredictor::predict(std::string_view material, double rpm, double bout_width_m,
                                               SpreadPrediction& out) {
  const int i = find(material);
  if (i < 0) return PredictionOutcome::kUnknownMaterial;
  spread_prediction_def def = spread_prediction_def_default();
  def.material = names_[static_cast<std::size_t>(i)].c_str();  // NUL-terminated copy owned by us
  def.rpm = rpm;
  def.cv_target_percent = cv_target_percent_;
  def.bout_width_m = bout_width_m;
  spread_prediction result{};
  const spread_status status = spread_predict(tables_, &def, &result, nullptr, 0);
  if (status == SPREAD_OK) {
    // Spreaders are driven to-and-fro (EN 13739's default overlap): its working width is the one used.
    out.throw_width_m = result.throw_width_m;
    out.effective_width_m = result.working_width_to_and_fro_m;
    out.first_band_width_m = result.first_band_width_to_and_fro_m;
    out.cv_percent = result.cv_percent;
    out.throw_width_se_m = result.throw_width_se_m;
    out.effective_width_se_m = result.working_width_to_and_fro_se_m;
    out.cv_se_percent = result.cv_se_percent;
    return PredictionOutcome::kOk;
  }
  if (status == SPREAD_ERROR_UNKNOWN_MATERIAL) return PredictionOutcome::kUnknownMaterial;
  if (status == SPREAD_ERROR_RPM_OUTSIDE_TABLE) return PredictionOutcome::kOutOfRange;
  last_error_ = spread_status_str(status);  // static string: assignment within capacity after the first
  return PredictionOutcome::kFailed;
}

}  // namespace spread::firmware
