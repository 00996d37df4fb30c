// spread_predict: C definition → predict::PredictionRequest → Predictor → C result. No allocation:
// the material name is viewed in place, the workspace belongs to the handle.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <numbers>
#include <string_view>

#include "capi/src/error_detail.hpp"
#include "capi/src/fault_seam.hpp"
#include "capi/src/predict_status.hpp"
#include "capi/src/prediction_request.hpp"
#include "capi/src/tables_handle.hpp"
#include "libspread/analysis/predict/wind_compensation.hpp"

// The C bits are passed through unchanged, so they must be the effect registry's. SPREAD_EFFECT_ALL is the
// OR of the header's bits: a flight row without its bit (or a bit left out of it) fails here. That each
// SPREAD_EFFECT_<NAME> is its row's bit: EffectRegistry.CHeaderDefinesEveryFlightBit.
static_assert(SPREAD_EFFECT_ALL == spread::effect::kFlightEffects,
              "spread.h: SPREAD_EFFECT_ALL must be the OR of one SPREAD_EFFECT_<NAME> per flight row of the effect "
              "registry");
static_assert(SPREAD_EFFECTS_AS_TABLE == spread::predict::kTableEffects);
static_assert((SPREAD_EFFECTS_AS_TABLE & SPREAD_EFFECT_ALL) == 0);
static_assert(SPREAD_MAX_BANDS == spread::predict::kMaxBands);

