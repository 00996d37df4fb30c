// spread_predict: C definition → predict::PredictionRequest → Predictor → C result. No allocation:
// the material name is viewed in place, the workspace belongs to the handle.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <new>
#include <numbers>
#include <string_view>

#include "capi/src/error_detail.hpp"
#include "capi/src/fault_seam.hpp"
#include "capi/src/predict_status.hpp"
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

// What a refused request was, for spread_last_error_detail (vsnprintf into the thread's buffer: no
// allocation).
constexpr const char* kDiscName[2] = {"left", "right"};
constexpr const char* kDiscRpmField[2] = {"disc_rpm[0]", "disc_rpm[1]"};
constexpr const char* kDiscTurnField[2] = {"disc_drop_point_turn_rad[0]", "disc_drop_point_turn_rad[1]"};

spread_status refused(spread_status status, const spread::predict::Predictor& predictor,
                      const spread_prediction_def& def, const spread::predict::PredictionRequest& request) {
  using spread::capi::fail;
  const bool v4 = def.struct_size >= spread::capi::kPredictionDefV4Size;
  switch (status) {
    case SPREAD_ERROR_UNKNOWN_MATERIAL:
      return fail(status, "spread_predict: no material \"%.200s\" in the table", def.material);
    case SPREAD_ERROR_RPM_OUTSIDE_TABLE: {
      const auto index = predictor.find_material(def.material);
      const double min_rpm = index ? predictor.min_rpm(*index) : 0.0, max_rpm = index ? predictor.max_rpm(*index) : 0.0;
      // The disc whose speed is outside: its own, or the both-discs rpm it takes.
      for (std::size_t d = 0; v4 && d < 2; ++d) {
        const double rpm = std::isnan(def.disc_rpm[d]) ? def.rpm : def.disc_rpm[d];
        if (!(rpm >= min_rpm && rpm <= max_rpm)) {
          return fail(status, "spread_predict: the %s disc's speed %g rpm (%s) outside the rows of \"%.200s\", [%g, %g]",
                      kDiscName[d], rpm, std::isnan(def.disc_rpm[d]) ? "rpm" : kDiscRpmField[d], def.material,
                      min_rpm, max_rpm);
        }
      }
      return fail(status, "spread_predict: rpm %g outside the rows of \"%.200s\", [%g, %g]", def.rpm, def.material,
                  min_rpm, max_rpm);
    }
    case SPREAD_ERROR_OUTSIDE_DOMAIN: {
      using Miss = spread::predict::Predictor::DomainMiss;
      const auto& domain = predictor.landing_domain();
      const char* const opt_in = "set fly_outside_domain to fly every launch sample instead";
      switch (predictor.landing_domain_miss(request)) {
        case Miss::kHeight:
          return fail(status, "spread_predict: disc_height_m %g outside the landing grid's heights [%g, %g] m (%s)",
                      std::isnan(def.disc_height_m) ? predictor.machine().disc_height_m : def.disc_height_m,
                      domain.min_disc_height_m, domain.max_disc_height_m, opt_in);
        case Miss::kWind:
          return fail(status, "spread_predict: wind_m_s {%g, %g}, %g m/s, above the landing grid's %g m/s (%s)",
                      def.wind_m_s[0], def.wind_m_s[1], std::hypot(def.wind_m_s[0], def.wind_m_s[1]),
                      domain.max_wind_m_s, opt_in);
        case Miss::kEffects:
          return fail(status, "spread_predict: effects 0x%x fly more than the table's drag, which the landing grid holds (%s)",
                      static_cast<unsigned>(def.effects), opt_in);
        case Miss::kNone: break;
      }
      return fail(status, "spread_predict: outside the landing grid's domain (%s)", opt_in);
    }
    case SPREAD_ERROR_UNKNOWN_EFFECT:
      return fail(status, "spread_predict: effects 0x%x has bits outside SPREAD_EFFECT_ALL | SPREAD_EFFECTS_AS_TABLE",
                  static_cast<unsigned>(def.effects));
    default: {
      // The one field at fault, named as the definition names it, with its value and its range
      // (spread::predict::Predictor::request_problem: the library's rules, not repeated here).
      using Field = spread::predict::RequestField;
      const spread::predict::RequestProblem problem = predictor.request_problem(request);
      struct Name {
        const char* field;
        const char* unit;
        double scale;  // library units to the definition's (cv_target is a fraction, cv_target_percent percent)
        int disc;      // a disc's own field: kLeftDisc, kRightDisc; -1 the both-discs ones
      };
      Name name{"a field", "", 1.0, -1};
      switch (problem.field) {
        case Field::kRpm: name = {"rpm", "rpm", 1.0, -1}; break;
        case Field::kDiscHeight: name = {"disc_height_m", "m", 1.0, -1}; break;
        case Field::kWindX: name = {"wind_m_s[0]", "m/s", 1.0, -1}; break;
        case Field::kWindY: name = {"wind_m_s[1]", "m/s", 1.0, -1}; break;
        case Field::kCvTarget: name = {"cv_target_percent", "percent", 100.0, -1}; break;
        case Field::kBoutWidth: name = {"bout_width_m", "m", 1.0, -1}; break;
        case Field::kTrayWidth: name = {"tray_width_m", "m", 1.0, -1}; break;
        case Field::kKernelHalfWidth: name = {"kernel_half_width_m", "m", 1.0, -1}; break;
        case Field::kDropPointTurn: name = {"drop_point_turn_rad", "rad", 1.0, -1}; break;
        case Field::kLeftDiscRpm: name = {kDiscRpmField[0], "rpm", 1.0, 0}; break;
        case Field::kRightDiscRpm: name = {kDiscRpmField[1], "rpm", 1.0, 1}; break;
        case Field::kLeftDiscDropPointTurn: name = {kDiscTurnField[0], "rad", 1.0, 0}; break;
        case Field::kRightDiscDropPointTurn: name = {kDiscTurnField[1], "rad", 1.0, 1}; break;
        case Field::kEffects:
        case Field::kNone: break;
      }
      const double value = name.scale * problem.value;
      if (status == SPREAD_ERROR_NOT_FINITE) return fail(status, "spread_predict: %s is %g", name.field, value);
      if (name.disc >= 0 && *problem.rule == '\0') {
        const bool speed = problem.field == Field::kLeftDiscRpm || problem.field == Field::kRightDiscRpm;
        return fail(status, "spread_predict: the %s disc's %s %s %g outside [%g, %g] %s", kDiscName[name.disc],
                    speed ? "speed" : "drop point", name.field, value, name.scale * problem.lower,
                    name.scale * problem.upper, name.unit);
      }
      if (*problem.rule != '\0' && problem.lower == problem.upper) {
        return fail(status, "spread_predict: %s %g %s", name.field, value, problem.rule);
      }
      return fail(status, "spread_predict: %s %g outside %s%g, %g] %s", name.field, value,
                  *problem.rule != '\0' ? "(" : "[", name.scale * problem.lower, name.scale * problem.upper, name.unit);
    }
  }
}

