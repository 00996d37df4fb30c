// The request-check stage of predict() (predictor.hpp): every field of the request in its domain before
// any is used (docs/c-api.md, PredictorLimits), then the material's rows around each disc's speed and the
// conditions the discs fly in. A refusal is a status with the field at fault (RequestProblem), never an
// exception, and allocates nothing.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "libspread/analysis/predict/launch_interpolation.hpp"
#include "libspread/analysis/predict/prediction_context.hpp"
#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

const char* to_string(PredictStatus status) {
  switch (status) {
    case PredictStatus::kOk: return "ok";
    case PredictStatus::kNotFinite: return "argument not finite";
    case PredictStatus::kOutOfRange: return "argument out of range";
    case PredictStatus::kUnknownEffect: return "unknown effect bits";
    case PredictStatus::kUnknownMaterial: return "unknown material";
    case PredictStatus::kRpmOutsideTable: return "rpm outside the table";
    case PredictStatus::kOutsideDomain: return "outside the landing grid's domain";
  }
  return "unknown status";
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Each check below records the first problem it finds in `found` (the field, its value and its range) and
// returns false; they run in this order, so the problem named is the first in the request's order.
bool refuse(RequestProblem& found, PredictStatus status, RequestField field, double value, double lower, double upper,
            const char* rule = "") {
  found = RequestProblem{status, field, value, lower, upper, rule};
  return false;
}

bool finite_fields(const PredictionRequest& r, double height_m, RequestProblem& found) {
  const std::pair<RequestField, double> fields[] = {
      {RequestField::kRpm, r.rpm},           {RequestField::kDiscHeight, height_m},   {RequestField::kWindX, r.wind_x_m_s},
      {RequestField::kWindY, r.wind_y_m_s},  {RequestField::kCvTarget, r.cv_target}, {RequestField::kBoutWidth, r.bout_width_m},
      {RequestField::kTrayWidth, r.tray_width_m}, {RequestField::kDropPointTurn, r.drop_point_turn_rad}};
  for (const auto& [field, v] : fields) {
    if (!std::isfinite(v)) return refuse(found, PredictStatus::kNotFinite, field, v, -kInf, kInf);
  }
  return true;
}

bool scalar_ranges(const PredictionRequest& r, double height_m, double lowest_height_m, const PredictorLimits& limits,
                   RequestProblem& found) {
  const PredictStatus range = PredictStatus::kOutOfRange;
  if (height_m < lowest_height_m || height_m > limits.max_disc_height_m) {
    return refuse(found, range, RequestField::kDiscHeight, height_m, lowest_height_m, limits.max_disc_height_m);
  }
  if (std::abs(r.wind_x_m_s) > limits.max_wind_m_s) {
    return refuse(found, range, RequestField::kWindX, r.wind_x_m_s, -limits.max_wind_m_s, limits.max_wind_m_s);
  }
  if (std::abs(r.wind_y_m_s) > limits.max_wind_m_s) {
    return refuse(found, range, RequestField::kWindY, r.wind_y_m_s, -limits.max_wind_m_s, limits.max_wind_m_s);
  }
  if (!(r.cv_target > 0.0) || r.cv_target > limits.max_cv_target) {
    return refuse(found, range, RequestField::kCvTarget, r.cv_target, 0.0, limits.max_cv_target, "above");
  }
  if (r.bout_width_m < 0.0 || r.bout_width_m > limits.max_bout_width_m) {
    return refuse(found, range, RequestField::kBoutWidth, r.bout_width_m, 0.0, limits.max_bout_width_m);
  }
  if (std::abs(r.drop_point_turn_rad) > kPi) {
    return refuse(found, range, RequestField::kDropPointTurn, r.drop_point_turn_rad, -kPi, kPi);
  }
  return true;
}

// Each disc's own setting: NaN is "as both discs"; an infinity is not finite. A both-discs value that no
// disc would use is refused, not dropped.
bool disc_fields(const PredictionRequest& r, int machine_discs, RequestProblem& found) {
  const RequestField rpm_field[2] = {RequestField::kLeftDiscRpm, RequestField::kRightDiscRpm};
  const RequestField turn_field[2] = {RequestField::kLeftDiscDropPointTurn, RequestField::kRightDiscDropPointTurn};
  for (std::size_t d = 0; d < 2; ++d) {
    const double rpm = r.disc_rpm[d], turn_rad = r.disc_drop_point_turn_rad[d];
    if (std::isinf(rpm)) return refuse(found, PredictStatus::kNotFinite, rpm_field[d], rpm, -kInf, kInf);
    if (std::isinf(turn_rad)) return refuse(found, PredictStatus::kNotFinite, turn_field[d], turn_rad, -kInf, kInf);
    if (std::abs(turn_rad) > kPi) return refuse(found, PredictStatus::kOutOfRange, turn_field[d], turn_rad, -kPi, kPi);
    if (d == kRightDisc && machine_discs < 2 && (!std::isnan(rpm) || !std::isnan(turn_rad))) {
      return refuse(found, PredictStatus::kOutOfRange, std::isnan(rpm) ? turn_field[d] : rpm_field[d],
                    std::isnan(rpm) ? turn_rad : rpm, 0.0, 0.0,
                    "given on a one-disc machine (only [0], the left disc, may be set)");
    }
  }
  const std::size_t discs = machine_discs < 2 ? 1 : 2;
  const auto all_given = [&](const std::array<double, 2>& values) {
    for (std::size_t d = 0; d < discs; ++d) {
      if (std::isnan(values[d])) return false;
    }
    return true;
  };
  if (all_given(r.disc_rpm) && r.rpm != 0.0) {
    return refuse(found, PredictStatus::kOutOfRange, RequestField::kRpm, r.rpm, 0.0, 0.0,
                  "given while every disc has its own speed (set it to 0)");
  }
  if (all_given(r.disc_drop_point_turn_rad) && r.drop_point_turn_rad != 0.0) {
    return refuse(found, PredictStatus::kOutOfRange, RequestField::kDropPointTurn, r.drop_point_turn_rad, 0.0, 0.0,
                  "given while every disc has its own drop point (set it to 0)");
  }
  return true;
}

// tray_capacity: Predictor::tray_capacity of the request's tray width (0: outside the limits).
bool layout_and_effects(const PredictionRequest& r, int tray_capacity, const PredictorLimits& limits,
                        RequestProblem& found) {
  if (tray_capacity == 0) {
    return refuse(found, PredictStatus::kOutOfRange, RequestField::kTrayWidth, r.tray_width_m, limits.min_tray_width_m,
                  limits.max_half_extent_m);
  }
  if (!std::isnan(r.kernel_half_width_m)) {
    if (!std::isfinite(r.kernel_half_width_m)) {
      return refuse(found, PredictStatus::kNotFinite, RequestField::kKernelHalfWidth, r.kernel_half_width_m, -kInf, kInf);
    }
    if (r.kernel_half_width_m < 0.0 || r.kernel_half_width_m > limits.max_kernel_half_width_m) {
      return refuse(found, PredictStatus::kOutOfRange, RequestField::kKernelHalfWidth, r.kernel_half_width_m, 0.0,
                    limits.max_kernel_half_width_m);
    }
  }
  if ((r.effects & ~(flight::kAllEffects | kTableEffects)) != 0) {
    return refuse(found, PredictStatus::kUnknownEffect, RequestField::kEffects, static_cast<double>(r.effects), 0.0, 0.0);
  }
  return true;
}

}  // namespace

