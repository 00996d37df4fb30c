// spread_predict_edge and spread_find_edge_setting: the C definitions → the field's PredictionRequest,
// the edge-side disc's EdgeSetting (and the other disc's drop point) and an EdgeRequest →
// predict::edge_profile or predict::find_edge_setting → the C result and the rate per tray.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <string_view>

#include "capi/src/abi_layout.hpp"
#include "capi/src/error_detail.hpp"
#include "capi/src/prediction_request.hpp"
#include "capi/src/tables_handle.hpp"
#include "libspread/analysis/predict/edge_spreading.hpp"

namespace {

using spread::capi::fail;
namespace pr = spread::predict;

// The edge definition's domain, each field named (edge_spreading.hpp's rules).
spread_status check_edge(const char* function, const spread_edge_def& e, double bout_width_m) {
  if (e.kind != SPREAD_EDGE_BORDER && e.kind != SPREAD_EDGE_FIELD) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: edge->kind %u is neither SPREAD_EDGE_BORDER nor SPREAD_EDGE_FIELD", function,
                static_cast<unsigned>(e.kind));
  }
  if (e.side != 0 && e.side != 1) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: edge->side %d is neither 0 (left) nor 1 (right)", function,
                static_cast<int>(e.side));
  }
  const struct {
    const char* name;
    double value, low, high;
    bool low_open;
  } ranges[] = {{"gap_m", e.gap_m, 0.0, 0.5 * bout_width_m, false},
                {"flow_fraction", e.flow_fraction, 0.0, pr::kEdgeMaxFlow, false},
                {"max_beyond_percent", e.max_beyond_percent, 0.0, 100.0, true},
                {"tolerance_percent", e.tolerance_percent, 0.0, 100.0, true},
                {"min_edge_rate_percent", e.min_edge_rate_percent, 0.0, 100.0, true}};
  for (const auto& r : ranges) {
    if (!std::isfinite(r.value)) {
      return fail(SPREAD_ERROR_NOT_FINITE, "%s: edge->%s is %g", function, r.name, r.value);
    }
    const bool above_low = r.low_open ? r.value > r.low : r.value >= r.low;
    // gap_m: below half the bout width (the edge line must lie beyond the tramline).
    const bool below_high = r.name == std::string_view("gap_m") ? r.value < r.high : r.value <= r.high;
    if (!above_low || !below_high) {
      return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: edge->%s %g outside %s%g, %g%s", function, r.name, r.value,
                  r.low_open ? "(" : "[", r.low, r.high, r.name == std::string_view("gap_m") ? ")" : "]");
    }
  }
  return SPREAD_OK;
}

// The checks both functions share: the handle, the definitions' versions and domains (the field's setting
// refused as spread_predict refuses it, with the same status and the field named), a two-disc machine and a
// bout width. On success `field` is the field's request: both discs alike at rpm and drop_point_turn_rad.
spread_status check_common(const char* function, spread_tables* tables, const spread_prediction_def* def,
                           const spread_edge_def* edge, const void* result, pr::PredictionRequest& field) {
  if (tables == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: the handle is NULL", function);
  if (!spread::capi::live(tables)) {
    return fail(SPREAD_ERROR_BAD_HANDLE, "%s: not a live spread_tables handle (closed?)", function);
  }
  if (def == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: def is NULL", function);
  if (edge == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: edge is NULL", function);
  if (result == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: result is NULL", function);
  if (const spread_status s = spread::capi::read_request(function, *def, field); s != SPREAD_OK) return s;
  if (def->struct_size < spread::capi::kPredictionDefV4Size) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: def->struct_size %u older than 0.4 (%zu): no per-disc fields", function,
                static_cast<unsigned>(def->struct_size), spread::capi::kPredictionDefV4Size);
  }
  if (edge->struct_size < sizeof(spread_edge_def)) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: edge->struct_size %u is smaller than the first published %zu", function,
                static_cast<unsigned>(edge->struct_size), sizeof(spread_edge_def));
  }
  // The field's setting: each disc's own fields belong to the last pass.
  for (std::size_t d = 0; d < 2; ++d) {
    field.disc_rpm[d] = std::numeric_limits<double>::quiet_NaN();
    field.disc_drop_point_turn_rad[d] = std::numeric_limits<double>::quiet_NaN();
  }
  const pr::Predictor& predictor = tables->predictor;
  if (const spread_status s = spread::capi::check_request(function, predictor, *def, field); s != SPREAD_OK) return s;
  if (predictor.machine().disc_count < 2) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: the table's machine has one disc (no edge-side disc to set apart)",
                function);
  }
  if (!(def->bout_width_m > 0.0)) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE,
                "%s: def->bout_width_m %g: the bout width (the last tramline lies half of it from the field edge) "
                "must be > 0",
                function, def->bout_width_m);
  }
  return check_edge(function, *edge, def->bout_width_m);
}

