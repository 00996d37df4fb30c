#include "capi/src/prediction_request.hpp"

#include <cmath>
#include <cstring>
#include <string_view>

#include "capi/src/abi_layout.hpp"
#include "capi/src/error_detail.hpp"
#include "capi/src/predict_status.hpp"

namespace spread::capi {

namespace {

constexpr const char* kDiscName[2] = {"left", "right"};
constexpr const char* kDiscRpmField[2] = {"disc_rpm[0]", "disc_rpm[1]"};
constexpr const char* kDiscTurnField[2] = {"disc_drop_point_turn_rad[0]", "disc_drop_point_turn_rad[1]"};

}  // namespace

spread_status read_request(const char* function, const spread_prediction_def& def, predict::PredictionRequest& request) {
  // struct_size first: a definition not made by spread_prediction_def_default() is refused before any
  // of its fields is read.
  if (def.struct_size < kPredictionDefV1Size) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: def->struct_size %u is smaller than the first published %zu", function,
                static_cast<unsigned>(def.struct_size), kPredictionDefV1Size);
  }
  if (def.material == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: def->material is NULL", function);
  request = predict::PredictionRequest{};
  request.material = std::string_view(def.material, std::strlen(def.material));
  request.rpm = def.rpm;
  request.disc_height_m = def.disc_height_m;
  request.wind_x_m_s = def.wind_m_s[0];
  request.wind_y_m_s = def.wind_m_s[1];
  request.cv_target = def.cv_target_percent / 100.0;
  request.effects = def.effects;
  request.bout_width_m = def.bout_width_m;
  request.tray_width_m = def.tray_width_m;
  if (def.struct_size >= kPredictionDefV2Size) request.kernel_half_width_m = def.kernel_half_width_m;
  if (def.struct_size >= kPredictionDefV3Size) request.drop_point_turn_rad = def.drop_point_turn_rad;
  if (def.struct_size >= kPredictionDefV4Size) {
    for (std::size_t d = 0; d < 2; ++d) {
      request.disc_rpm[d] = def.disc_rpm[d];
      request.disc_drop_point_turn_rad[d] = def.disc_drop_point_turn_rad[d];
    }
  }
  if (def.struct_size >= kPredictionDefV5Size) {
    // A flag is 0 or 1: any other value is a caller's mistake (an uninitialised field, a count), not a yes.
    if (def.fly_outside_domain > 1u) {
      return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: def->fly_outside_domain %u is neither 0 nor 1", function,
                  static_cast<unsigned>(def.fly_outside_domain));
    }
    request.fly_outside_domain = def.fly_outside_domain == 1u;
  }
  return SPREAD_OK;
}

spread_status check_result_size(const char* function, const spread_prediction_def& def) {
  // Up to 0.2 the definition's version is the result's; from 0.3 on result_size says how much result the
  // caller has, and every answer writes at least 0.2's fields.
  if (def.struct_size >= kPredictionDefV3Size && def.result_size < kPredictionV2Size) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE,
                "%s: def->result_size %u is smaller than the smallest result written for this definition (%zu bytes, "
                "0.2's; spread_prediction_def_default() sets sizeof(spread_prediction))",
                function, static_cast<unsigned>(def.result_size), kPredictionV2Size);
  }
  return SPREAD_OK;
}

spread_status check_request(const char* function, const predict::Predictor& predictor,
                            const spread_prediction_def& def, const predict::PredictionRequest& request) {
  const auto reject = [&](predict::PredictStatus status) {
    return refused(function, status_of(status), predictor, def, request);
  };
  const predict::RequestProblem problem = predictor.request_problem(request);
  if (problem.status != predict::PredictStatus::kOk) return reject(problem.status);
  const auto material = predictor.find_material(request.material);
  if (!material) return reject(predict::PredictStatus::kUnknownMaterial);
  const double min_rpm = predictor.min_rpm(*material), max_rpm = predictor.max_rpm(*material);
  const int discs = predictor.machine().disc_count < 2 ? 1 : 2;
  for (int d = 0; d < discs; ++d) {
    const double rpm = predict::disc_setting(request, d).rpm;
    if (!(rpm >= min_rpm && rpm <= max_rpm)) return reject(predict::PredictStatus::kRpmOutsideTable);
  }
  if (predictor.limits().refuse_outside_domain && !request.fly_outside_domain &&
      predictor.landing_domain_miss(request) != predict::Predictor::DomainMiss::kNone) {
    return reject(predict::PredictStatus::kOutsideDomain);
  }
  return SPREAD_OK;
}

