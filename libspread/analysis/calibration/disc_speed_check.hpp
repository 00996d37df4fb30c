#pragma once
// Whether a pattern fit's launch correction says the disc speed given (--rpm) was not the tray test's.
// Launch speeds scale with the disc's rim speed, so a test at 600 r/min fitted at 750 r/min returns a
// launch speed factor of about 600 / 750 = 0.8, and since the table's launch direction changes with the
// disc speed, a launch-angle offset too (the walkthrough's test: 0.802 and 11.9°). The fit converges
// and would write that error into every rpm row of the calibrated material. What the correction is for —
// a worn vane, another batch of the material, a moved drop point — moves the launches by a few per cent
// and a few degrees (the walkthrough's machine: 5 % slower, 4° later).
#include <string>
#include <vector>

#include "libspread/analysis/calibration/pattern_fit.hpp"

namespace spread::calibration {

// Three times the walkthrough's 5 %: beyond, a disc speed off by as much is likelier than wear. 15 % is
// also the step between common disc speeds (e.g. 640 and 750 r/min).
inline constexpr double kSpeedFactorTolerance = 0.15;
// 2.5 times the walkthrough's 4°: a feed or drop-point setting other than the table's, or a wrong disc
// speed.
inline constexpr double kAngleOffsetTolerance_deg = 10.0;

// One warning per fitted parameter beyond its tolerance, naming the value, the tolerance and why, and
// for the speed factor the disc speed it implies (factor × rpm). Empty when neither is fitted or both
// are within.
std::vector<std::string> disc_speed_warnings(const PatternFitResult& fit, double rpm);

}  // namespace spread::calibration
