#include "libspread/analysis/calibration/tray_analysis.hpp"

#include "libspread/analysis/calibration/cv_without_missing.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace spread::calibration {

double cv_target_from_percent(double percent, const std::string& option) {
  char text[256];
  if (!std::isfinite(percent) || !(percent >= kLeastCvTargetPercent) || percent > 100.0) {
    if (std::isfinite(percent) && percent > 0.0 && percent < kLeastCvTargetPercent) {
      std::snprintf(text, sizeof text,
                    "%s %g: the target is in per cent — %g would be %g %%, which no spreader reaches; for %g %% "
                    "write %s %g",
                    option.c_str(), percent, percent, percent, 100.0 * percent, option.c_str(), 100.0 * percent);
    } else {
      std::snprintf(text, sizeof text, "%s %g: the CV target must be in [%g, 100] %%", option.c_str(), percent,
                    kLeastCvTargetPercent);
    }
    throw std::invalid_argument(text);
  }
  return percent / 100.0;
}

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
  a.requested_bout_width_m = bout_width_m;
  for (int n = 2; n <= test.layout.tray_count; ++n) a.widths_m.push_back(n * test.layout.tray_width_m);
  a.cv_to_and_fro_curve.resize(a.widths_m.size());
  a.cv_racetrack_curve.resize(a.widths_m.size());
  if (bout_width_m > 0.0) a.bout_width_m = metrics::bout_tray_count(test.layout, bout_width_m) * test.layout.tray_width_m;

  // Measured trays carry no sampling standard error: the headline rule takes the widest band
  // (docs/metrics.md "Effective working width").
  const auto keep = [](const metrics::WorkingWidth& w, double& width_m, std::vector<std::pair<double, double>>& bands) {
    width_m = w.width_m;
    bands.clear();
    for (int b = 0; b < w.stored_bands(); ++b) bands.emplace_back(w.bands[b].lower_m, w.bands[b].upper_m);
  };
  if (!test.has_missing_trays()) {
    keep(metrics::working_width(test.layout_mass_kg, test.layout, Overlap::kToAndFro, cv_target),
         a.working_width_to_and_fro_m, a.bands_to_and_fro_m);
    keep(metrics::working_width(test.layout_mass_kg, test.layout, Overlap::kRacetrack, cv_target),
         a.working_width_racetrack_m, a.bands_racetrack_m);
    if (bout_width_m > 0.0) {
      a.cv_to_and_fro = metrics::cv_at_width(test.layout_mass_kg, test.layout, bout_width_m, Overlap::kToAndFro);
      a.cv_racetrack = metrics::cv_at_width(test.layout_mass_kg, test.layout, bout_width_m, Overlap::kRacetrack);
    }
    metrics::cv_curve(test.layout_mass_kg, test.layout, a.widths_m, Overlap::kToAndFro, a.cv_to_and_fro_curve);
    metrics::cv_curve(test.layout_mass_kg, test.layout, a.widths_m, Overlap::kRacetrack, a.cv_racetrack_curve);
    return a;
  }
  // Missing trays are left out of every bout they feed (cv_without_missing.hpp); the working widths
  // follow the same rule as metrics::effective_working_width, on this curve.
  auto cv = [&](int trays, Overlap overlap) {
    return cv_without_missing(test.layout_mass_kg, test.layout_missing, test.layout, trays, overlap);
  };
  for (std::size_t i = 0; i < a.widths_m.size(); ++i) {
    a.cv_to_and_fro_curve[i] = cv(static_cast<int>(i) + 2, Overlap::kToAndFro);
    a.cv_racetrack_curve[i] = cv(static_cast<int>(i) + 2, Overlap::kRacetrack);
  }
  // A bout left with less than two trays read has no CV (NaN): the rule runs over the widths that have one.
  auto working_width = [&](const std::vector<double>& curve) {
    std::vector<double> widths, cvs;
    for (std::size_t i = 0; i < curve.size(); ++i) {
      if (std::isnan(curve[i])) continue;
      widths.push_back(a.widths_m[i]);
      cvs.push_back(curve[i]);
    }
    return widths.empty() ? metrics::WorkingWidth{} : metrics::working_width_on_curve(widths, cvs, cv_target);
  };
  keep(working_width(a.cv_to_and_fro_curve), a.working_width_to_and_fro_m, a.bands_to_and_fro_m);
  keep(working_width(a.cv_racetrack_curve), a.working_width_racetrack_m, a.bands_racetrack_m);
  if (bout_width_m > 0.0) {
    const int n = metrics::bout_tray_count(test.layout, bout_width_m);
    a.cv_to_and_fro = cv(n, Overlap::kToAndFro);
    a.cv_racetrack = cv(n, Overlap::kRacetrack);
  }
  return a;
}

}  // namespace spread::calibration