PredictStatus Predictor::validate(const PredictionRequest& r, double& height_m, RequestProblem* problem) const {
  RequestProblem found;
  height_m = std::isnan(r.disc_height_m) ? contents_.machine.disc_height_m : r.disc_height_m;
  const double lowest_height_m = std::max(0.0, -lowest_sample_z_m_);
  const bool valid = finite_fields(r, height_m, found) && scalar_ranges(r, height_m, lowest_height_m, limits_, found) &&
                     disc_fields(r, contents_.machine.disc_count, found) &&
                     layout_and_effects(r, tray_capacity(r.tray_width_m), limits_, found);
  if (!valid && problem != nullptr) *problem = found;
  return found.status;
}

RequestProblem Predictor::request_problem(const PredictionRequest& request) const {
  RequestProblem problem;
  double height_m = 0.0;
  validate(request, height_m, &problem);
  return problem;
}

DiscSetting disc_setting(const PredictionRequest& request, int disc) {
  const double rpm = request.disc_rpm[static_cast<std::size_t>(disc)];
  const double turn_rad = request.disc_drop_point_turn_rad[static_cast<std::size_t>(disc)];
  return {std::isnan(rpm) ? request.rpm : rpm, std::isnan(turn_rad) ? request.drop_point_turn_rad : turn_rad};
}

