#include "capi/cpp/capi_spread_predictor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "spread/spread.h"

namespace spread::firmware {

CapiSpreadPredictor::CapiSpreadPredictor(const std::string& table_path, double cv_target_percent)
    : cv_target_percent_(cv_target_percent) {
  if (!(cv_target_percent > 0.0) || !std::isfinite(cv_target_percent)) {
    throw std::invalid_argument("CapiSpreadPredictor: CV target must be > 0 %");
  }
  const spread_status status = spread_open(table_path.c_str(), &tables_);
  if (status != SPREAD_OK) {
    throw std::runtime_error("spread tables '" + table_path + "': " + spread_status_str(status));
  }
  list_materials("spread tables '" + table_path + "'");
}

CapiSpreadPredictor::CapiSpreadPredictor(spread_tables* borrowed, double cv_target_percent)
    : tables_(borrowed), owned_(false), cv_target_percent_(cv_target_percent) {
  if (!(cv_target_percent > 0.0) || !std::isfinite(cv_target_percent)) {
    throw std::invalid_argument("CapiSpreadPredictor: CV target must be > 0 %");
  }
  if (borrowed == nullptr) throw std::invalid_argument("CapiSpreadPredictor: no tables handle");
  list_materials("spread tables");
}

void CapiSpreadPredictor::list_materials(const std::string& where) {
  std::int32_t count = 0;
  spread_status status = spread_material_count(tables_, &count);
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
    if (owned_) spread_close(tables_);
    throw std::runtime_error(where + ": listing materials: " + spread_status_str(status));
  }
}

CapiSpreadPredictor::~CapiSpreadPredictor() {
  if (owned_) spread_close(tables_);
}

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

PredictionOutcome CapiSpreadPredictor::narrow_side(const NarrowingRequest& request, std::span<const SideStrip> strips,
                                                   std::span<double> strip_rate_percent, SideNarrowing& out) {
  const int i = find(request.material);
  if (i < 0) return PredictionOutcome::kUnknownMaterial;
  if (strip_rate_percent.size() < strips.size()) return PredictionOutcome::kFailed;
  const double half_m = 0.5 * request.bout_width_m;
  if (!(request.edge_line_m > 0.0 && request.edge_line_m <= half_m)) return PredictionOutcome::kOutOfRange;
  const int side = request.side;
  spread_prediction_def def = spread_prediction_def_default();
  def.material = names_[static_cast<std::size_t>(i)].c_str();
  def.rpm = request.rpm;
  def.cv_target_percent = cv_target_percent_;
  def.bout_width_m = request.bout_width_m;
  def.wind_m_s[0] = request.wind_x_m_s;
  def.wind_m_s[1] = request.wind_y_m_s;
  spread_edge_def edge = spread_edge_def_default();
  edge.kind = request.field_edge ? SPREAD_EDGE_FIELD : SPREAD_EDGE_BORDER;
  edge.side = side;
  edge.gap_m = half_m - request.edge_line_m;
  edge.max_beyond_percent = request.max_beyond_percent;
  spread_edge_setting setting{};
  spread_edge_result result{};
  // The profile's tray count is known only from a first answer: ask without the buffer, then with it.
  spread_status status = spread_find_edge_setting(tables_, &def, &edge, &setting, &result, nullptr, 0);
  if (status == SPREAD_OK) {
    // The same request again would search again: read the profile at the setting found instead.
    profile_rate_percent_.resize(static_cast<std::size_t>(result.tray_count));
    spread_prediction_def at = def;
    at.disc_rpm[side] = setting.disc_rpm;
    at.disc_drop_point_turn_rad[side] = setting.disc_drop_point_turn_rad;
    at.disc_drop_point_turn_rad[1 - side] = setting.field_side_drop_point_turn_rad;
    spread_edge_def with_flow = edge;
    with_flow.flow_fraction = setting.flow_fraction;
    status = spread_predict_edge(tables_, &at, &with_flow, &result, profile_rate_percent_.data(),
                                 profile_rate_percent_.size());
  }
  if (status == SPREAD_ERROR_RPM_OUTSIDE_TABLE) return PredictionOutcome::kOutOfRange;
  if (status != SPREAD_OK) {
    last_error_ = spread_status_str(status);
    // A one-disc machine has no side to narrow.
    return status == SPREAD_ERROR_OUT_OF_RANGE ? PredictionOutcome::kUnsupported : PredictionOutcome::kFailed;
  }
  out.rpm = setting.disc_rpm;
  out.drop_point_turn_rad = setting.disc_drop_point_turn_rad;
  out.flow_fraction = setting.flow_fraction;
  out.other_drop_point_turn_rad = setting.field_side_drop_point_turn_rad;
  out.mass_beyond_percent = result.mass_beyond_percent;
  out.meets = result.meets != 0;
  // Tray k covers [left + k w, left + (k+1) w] in x from the tramline towards the edge; each strip's mean
  // is the overlap-weighted average of the trays it covers.
  for (std::size_t s = 0; s < strips.size(); ++s) {
    double sum = 0.0;
    for (int k = 0; k < result.tray_count; ++k) {
      const double lo = result.tray_left_edge_m + k * result.tray_width_m, hi = lo + result.tray_width_m;
      const double overlap = std::min(hi, strips[s].to_m) - std::max(lo, strips[s].from_m);
      if (overlap > 0.0) sum += overlap * profile_rate_percent_[static_cast<std::size_t>(k)];
    }
    const double length = strips[s].to_m - strips[s].from_m;
    strip_rate_percent[s] = length > 0.0 ? sum / length : 0.0;
  }
  return PredictionOutcome::kOk;
}

PredictionOutcome CapiSpreadPredictor::compensate_wind(std::string_view material, double rpm, double bout_width_m,
                                                       double wind_x_m_s, double wind_y_m_s,
                                                       std::array<SideNarrowing, 2>& out) {
  const int i = find(material);
  if (i < 0) return PredictionOutcome::kUnknownMaterial;
  spread_prediction_def def = spread_prediction_def_default();
  def.material = names_[static_cast<std::size_t>(i)].c_str();
  def.rpm = rpm;
  def.cv_target_percent = cv_target_percent_;
  def.bout_width_m = bout_width_m;
  def.wind_m_s[0] = wind_x_m_s;
  def.wind_m_s[1] = wind_y_m_s;
  spread_prediction result{};
  const spread_status status = spread_compensate_wind(tables_, &def, &result, nullptr, 0);
  if (status == SPREAD_ERROR_UNKNOWN_MATERIAL) return PredictionOutcome::kUnknownMaterial;
  if (status == SPREAD_ERROR_RPM_OUTSIDE_TABLE) return PredictionOutcome::kOutOfRange;
  if (status != SPREAD_OK) {
    last_error_ = spread_status_str(status);
    return status == SPREAD_ERROR_OUT_OF_RANGE ? PredictionOutcome::kUnsupported : PredictionOutcome::kFailed;
  }
  for (std::size_t d = 0; d < 2; ++d) {
    out[d] = SideNarrowing{};
    out[d].rpm = result.disc_rpm[d];
    out[d].drop_point_turn_rad = result.disc_drop_point_turn_rad[d];
    out[d].flow_fraction = 1.0;
    out[d].meets = result.cv_percent <= cv_target_percent_;
  }
  return PredictionOutcome::kOk;
}

}  // namespace spread::firmware
