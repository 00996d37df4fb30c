#pragma once
// Each disc's ground pattern at the state the ECU has it in, as stamps: a disc's speed, its drop point and
// the wind in the machine frame make its landings; the stamp holds them as fractions of that disc's own
// discharge (so a step stamps it with the mass that disc's gate delivered). Built on first use and kept:
// the states a field run passes through (the field's setting, a narrowed side, a border setting, the
// seconds a disc takes between them) repeat pass after pass.
//
// A state is keyed to rpm_step_rpm in speed (a disc changing speed is stamped at the nearest step: at
// 10 r/min the throw moves by under 2 % at a field's 600 r/min) and to kTurnStep_rad in drop point. Speeds
// outside the table's rows are stamped at its nearest row: the ECU closes a disc's gate below
// its spreading speed, so only a disc spinning up through the table's low end meets them.
#include <cstddef>
#include <map>
#include <tuple>

#include "libspread/analysis/field/stamp_pattern.hpp"
#include "libspread/analysis/predict/predictor.hpp"

namespace spread::field {

inline constexpr double kTurnStep_rad = 0.005;  // 0.3°: well inside a border search's own resolution

struct DiscState {
  int disc = predict::kLeftDisc;
  double rpm = 0.0;                  // [r/min]
  double drop_point_turn_rad = 0.0;  // from the table's drop point [rad]
  double wind_x_m_s = 0.0;           // machine frame: across the travel, to the right [m/s]
  double wind_y_m_s = 0.0;           // along the travel, forward [m/s]
};

class DiscStamps {
 public:
  // `field` gives the material, the height and the flight effects of every state's request (its speed,
  // drop point and wind are the state's); it and `predictor` must outlive the cache.
  DiscStamps(predict::Predictor& predictor, const predict::PredictionRequest& field, double cell_m,
             double rpm_step_rpm);

  // The stamp of `state` (built now if new). Throws spread::Error (kArgument, "field setting") naming the
  // state when the predictor refuses it.
  const StampPattern& at(const DiscState& state);
  std::size_t size() const { return stamps_.size(); }
  double cell_m() const { return cell_m_; }

 private:
  using Key = std::tuple<int, long, long, long, long>;
  StampPattern build(const DiscState& state, double rpm) const;

  predict::Predictor& predictor_;
  predict::PredictionRequest field_;
  double cell_m_, rpm_step_rpm_, min_rpm_ = 0.0, max_rpm_ = 0.0;
  std::map<Key, StampPattern> stamps_;
};

}  // namespace spread::field