pr::EdgeRequest edge_request(const spread_edge_def& edge) {
  pr::EdgeRequest request;
  request.kind = edge.kind == SPREAD_EDGE_BORDER ? pr::EdgeKind::kBorder : pr::EdgeKind::kEdge;
  request.side = edge.side;
  request.gap_m = edge.gap_m;
  request.max_beyond_fraction = edge.max_beyond_percent / 100.0;
  request.rate_tolerance = edge.tolerance_percent / 100.0;
  request.min_edge_rate = edge.min_edge_rate_percent / 100.0;
  return request;
}

// The profile into the C result and the rate buffer (percent).
spread_status write_profile(const char* function, const pr::EdgeProfile& profile, spread_edge_result* result,
                            double* rate_percent, size_t rate_capacity) {
  if (rate_percent != nullptr && rate_capacity < profile.rate.size()) {
    return fail(SPREAD_ERROR_BUFFER_TOO_SMALL, "%s: rate buffer of %zu values, the profile has %zu trays", function,
                rate_capacity, profile.rate.size());
  }
  result->edge_line_m = profile.edge_line_m;
  result->mass_beyond_percent = 100.0 * profile.mass_beyond_fraction;
  result->max_rate_inside_percent = 100.0 * profile.max_rate_inside;
  result->rate_at_edge_percent = 100.0 * profile.rate_at_edge;
  result->over_limit_percent = 100.0 * profile.over_limit;
  result->under_limit_percent = 100.0 * profile.under_limit;
  result->missing_inside_m = profile.missing_inside_m;
  result->meets = profile.meets ? 1 : 0;
  result->tray_count = profile.trays.tray_count;
  result->tray_width_m = profile.trays.tray_width_m;
  result->tray_left_edge_m = profile.trays.left_edge_m();
  if (rate_percent != nullptr) {
    std::transform(profile.rate.begin(), profile.rate.end(), rate_percent, [](double r) { return 100.0 * r; });
  }
  return SPREAD_OK;
}

}  // namespace

extern "C" spread_status spread_predict_edge(spread_tables* tables, const spread_prediction_def* def,
                                             const spread_edge_def* edge, spread_edge_result* result,
                                             double* rate_percent, size_t rate_capacity) {
  constexpr const char* kFunction = "spread_predict_edge";
  pr::PredictionRequest field;
  if (const spread_status s = check_common(kFunction, tables, def, edge, result, field); s != SPREAD_OK) return s;
  const int side = edge->side, other = 1 - side;
  if (!std::isnan(def->disc_rpm[other])) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE,
                "%s: disc_rpm[%d] %g set: the disc away from the edge runs at the field's speed (rpm; only its drop "
                "point may change on the last pass)",
                kFunction, other, def->disc_rpm[other]);
  }
  try {
    pr::EdgeSetting setting;
    setting.disc.rpm = std::isnan(def->disc_rpm[side]) ? def->rpm : def->disc_rpm[side];
    setting.disc.drop_point_turn_rad =
        std::isnan(def->disc_drop_point_turn_rad[side]) ? def->drop_point_turn_rad : def->disc_drop_point_turn_rad[side];
    setting.flow_fraction = edge->flow_fraction;
    setting.field_side_drop_point_turn_rad = def->disc_drop_point_turn_rad[other];  // NaN: the field's
    // The last pass as the library predicts it (each disc its own setting), refused as spread_predict
    // refuses it: only the disc fields of the definition can be at fault here, the field's passed above.
    pr::PredictionRequest pass = field;
    pass.rpm = 0.0;
    pass.drop_point_turn_rad = 0.0;
    pass.disc_rpm[static_cast<std::size_t>(side)] = setting.disc.rpm;
    pass.disc_drop_point_turn_rad[static_cast<std::size_t>(side)] = setting.disc.drop_point_turn_rad;
    pass.disc_rpm[static_cast<std::size_t>(other)] = def->rpm;
    pass.disc_drop_point_turn_rad[static_cast<std::size_t>(other)] =
        std::isnan(def->disc_drop_point_turn_rad[other]) ? def->drop_point_turn_rad : def->disc_drop_point_turn_rad[other];
    if (const spread_status s = spread::capi::check_request(kFunction, tables->predictor, *def, pass); s != SPREAD_OK) {
      return s;
    }
    pr::EdgeProfile profile(&tables->memory);
    const pr::PredictStatus status =
        pr::edge_profile(tables->predictor, field, edge_request(*edge), setting, profile, &tables->memory);
    if (status != pr::PredictStatus::kOk) {
      // Every refusal is found above; this is the library disagreeing with those checks.
      return fail(SPREAD_ERROR_INTERNAL, "%s: the edge profile refused a checked request (%s)", kFunction,
                  pr::to_string(status));
    }
    return write_profile(kFunction, profile, result, rate_percent, rate_capacity);
  } catch (const std::bad_alloc&) {
    return fail(SPREAD_ERROR_OUT_OF_MEMORY, "%s: out of memory", kFunction);
  } catch (const std::exception& e) {
    return fail(SPREAD_ERROR_INTERNAL, "%s: %.400s", kFunction, e.what());
  }
}

