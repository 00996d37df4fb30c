#pragma once
// Automatic mode's inverse problem: the disc speed whose first band of bout widths within the CV target
// (SpreadPrediction::first_band_width_m) reaches the set-point working width — every narrower bout then
// meets the target too, and the width grows steadily with the speed. (The headline working width can
// jump to a wider band: at 450 rpm the main job's Urea headline is 11.6 m, its first band 5.9 m, and a
// set-point of 8 m lies between the two bands.)
//
// One prediction through the C API costs milliseconds (measured 3.8 ms on the default tables), so a
// search inside the 50 ms loop step must be bounded. The width does not depend on the bout width, only
// on material and speed: the ECU samples width(rpm) once per material at start (WidthCurve), and a
// solve in the loop is a scan of that curve for the first sample reaching the set-point plus a few
// bisection steps between that sample and the one before (max_bisections predictions). Table-based
// widths are neither smooth nor monotonic (tray quantisation), which the first-crossing scan tolerates.
#include <string>
#include <string_view>
#include <vector>

#include "libspread/control/spread_predictor.hpp"

namespace spread::firmware {

struct RpmSolverSettings {
  double curve_rpm_step = 5.0;      // spacing of the precomputed width curve [r/min]
  int max_bisections = 3;           // predictions spent refining between two curve samples per solve
  double width_tolerance_m = 0.5;   // |width - set-point| accepted as "reached" at a range end [m] (one tray)
  // The ECU asks the solver for the set-point plus a margin, and widens the margin by a step each time
  // the pattern at the settled disc speed still misses the set-point, up to the maximum.
  double width_margin_m = 0.5;        // [m]
  double width_margin_step_m = 0.5;   // [m]
  double max_width_margin_m = 2.0;    // [m]
};

// Effective width sampled over a speed range for one material.
struct WidthCurve {
  std::string material;
  std::vector<double> rpm;       // ascending [r/min]
  std::vector<double> width_m;   // first band's width at rpm[i] [m]; NaN where the prediction failed
};

// Samples [range.min_rpm, range.max_rpm] every `rpm_step`. Throws std::invalid_argument on a bad range.
WidthCurve sample_width_curve(SpreadPredictor& predictor, std::string_view material, RpmRange range,
                              double rpm_step);

struct RpmSolution {
  double rpm = 0.0;                 // chosen disc speed [r/min]
  double effective_width_m = 0.0;   // predicted first band's width at `rpm` [m]
  bool reachable = false;           // false: the set-point lies outside what the range can deliver
  bool prediction_failed = false;   // a refinement prediction returned an error
  int predictions = 0;              // predictor calls spent in this solve (cost indicator)
};

class RpmForWidthSolver {
 public:
  explicit RpmForWidthSolver(RpmSolverSettings settings = {});

  // Out of reach: the curve's widest sample (too wide) or its slowest sample (too narrow).
  RpmSolution solve(SpreadPredictor& predictor, const WidthCurve& curve, double width_setpoint_m) const;

  const RpmSolverSettings& settings() const { return settings_; }

 private:
  RpmSolverSettings settings_;
};

}  // namespace spread::firmware
