#include "libspread/analysis/calibration/disc_speed_check.hpp"

#include <cmath>
#include <cstdio>

namespace spread::calibration {

std::vector<std::string> disc_speed_warnings(const PatternFitResult& fit, double rpm) {
  std::vector<std::string> warnings;
  char text[512];
  const double s = fit.fitted.launch_speed_factor;
  if (fit.fitted_mask[kLaunchSpeed] && std::abs(s - 1.0) > kSpeedFactorTolerance) {
    std::snprintf(text, sizeof text,
                  "the launch speed factor %.3f is %.0f %% from 1 (warning beyond %.0f %%; vane wear or another "
                  "batch moves it by a few %%): launch speeds scale with the disc speed, so this test looks like "
                  "one at about %.0f rpm fitted at --rpm %g — check the disc speed of the tray test before using "
                  "the calibrated material",
                  s, 100.0 * std::abs(s - 1.0), 100.0 * kSpeedFactorTolerance, s * rpm, rpm);
    warnings.emplace_back(text);
  }
  const double offset_deg = fit.fitted.launch_angle_offset_rad * 180.0 / kPi;
  if (fit.fitted_mask[kAngleOffset] && std::abs(offset_deg) > kAngleOffsetTolerance_deg) {
    std::snprintf(text, sizeof text,
                  "the launch-angle offset %.1f deg is beyond %.0f deg (a moved drop point or worn vane turns "
                  "the launch by a few degrees): a feed or drop-point setting other than the table's scene, or a "
                  "disc speed other than --rpm %g — check both before using the calibrated material",
                  offset_deg, kAngleOffsetTolerance_deg, rpm);
    warnings.emplace_back(text);
  }
  return warnings;
}

}  // namespace spread::calibration