namespace {

using spread::capi::status_of;

void copy_band(const spread::predict::PredictedBand& b, spread_band& out) {
  out.lower_m = b.lower_m;
  out.upper_m = b.upper_m;
  out.upper_se_m = b.upper_se_m;
  out.bout_width_m = b.bout_width_m;
  out.cv_percent = 100.0 * b.cv;
  out.cv_se_percent = 100.0 * b.cv_se;
  out.lowest_cv_percent = 100.0 * b.lowest_cv;
  out.lowest_cv_se_percent = 100.0 * b.lowest_cv_se;
  out.lowest_cv_bout_width_m = b.lowest_cv_bout_width_m;
  out.established = b.established ? 1 : 0;
  out.limited_by_layout = b.limited_by_layout ? 1 : 0;
}

void copy_result(const spread::predict::Prediction& p, bool v2, bool v3, bool v4, spread_prediction& r) {
  r.throw_width_m = p.throw_width_m;
  r.working_width_to_and_fro_m = p.working_width_to_and_fro_m;
  r.working_width_racetrack_m = p.working_width_racetrack_m;
  r.bout_width_m = p.bout_width_m;
  r.cv_percent = 100.0 * p.cv_to_and_fro;
  r.cv_racetrack_percent = 100.0 * p.cv_racetrack;
  r.mean_radius_m = p.mean_radius_m;
  r.radial_width_m = p.radial_width_m;
  r.disc_height_m = p.disc_height_m;
  r.lost_mass_fraction = p.lost_mass_fraction;
  r.tray_count = p.trays.tray_count;
  r.tray_width_m = p.trays.tray_width_m;
  r.tray_left_edge_m = p.trays.left_edge_m();
  r.flights = p.flights;
  if (!v2) return;  // a caller of the first release has no room for the rest
  r.sample_count = static_cast<int32_t>(std::min<std::size_t>(p.sample_count, INT32_MAX));
  r.throw_width_se_m = p.throw_width_se_m;
  r.working_width_to_and_fro_se_m = p.working_width_to_and_fro_se_m;
  r.working_width_racetrack_se_m = p.working_width_racetrack_se_m;
  r.cv_se_percent = 100.0 * p.cv_to_and_fro_se;
  r.cv_racetrack_se_percent = 100.0 * p.cv_racetrack_se;
  r.cv_crossings_to_and_fro = p.cv_crossings_to_and_fro;
  r.cv_crossings_racetrack = p.cv_crossings_racetrack;
  r.effects = p.effects;
  r.kernel_half_width_m = p.kernel_half_width_m;
  if (!v3) return;
  r.band_count_to_and_fro = p.band_count_to_and_fro;
  r.band_count_racetrack = p.band_count_racetrack;
  r.headline_band_to_and_fro = p.headline_band_to_and_fro;
  r.headline_band_racetrack = p.headline_band_racetrack;
  r.first_band_width_to_and_fro_m = p.first_band_width_to_and_fro_m;
  r.first_band_width_racetrack_m = p.first_band_width_racetrack_m;
  // Unused slots are zeroed: a caller never reads stale bands of an earlier prediction.
  for (int b = 0; b < SPREAD_MAX_BANDS; ++b) {
    r.bands_to_and_fro[b] = spread_band{};
    r.bands_racetrack[b] = spread_band{};
  }
  for (int b = 0; b < p.stored_bands_to_and_fro(); ++b) copy_band(p.bands_to_and_fro[b], r.bands_to_and_fro[b]);
  for (int b = 0; b < p.stored_bands_racetrack(); ++b) copy_band(p.bands_racetrack[b], r.bands_racetrack[b]);
  if (!v4) return;
  for (int d = 0; d < 2; ++d) {
    r.disc_rpm[d] = p.discs[d].rpm;
    r.disc_drop_point_turn_rad[d] = p.discs[d].drop_point_turn_rad;
  }
}

// spread_predict, spread_workspace_predict and spread_compensate_wind: `run(request, prediction)` predicts with the
// workspace the entry point chose.
template <typename Run>
spread_status predict_with(const char* function, const spread::predict::Predictor& predictor,
                           spread::predict::Prediction& prediction, const spread_prediction_def* def,
                           spread_prediction* result, double* transverse_mass_fraction, size_t transverse_capacity,
                           Run run) {
  using spread::capi::fail;
  if (def == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: def is NULL", function);
  if (result == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: result is NULL", function);
  try {
    spread::capi::detail::fault_point();
    spread::predict::PredictionRequest request;
    if (const spread_status s = spread::capi::read_request(function, *def, request); s != SPREAD_OK) return s;
    if (const spread_status s = spread::capi::check_result_size(function, *def); s != SPREAD_OK) return s;
    const bool v2 = def->struct_size >= spread::capi::kPredictionDefV2Size;
    const bool v3_def = def->struct_size >= spread::capi::kPredictionDefV3Size;
    const bool v3 = v3_def && def->result_size >= spread::capi::kPredictionV3Size;
    const bool v4 = v3_def && def->result_size >= spread::capi::kPredictionV4Size;

    const auto status = run(request, prediction);
    if (status != spread::predict::PredictStatus::kOk) {
      return spread::capi::refused(function, status_of(status), predictor, *def, request);
    }
    copy_result(prediction, v2, v3, v4, *result);
    if (transverse_mass_fraction != nullptr) {
      const auto& trays = prediction.tray_mass_fraction;
      if (transverse_capacity < trays.size()) {
        return fail(SPREAD_ERROR_BUFFER_TOO_SMALL, "%s: transverse buffer of %zu values, the prediction has %zu trays",
                    function, transverse_capacity, trays.size());
      }
      std::copy(trays.begin(), trays.end(), transverse_mass_fraction);
    }
    return SPREAD_OK;
  } catch (const std::bad_alloc&) {
    return fail(SPREAD_ERROR_OUT_OF_MEMORY, "%s: out of memory", function);
  } catch (const std::exception& e) {
    return fail(SPREAD_ERROR_INTERNAL, "%s: %.400s", function, e.what());
  } catch (...) {
    return fail(SPREAD_ERROR_INTERNAL, "%s: unknown exception", function);
  }
}

}  // namespace

extern "C" spread_status spread_predict(spread_tables* tables, const spread_prediction_def* def,
                                        spread_prediction* result, double* transverse_mass_fraction,
                                        size_t transverse_capacity) {
  if (tables == nullptr) return spread::capi::fail(SPREAD_ERROR_NULL_POINTER, "spread_predict: the handle is NULL");
  if (!spread::capi::live(tables)) {
    return spread::capi::fail(SPREAD_ERROR_BAD_HANDLE, "spread_predict: not a live spread_tables handle (closed?)");
  }
  spread::predict::Predictor& predictor = tables->predictor;
  return predict_with("spread_predict", predictor, tables->prediction, def, result, transverse_mass_fraction,
                      transverse_capacity,
                      [&](const spread::predict::PredictionRequest& request, spread::predict::Prediction& out) {
                        return predictor.predict(request, out);
                      });
}

extern "C" spread_status spread_workspace_predict(spread_workspace* workspace, const spread_prediction_def* def,
                                                  spread_prediction* result, double* transverse_mass_fraction,
                                                  size_t transverse_capacity) {
  if (workspace == nullptr) return spread::capi::fail(SPREAD_ERROR_NULL_POINTER, "spread_workspace_predict: the workspace is NULL");
  if (!spread::capi::live(workspace) || !spread::capi::live(workspace->tables)) {
    return spread::capi::fail(SPREAD_ERROR_BAD_HANDLE,
                              "spread_workspace_predict: the workspace or its spread_tables handle is not live");
  }
  const spread::predict::Predictor& predictor = workspace->tables->predictor;
  return predict_with("spread_workspace_predict", predictor, workspace->prediction, def, result, transverse_mass_fraction,
                      transverse_capacity,
                      [&](const spread::predict::PredictionRequest& request, spread::predict::Prediction& out) {
                        return predictor.predict(request, out, workspace->workspace);
                      });
}

namespace {

// spread_compensate_wind and spread_compensate_wind_within: at most `max_predictions` (INT_MAX: the whole
// search); *finished (when not NULL) whether the search ran to its end.
spread_status compensate_wind(const char* kFunction, spread_tables* tables, const spread_prediction_def* def,
                              int max_predictions, spread_prediction* result, double* transverse_mass_fraction,
                              size_t transverse_capacity, int32_t* finished) {
  using spread::capi::fail;
  if (tables == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: the handle is NULL", kFunction);
  if (!spread::capi::live(tables)) {
    return fail(SPREAD_ERROR_BAD_HANDLE, "%s: not a live spread_tables handle (closed?)", kFunction);
  }
  if (def == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: def is NULL", kFunction);
  if (result == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: result is NULL", kFunction);
  spread::predict::PredictionRequest request;
  if (const spread_status s = spread::capi::read_request(kFunction, *def, request); s != SPREAD_OK) return s;
  // The answer is a per-disc setting: only a caller whose structs have the 0.4 fields can read it.
  if (def->struct_size < spread::capi::kPredictionDefV4Size) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE,
                "%s: def->struct_size %u older than 0.4 (%zu): the per-disc setting it answers has no field there",
                kFunction, static_cast<unsigned>(def->struct_size), spread::capi::kPredictionDefV4Size);
  }
  if (def->result_size < spread::capi::kPredictionV4Size) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE,
                "%s: def->result_size %u older than 0.4 (%zu): the per-disc setting it answers has no field there",
                kFunction, static_cast<unsigned>(def->result_size), spread::capi::kPredictionV4Size);
  }
  spread::predict::Predictor& predictor = tables->predictor;
  // The present setting as spread_predict would take it, refused as spread_predict would refuse it.
  if (const spread_status s = spread::capi::check_request(kFunction, predictor, *def, request); s != SPREAD_OK) return s;
  if (predictor.machine().disc_count < 2) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: the table's machine has one disc (nothing to set apart)", kFunction);
  }
  if (!(def->bout_width_m > 0.0)) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: def->bout_width_m %g: the bout width to compensate at must be > 0",
                kFunction, def->bout_width_m);
  }
  spread::predict::WindCompensationLimits limits;
  limits.max_predictions = max_predictions;
  return predict_with(kFunction, predictor, tables->prediction, def, result, transverse_mass_fraction,
                      transverse_capacity,
                      [&](const spread::predict::PredictionRequest& checked, spread::predict::Prediction& out) {
                        const spread::predict::WindCompensation found =
                            spread::predict::compensate_wind(predictor, checked, out, predictor.own_workspace(), limits);
                        if (finished != nullptr) *finished = found.finished ? 1 : 0;
                        return found.status;
                      });
}

}  // namespace

