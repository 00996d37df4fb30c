#include "libspread/calibration/tray_analysis.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::calibration {

TrayTestAnalysis analyse_tray_test(const TrayTest& test, double cv_target, double bout_width_m) {
  if (!std::isfinite(cv_target) || !(cv_target > 0.0) || cv_target > 1.0) {
    throw std::invalid_argument("CV target must be in (0, 100] %, got " + std::to_string(100.0 * cv_target) + " %");
  }
  if (!std::isfinite(bout_width_m) || bout_width_m < 0.0) {
    throw std::invalid_argument("bout width must be >= 0 m, got " + std::to_string(bout_width_m));
  }
  using metrics::Overlap;
  TrayTestAnalysis a;
  a.total_mass_kg = test.total_mass_kg();
  a.cv_target = cv_target;
  a.throw_width_m = metrics::throw_width(test.layout_mass_kg, test.layout, 0.99);
  a.working_width_to_and_fro_m =
      metrics::effective_working_width(test.layout_mass_kg, test.layout, Overlap::kToAndFro, cv_target);
  a.working_width_racetrack_m =
      metrics::effective_working_width(test.layout_mass_kg, test.layout, Overlap::kRacetrack, cv_target);
  a.requested_bout_width_m = bout_width_m;
  if (bout_width_m > 0.0) {
    a.bout_width_m = metrics::bout_tray_count(test.layout, bout_width_m) * test.layout.tray_width_m;
    a.cv_to_and_fro = metrics::cv_at_width(test.layout_mass_kg, test.layout, bout_width_m, Overlap::kToAndFro);
    a.cv_racetrack = metrics::cv_at_width(test.layout_mass_kg, test.layout, bout_width_m, Overlap::kRacetrack);
  }
  for (int n = 2; n <= test.layout.tray_count; ++n) a.widths_m.push_back(n * test.layout.tray_width_m);
  a.cv_to_and_fro_curve.resize(a.widths_m.size());
  a.cv_racetrack_curve.resize(a.widths_m.size());
  metrics::cv_curve(test.layout_mass_kg, test.layout, a.widths_m, Overlap::kToAndFro, a.cv_to_and_fro_curve);
  metrics::cv_curve(test.layout_mass_kg, test.layout, a.widths_m, Overlap::kRacetrack, a.cv_racetrack_curve);
  return a;
}

}  // namespace spread::calibration
