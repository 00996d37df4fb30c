#pragma once
// Wind compensation: the per-disc settings that bring the CV at a bout width back towards the target in a
// crosswind. A wind across the driving direction carries every pass's pattern downwind — on the ground the
// same way whichever way the pass is driven, so the field's passes still overlap at the bout width, but
// each pattern is bent out of shape (the upwind side shortened, the downwind side stretched). A twin-disc
// spreader answers with each disc's own speed and drop point, set for the heading: the setting found is
// the outgoing pass's, and on the return pass, which meets the wind from the other side, the discs swap
// settings (the left disc takes the right disc's and the right the left's: ReturnPassSettings::kSwapped).
// The CVs are the field's (docs/metrics.md "To-and-fro in wind"): the present setting kept on both
// headings (kSame), the answer swapped with the heading — for a lateral wind the racetrack overlap of the
// outgoing pattern. Each disc's speed and drop point:
// here each disc's speed and drop-point turn (the right disc's in its own mirrored frame) are searched on
// their own, within the limits below and the drop-point turns the table validates
// (Predictor::drop_point_turn_range).
//
// The discs fly apart, so the pattern of a setting is the sum of each disc's landings: a disc is flown once
// per setting tried and combined with the other disc's trays as they stand, on one tray layout and kernel
// (the present setting's kernel; trays wide enough for the fastest speed searched). Search (deterministic,
// bounded, the disc the wind comes from first): for each disc, a grid of kWindSpeedSteps speeds times
// drop-point turns every kWindTurnStep_rad over its range, the other disc held; then, for kWindRefineRounds
// rounds, golden-section search along each disc's speed and drop point within one grid step of its best,
// to the tolerances below. A refinement keeps a point only when it is lower. Every prediction of the
// search is made without standard errors (PredictionRequest::standard_errors); the answer is predicted
// once more with them, on its own trays — and the present setting instead should that come out higher, so
// the answer is never worse than the present setting.
// No allocation: the predictions go into the caller's Prediction and workspace, the trays into the
// workspace's search buffer (PredictorWorkspace::search_buffer).
#include <limits>

#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

struct WindCompensationLimits {
  double max_speed_offset_rpm = 150.0;  // each disc within ± this of its present speed (and within the rows)
  // Each disc's drop point within ± this of its present one (and within the table's validated turns).
  double max_drop_point_turn_rad = 1.5707963267948966;  // 90°
  double speed_tolerance_rpm = 2.0;
  double drop_point_tolerance_rad = 0.008726646259971648;  // 0.5°
  // The budget: at most this many predictions (at least kWindMinPredictions: the present setting's, the
  // answer's and the present setting's again should the answer come out higher). A setting the budget
  // leaves no prediction for is not flown (it ranks as no better); the search goes on in its order with
  // the settings it has, so the answer is the best of those flown (WindCompensation::finished false).
  // Unlimited, the whole search.
  int max_predictions = std::numeric_limits<int>::max();
};
inline constexpr int kWindMinPredictions = 3;

inline constexpr int kWindSpeedSteps = 3;                          // grid speeds per disc, over its range
inline constexpr double kWindTurnStep_rad = 0.17453292519943295;  // 10°
inline constexpr int kWindRefineRounds = 2;

struct WindCompensation {
  PredictStatus status = PredictStatus::kOk;  // of the present setting's request (kOk: searched)
  DiscSetting discs[2];                       // the compensated setting (kLeftDisc, kRightDisc)
  double present_cv = 0.0;                    // to-and-fro CV at the bout in the wind, present setting kept
  double cv = 0.0;                            // the same with the compensated setting, swapped on the return
                                              // pass (`out` has it ± SE)
  int predictions = 0;
  bool finished = true;                       // false: the budget left settings of the search unflown
};

// `request`: the present setting (rpm, drop point, or each disc's own), the wind, the bout width (> 0)
// and the CV target. On success `out` is the prediction at the compensated setting (with standard
// errors; out.discs says the setting). A request the predictor refuses is returned as its status, and
// kOutOfRange without a bout width or on a one-disc machine; `out` is then unchanged.
WindCompensation compensate_wind(const Predictor& predictor, const PredictionRequest& request, Prediction& out,
                                 PredictorWorkspace& workspace, const WindCompensationLimits& limits = {});

}  // namespace spread::predict