PredictStatus Predictor::check_request(Context& c) const {
  const PredictionRequest& request = c.request;
  if (const PredictStatus s = validate(request, c.height_m); s != PredictStatus::kOk) return s;
  const auto material_index = find_material(request.material);
  if (!material_index) return PredictStatus::kUnknownMaterial;
  const MaterialRows& rows = materials_[*material_index];
  c.rows = &rows;
  c.two_discs = contents_.machine.disc_count == 2;
  const DiscSetting left = disc_setting(request, kLeftDisc);
  const DiscSetting right = c.two_discs ? disc_setting(request, kRightDisc) : left;
  c.settings[kLeftDisc] = left;
  c.settings[kRightDisc] = right;
  // Discs at their own settings each get their own samples, flights and landings; alike, the right disc
  // is the left one's mirror image (flown as such only in a lateral wind).
  c.per_disc = c.two_discs && !(left == right);
  for (int d = 0; d < (c.per_disc ? 2 : 1); ++d) {
    const auto bracket = bracket_rpm(std::span(run_rpm_).subspan(rows.first_run, rows.run_count), c.settings[d].rpm);
    if (!bracket) return PredictStatus::kRpmOutsideTable;
    // On a row (t = 0) that row alone.
    DiscRows& disc = c.disc_rows[d];
    disc.lower_run = rows.first_run + bracket->lower;
    disc.upper_run = bracket->upper_weight == 0.0 ? disc.lower_run : rows.first_run + bracket->upper;
    disc.t = bracket->upper_weight;
  }
  if (!c.per_disc) c.disc_rows[1] = c.disc_rows[0];
  flight_conditions(request, c.disc_rows, c.effects, c.air);
  if (limits_.refuse_outside_domain && !request.fly_outside_domain &&
      landing_grid_for(rows, c.height_m, c.effects, c.air) == nullptr &&
      landing_domain_miss(request) != DomainMiss::kNone) {
    return PredictStatus::kOutsideDomain;
  }
  const bool windy = (c.effects & flight::kWind) != 0;
  c.fly_right_disc = c.two_discs && (c.per_disc || (windy && request.wind_x_m_s != 0.0));
  return PredictStatus::kOk;
}

void Predictor::flight_conditions(const PredictionRequest& request, const DiscRows (&disc_rows)[2],
                                  flight::EffectSet& effects, flight::Air& air) const {
  // Wind: a zero wind is no wind (the still-air right-hand side is cheaper). Only a lateral component
  // breaks the left/right mirror symmetry; wind along y is symmetric under x → −x.
  effects = request.effects & flight::kAllEffects;
  if ((request.effects & kTableEffects) != 0) {
    for (const DiscRows& r : disc_rows) effects |= run_effects_[r.lower_run] | run_effects_[r.upper_run];
    if (request.wind_x_m_s != 0.0 || request.wind_y_m_s != 0.0) effects |= flight::kWind;
  }
  air = flight::Air{};
  const bool windy = (effects & flight::kWind) != 0 && (request.wind_x_m_s != 0.0 || request.wind_y_m_s != 0.0);
  if (windy) {
    air.wind_m_s = Vec3(request.wind_x_m_s, request.wind_y_m_s, 0.0);
  } else {
    effects &= ~flight::EffectSet{flight::kWind};
  }
}

Predictor::DomainMiss Predictor::landing_domain_miss(const PredictionRequest& request) const {
  const auto material_index = find_material(request.material);
  if (!material_index) return DomainMiss::kNone;
  const MaterialRows& rows = materials_[*material_index];
  const LandingGrid& grid = grids_[rows.material];
  if (!landing_grid_enabled_ || grid.empty()) return DomainMiss::kNone;
  // A grid's material flies the same still-air effects in every row (grid_effects), so the first
  // row stands for any the request falls between.
  const DiscRows first_row[2] = {{rows.first_run, rows.first_run, 0.0}, {rows.first_run, rows.first_run, 0.0}};
  flight::EffectSet effects = 0;
  flight::Air air;
  flight_conditions(request, first_row, effects, air);
  if ((effects & ~flight::EffectSet{flight::kWind}) != grid.effects()) return DomainMiss::kEffects;
  const double height_m = std::isnan(request.disc_height_m) ? contents_.machine.disc_height_m : request.disc_height_m;
  if (!(height_m >= domain_.min_disc_height_m && height_m <= domain_.max_disc_height_m)) return DomainMiss::kHeight;
  if (!domain_.covers(height_m, air.wind_m_s.x(), air.wind_m_s.y())) return DomainMiss::kWind;
  return DomainMiss::kNone;
}

}  // namespace spread::predict
