#pragma once
// Wind compensation: the per-disc settings that bring the CV at a bout width back towards the target in a
// crosswind. A wind across the driving direction carries the whole pattern downwind, so the passes no
// longer overlap as in still air. A twin-disc spreader answers by throwing further on the upwind side and
// shorter on the downwind side, and by turning both fans against the wind: here the discs' speeds move
// apart by ±δ (the left disc +δ) and their drop points turn by ±θ (the left disc +θ, the right −θ in its
// own mirrored frame, so both fans turn the same way seen from above), from the present setting.
//
// Search (deterministic, bounded): a coarse grid of kCoarseSteps × kCoarseSteps over δ and θ, then
// golden-section search along δ and then along θ around the grid's best, to the tolerances below; a
// refinement keeps a point only when it is lower. Every prediction of the search is made without
// standard errors (PredictionRequest::standard_errors); the answer is predicted once more with them.
// No allocation: the predictions go into the caller's Prediction and workspace.
#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

struct WindCompensationLimits {
  double max_speed_offset_rpm = 150.0;          // |δ| at most (and both discs stay within the table's rows)
  double max_drop_point_turn_rad = 0.7853981633974483;  // |θ| at most (45°; both turns stay within ±π)
  double speed_tolerance_rpm = 4.0;
  double drop_point_tolerance_rad = 0.008726646259971648;  // 0.5°
};

inline constexpr int kCoarseSteps = 5;

struct WindCompensation {
  PredictStatus status = PredictStatus::kOk;  // of the present setting's request (kOk: searched)
  double speed_offset_rpm = 0.0;              // δ found
  double drop_point_turn_rad = 0.0;           // θ found
  DiscSetting discs[2];                       // the compensated setting (kLeftDisc, kRightDisc)
  double present_cv = 0.0;                    // to-and-fro CV at the bout in the wind, present setting
  double cv = 0.0;                            // the same at the compensated setting (`out` has it ± SE)
  int predictions = 0;
};

// `request`: the present setting (rpm, drop point, or each disc's own), the wind, the bout width (> 0)
// and the CV target. On success `out` is the prediction at the compensated setting (with standard
// errors; out.discs says the setting). A request the predictor refuses is returned as its status, and
// kOutOfRange without a bout width or on a one-disc machine; `out` is then unchanged.
WindCompensation compensate_wind(const Predictor& predictor, const PredictionRequest& request, Prediction& out,
                                 PredictorWorkspace& workspace, const WindCompensationLimits& limits = {});

}  // namespace spread::predict