spread_status refused(const char* function, spread_status status, const predict::Predictor& predictor,
                      const spread_prediction_def& def, const predict::PredictionRequest& request) {
  const bool v4 = def.struct_size >= kPredictionDefV4Size;
  switch (status) {
    case SPREAD_ERROR_UNKNOWN_MATERIAL:
      return fail(status, "%s: material \"%.200s\" is not in the table", function, def.material);
    case SPREAD_ERROR_RPM_OUTSIDE_TABLE: {
      const auto index = predictor.find_material(def.material);
      const double min_rpm = index ? predictor.min_rpm(*index) : 0.0, max_rpm = index ? predictor.max_rpm(*index) : 0.0;
      // The disc whose speed is outside: its own, or the both-discs rpm it takes.
      for (std::size_t d = 0; v4 && d < 2; ++d) {
        const double rpm = std::isnan(request.disc_rpm[d]) ? request.rpm : request.disc_rpm[d];
        if (!(rpm >= min_rpm && rpm <= max_rpm)) {
          return fail(status, "%s: the %s disc's speed %g rpm (%s) outside the rows of \"%.200s\", [%g, %g]", function,
                      kDiscName[d], rpm, std::isnan(request.disc_rpm[d]) ? "rpm" : kDiscRpmField[d], def.material,
                      min_rpm, max_rpm);
        }
      }
      return fail(status, "%s: rpm %g outside the rows of \"%.200s\", [%g, %g]", function, def.rpm, def.material, min_rpm,
                  max_rpm);
    }
    case SPREAD_ERROR_OUTSIDE_DOMAIN: {
      using Miss = predict::Predictor::DomainMiss;
      const auto& domain = predictor.landing_domain();
      const char* const opt_in = "set fly_outside_domain to fly every launch sample instead";
      switch (predictor.landing_domain_miss(request)) {
        case Miss::kHeight:
          return fail(status, "%s: disc_height_m %g outside the landing grid's heights [%g, %g] m (%s)", function,
                      std::isnan(def.disc_height_m) ? predictor.machine().disc_height_m : def.disc_height_m,
                      domain.min_disc_height_m, domain.max_disc_height_m, opt_in);
        case Miss::kWind:
          return fail(status, "%s: wind_m_s {%g, %g}, %g m/s, above the landing grid's %g m/s (%s)", function,
                      def.wind_m_s[0], def.wind_m_s[1], std::hypot(def.wind_m_s[0], def.wind_m_s[1]),
                      domain.max_wind_m_s, opt_in);
        case Miss::kEffects:
          return fail(status, "%s: effects 0x%x fly more than the table's drag, which the landing grid holds (%s)",
                      function, static_cast<unsigned>(def.effects), opt_in);
        case Miss::kNone: break;
      }
      return fail(status, "%s: outside the landing grid's domain (%s)", function, opt_in);
    }
    case SPREAD_ERROR_UNKNOWN_EFFECT:
      return fail(status, "%s: effects 0x%x has bits outside SPREAD_EFFECT_ALL | SPREAD_EFFECTS_AS_TABLE", function,
                  static_cast<unsigned>(def.effects));
    default: {
      // The one field at fault, named as the definition names it, with its value and its range
      // (predict::Predictor::request_problem: the library's rules, not repeated here).
      using Field = predict::RequestField;
      const predict::RequestProblem problem = predictor.request_problem(request);
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
      if (status == SPREAD_ERROR_NOT_FINITE) return fail(status, "%s: %s is %g", function, name.field, value);
      if (name.disc >= 0 && *problem.rule == '\0') {
        const bool speed = problem.field == Field::kLeftDiscRpm || problem.field == Field::kRightDiscRpm;
        return fail(status, "%s: the %s disc's %s %s %g outside [%g, %g] %s", function, kDiscName[name.disc],
                    speed ? "speed" : "drop point", name.field, value, name.scale * problem.lower,
                    name.scale * problem.upper, name.unit);
      }
      if (*problem.rule != '\0' && problem.lower == problem.upper) {
        return fail(status, "%s: %s %g %s", function, name.field, value, problem.rule);
      }
      return fail(status, "%s: %s %g outside %s%g, %g] %s", function, name.field, value,
                  *problem.rule != '\0' ? "(" : "[", name.scale * problem.lower, name.scale * problem.upper, name.unit);
    }
  }
}

}  // namespace spread::capi