namespace {

// spread_find_edge_setting and spread_find_edge_setting_within: at most `max_predictions` (INT_MAX: the
// whole search); *finished (when not NULL) whether the search ran to its end.
spread_status find_edge_setting(const char* kFunction, spread_tables* tables, const spread_prediction_def* def,
                                const spread_edge_def* edge, int max_predictions, spread_edge_setting* setting,
                                spread_edge_result* result, double* rate_percent, size_t rate_capacity,
                                int32_t* finished) {
  if (setting == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: setting is NULL", kFunction);
  pr::PredictionRequest field;
  if (const spread_status s = check_common(kFunction, tables, def, edge, result, field); s != SPREAD_OK) return s;
  // The search sets each disc apart itself: a value given here would be dropped.
  for (int disc = 0; disc < 2; ++disc) {
    const struct {
      const char* name;
      double value;
    } own[] = {{"disc_rpm", def->disc_rpm[disc]}, {"disc_drop_point_turn_rad", def->disc_drop_point_turn_rad[disc]}};
    for (const auto& f : own) {
      if (!std::isnan(f.value)) {
        return fail(SPREAD_ERROR_OUT_OF_RANGE,
                    "%s: %s[%d] %g set: the search chooses each disc's setting on the last pass (give the field's in "
                    "rpm and drop_point_turn_rad, leave this NaN)",
                    kFunction, f.name, disc, f.value);
      }
    }
  }
  if (edge->flow_fraction != 1.0) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE,
                "%s: edge->flow_fraction %g set: the search chooses the edge-side disc's flow (leave it at 1)",
                kFunction, edge->flow_fraction);
  }
  try {
    pr::EdgeRequest request = edge_request(*edge);
    request.max_predictions = max_predictions;
    const pr::EdgeResult found = pr::find_edge_setting(tables->predictor, field, request, &tables->memory);
    if (found.status != pr::PredictStatus::kOk) {
      // Every refusal is found above; this is the library disagreeing with those checks.
      return fail(SPREAD_ERROR_INTERNAL, "%s: the search refused a checked request (%s)", kFunction,
                  pr::to_string(found.status));
    }
    if (const spread_status s = write_profile(kFunction, found.profile, result, rate_percent, rate_capacity); s != SPREAD_OK) {
      return s;
    }
    setting->disc_rpm = found.setting.disc.rpm;
    setting->disc_drop_point_turn_rad = found.setting.disc.drop_point_turn_rad;
    setting->flow_fraction = found.setting.flow_fraction;
    setting->field_side_drop_point_turn_rad = found.setting.field_side_drop_point_turn_rad;
    setting->predictions = found.predictions;
    setting->reserved = 0;
    if (finished != nullptr) *finished = found.finished ? 1 : 0;
    return SPREAD_OK;
  } catch (const std::bad_alloc&) {
    return fail(SPREAD_ERROR_OUT_OF_MEMORY, "%s: out of memory", kFunction);
  } catch (const std::exception& e) {
    return fail(SPREAD_ERROR_INTERNAL, "%s: %.400s", kFunction, e.what());
  }
}

}  // namespace

extern "C" spread_status spread_find_edge_setting(spread_tables* tables, const spread_prediction_def* def,
                                                  const spread_edge_def* edge, spread_edge_setting* setting,
                                                  spread_edge_result* result, double* rate_percent,
                                                  size_t rate_capacity) {
  return find_edge_setting("spread_find_edge_setting", tables, def, edge, std::numeric_limits<int>::max(), setting,
                           result, rate_percent, rate_capacity, nullptr);
}

extern "C" spread_status spread_find_edge_setting_within(spread_tables* tables, const spread_prediction_def* def,
                                                         const spread_edge_def* edge, int32_t max_predictions,
                                                         spread_edge_setting* setting, spread_edge_result* result,
                                                         double* rate_percent, size_t rate_capacity,
                                                         int32_t* out_finished) {
  constexpr const char* kFunction = "spread_find_edge_setting_within";
  if (out_finished == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: out_finished is NULL", kFunction);
  if (max_predictions != 0 && max_predictions < pr::kEdgeMinPredictions) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE,
                "%s: max_predictions %d below the %d every search makes (the field's, the normal pass, the "
                "answer's profile); 0: no limit",
                kFunction, static_cast<int>(max_predictions), pr::kEdgeMinPredictions);
  }
  return find_edge_setting(kFunction, tables, def, edge,
                           max_predictions == 0 ? std::numeric_limits<int>::max() : static_cast<int>(max_predictions),
                           setting, result, rate_percent, rate_capacity, out_finished);
}