// spread_predict, spread_workspace_predict and spread_compensate_wind: `run(request, prediction)` predicts with the
// workspace the entry point chose.
template <typename Run>
spread_status predict_with(const spread::predict::Predictor& predictor, spread::predict::Prediction& prediction,
                           const spread_prediction_def* def, spread_prediction* result,
                           double* transverse_mass_fraction, size_t transverse_capacity, Run run) {
  using spread::capi::fail;
  if (def == nullptr || result == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_predict: def or result is NULL");
  // struct_size first: a definition not made by spread_prediction_def_default() is refused before any
  // of its fields is read.
  if (def->struct_size < spread::capi::kPredictionDefV1Size) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "spread_predict: def->struct_size %u is smaller than the first published %zu",
                static_cast<unsigned>(def->struct_size), spread::capi::kPredictionDefV1Size);
  }
  if (def->material == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_predict: def->material is NULL");
  try {
    spread::capi::detail::fault_point();
    spread::predict::PredictionRequest request;
    request.material = std::string_view(def->material, std::strlen(def->material));
    request.rpm = def->rpm;
    request.disc_height_m = def->disc_height_m;
    request.wind_x_m_s = def->wind_m_s[0];
    request.wind_y_m_s = def->wind_m_s[1];
    request.cv_target = def->cv_target_percent / 100.0;
    request.effects = def->effects;
    request.bout_width_m = def->bout_width_m;
    request.tray_width_m = def->tray_width_m;
    const bool v2 = def->struct_size >= spread::capi::kPredictionDefV2Size;
    if (v2) request.kernel_half_width_m = def->kernel_half_width_m;
    const bool v3_def = def->struct_size >= spread::capi::kPredictionDefV3Size;
    if (v3_def) request.drop_point_turn_rad = def->drop_point_turn_rad;
    const bool v3 = v3_def && def->result_size >= spread::capi::kPredictionV3Size;
    const bool v4_def = def->struct_size >= spread::capi::kPredictionDefV4Size;
    if (v4_def) {
      for (std::size_t d = 0; d < 2; ++d) {
        request.disc_rpm[d] = def->disc_rpm[d];
        request.disc_drop_point_turn_rad[d] = def->disc_drop_point_turn_rad[d];
      }
    }
    const bool v4 = v3_def && def->result_size >= spread::capi::kPredictionV4Size;
    if (def->struct_size >= spread::capi::kPredictionDefV5Size) request.fly_outside_domain = def->fly_outside_domain != 0;

    const auto status = run(request, prediction);
    if (status != spread::predict::PredictStatus::kOk) return refused(status_of(status), predictor, *def, request);
    copy_result(prediction, v2, v3, v4, *result);
    if (transverse_mass_fraction != nullptr) {
      const auto& trays = prediction.tray_mass_fraction;
      if (transverse_capacity < trays.size()) {
        return fail(SPREAD_ERROR_BUFFER_TOO_SMALL, "spread_predict: transverse buffer of %zu values, the prediction has %zu trays",
                    transverse_capacity, trays.size());
      }
      std::copy(trays.begin(), trays.end(), transverse_mass_fraction);
    }
    return SPREAD_OK;
  } catch (const std::bad_alloc&) {
    return fail(SPREAD_ERROR_OUT_OF_MEMORY, "spread_predict: out of memory");
  } catch (const std::exception& e) {
    return fail(SPREAD_ERROR_INTERNAL, "spread_predict: %.400s", e.what());
  } catch (...) {
    return fail(SPREAD_ERROR_INTERNAL, "spread_predict: unknown exception");
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
  return predict_with(predictor, tables->prediction, def, result, transverse_mass_fraction, transverse_capacity,
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
  return predict_with(predictor, workspace->prediction, def, result, transverse_mass_fraction, transverse_capacity,
                      [&](const spread::predict::PredictionRequest& request, spread::predict::Prediction& out) {
                        return predictor.predict(request, out, workspace->workspace);
                      });
}

extern "C" spread_status spread_compensate_wind(spread_tables* tables, const spread_prediction_def* def,
                                                spread_prediction* result, double* transverse_mass_fraction,
                                                size_t transverse_capacity) {
  using spread::capi::fail;
  if (tables == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_compensate_wind: the handle is NULL");
  if (!spread::capi::live(tables)) {
    return fail(SPREAD_ERROR_BAD_HANDLE, "spread_compensate_wind: not a live spread_tables handle (closed?)");
  }
  if (def == nullptr || result == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_compensate_wind: def or result is NULL");
  // The answer is a per-disc setting: only a caller whose structs have the 0.4 fields can read it.
  if (def->struct_size < spread::capi::kPredictionDefV4Size || def->result_size < spread::capi::kPredictionV4Size) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE,
                "spread_compensate_wind: def->struct_size %u / result_size %u older than 0.4 (%zu / %zu): the "
                "per-disc setting it answers has no field there",
                static_cast<unsigned>(def->struct_size), static_cast<unsigned>(def->result_size),
                spread::capi::kPredictionDefV4Size, spread::capi::kPredictionV4Size);
  }
  spread::predict::Predictor& predictor = tables->predictor;
  if (predictor.machine().disc_count < 2) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "spread_compensate_wind: the machine has one disc (nothing to set apart)");
  }
  if (!(def->bout_width_m > 0.0)) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "spread_compensate_wind: def->bout_width_m %g: the bout width to compensate at must be > 0",
                def->bout_width_m);
  }
  return predict_with(predictor, tables->prediction, def, result, transverse_mass_fraction, transverse_capacity,
                      [&](const spread::predict::PredictionRequest& request, spread::predict::Prediction& out) {
                        return spread::predict::compensate_wind(predictor, request, out, predictor.own_workspace()).status;
                      });
}