extern "C" spread_status spread_compensate_wind(spread_tables* tables, const spread_prediction_def* def,
                                                spread_prediction* result, double* transverse_mass_fraction,
                                                size_t transverse_capacity) {
  return compensate_wind("spread_compensate_wind", tables, def, std::numeric_limits<int>::max(), result,
                         transverse_mass_fraction, transverse_capacity, nullptr);
}

extern "C" spread_status spread_compensate_wind_within(spread_tables* tables, const spread_prediction_def* def,
                                                       int32_t max_predictions, spread_prediction* result,
                                                       double* transverse_mass_fraction, size_t transverse_capacity,
                                                       int32_t* out_finished) {
  using spread::capi::fail;
  constexpr const char* kFunction = "spread_compensate_wind_within";
  if (out_finished == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: out_finished is NULL", kFunction);
  if (max_predictions != 0 && max_predictions < spread::predict::kWindMinPredictions) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE,
                "%s: max_predictions %d below the %d every compensation may make (the present setting's, the "
                "answer's and the present setting's again); 0: no limit",
                kFunction, static_cast<int>(max_predictions), spread::predict::kWindMinPredictions);
  }
  return compensate_wind(kFunction, tables, def,
                         max_predictions == 0 ? std::numeric_limits<int>::max() : static_cast<int>(max_predictions),
                         result, transverse_mass_fraction, transverse_capacity, out_finished);
}
