// The stamps of the discs' states (disc_stamps.hpp).
#include "libspread/analysis/field/disc_stamps.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "libspread/core/error.hpp"

namespace spread::field {

DiscStamps::DiscStamps(predict::Predictor& predictor, const predict::PredictionRequest& field, double cell_m,
                       double rpm_step_rpm)
    : predictor_(predictor), field_(field), cell_m_(cell_m), rpm_step_rpm_(rpm_step_rpm) {
  const std::optional<std::size_t> material = predictor.find_material(field.material);
  if (!material) {
    throw Error(ErrorKind::kArgument, "field setting", "field setting: no material '" + std::string(field.material) + "'");
  }
  min_rpm_ = predictor.min_rpm(*material);
  max_rpm_ = predictor.max_rpm(*material);
}

const StampPattern& DiscStamps::at(const DiscState& s) {
  const double rpm = std::clamp(std::round(s.rpm / rpm_step_rpm_) * rpm_step_rpm_, min_rpm_, max_rpm_);
  // Wind to a tenth of a metre per second, as the ECU keys its plans.
  const Key key{s.disc, std::lround(rpm * 1000.0), std::lround(s.drop_point_turn_rad / kTurnStep_rad),
                std::lround(s.wind_x_m_s * 10.0), std::lround(s.wind_y_m_s * 10.0)};
  auto found = stamps_.find(key);
  if (found == stamps_.end()) found = stamps_.emplace(key, build(s, rpm)).first;
  return found->second;
}

StampPattern DiscStamps::build(const DiscState& s, double rpm) const {
  predict::PredictionRequest r = field_;
  r.rpm = 0.0;
  r.drop_point_turn_rad = 0.0;
  // Both discs at this state: only this disc's landings are kept.
  r.disc_rpm = {rpm, rpm};
  const double turn = std::round(s.drop_point_turn_rad / kTurnStep_rad) * kTurnStep_rad;
  r.disc_drop_point_turn_rad = {turn, turn};
  if (predictor_.machine().disc_count < 2) {
    r.disc_rpm[predict::kRightDisc] = r.disc_drop_point_turn_rad[predict::kRightDisc] =
        std::numeric_limits<double>::quiet_NaN();
  }
  r.wind_x_m_s = std::round(s.wind_x_m_s * 10.0) / 10.0;
  r.wind_y_m_s = std::round(s.wind_y_m_s * 10.0) / 10.0;
  r.standard_errors = false;
  predict::Prediction p;
  const predict::PredictStatus status = predictor_.predict(r, p);
  if (status != predict::PredictStatus::kOk) {
    std::ostringstream out;
    out << "field setting: the predictor refuses disc " << s.disc << " at " << rpm << " r/min, drop point turned "
        << turn << " rad, wind (" << r.wind_x_m_s << ", " << r.wind_y_m_s << ") m/s: " << predict::to_string(status);
    throw Error(ErrorKind::kArgument, "field setting", out.str());
  }
  StampPattern out = stamp_pattern_of_disc(p, s.disc, cell_m_);
  // As fractions of this disc's own discharge.
  const double share = disc_share(p, s.disc);
  if (share > 0.0) {
    for (double& f : out.fraction) f /= share;
    out.landed_fraction /= share;
  }
  return out;
}

}  // namespace spread::field
