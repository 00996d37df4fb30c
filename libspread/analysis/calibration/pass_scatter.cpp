#include "libspread/analysis/calibration/pass_scatter.hpp"

#include <cmath>

namespace spread::calibration {

// kResidualToScatterLimit = 3: a correct model leaves a residual rms about equal to the scatter of the
// mean (ratio 1, ±11 % from the estimate of the scatter, plus the model's own sampling of the launch):
// 0.86 for the example file fitted at its 600 rpm, 1.01 for a synthetic 750 rpm test fitted at 750 rpm,
// but 12.3 for that test fitted at 600 rpm (docs/field-calibration.md). A ratio of 3 is a residual
// variance 9 times the tray test's noise — the prediction then misses the pattern by far more than the
// test can measure (a wrong rpm, a wrong inlet, trays off the centre line), and the fitted values
// describe the model's compromise, not the material.

PassScatter pass_scatter(const TrayTest& test) {
  PassScatter r;
  const std::size_t passes = test.pass_mass_kg.size();
  r.passes = static_cast<int>(passes);
  if (passes < 2) return r;
  const std::size_t trays = test.position_m.size();
  auto read_in_all = [&](std::size_t i) {
    for (const auto& pass : test.pass_mass_kg) {
      if (i >= pass.size() || std::isnan(pass[i])) return false;
    }
    return true;
  };
  std::vector<double> pass_total_kg(passes, 0.0);
  for (std::size_t i = 0; i < trays; ++i) {
    if (!read_in_all(i)) continue;
    ++r.trays;
    for (std::size_t p = 0; p < passes; ++p) pass_total_kg[p] += test.pass_mass_kg[p][i];
  }
  for (double total : pass_total_kg) {
    if (!(total > 0.0)) return r;  // a pass with nothing in the trays read in all passes: no shape
  }
  if (r.trays < 2) return r;
  double sum_of_variances = 0.0;
  for (std::size_t i = 0; i < trays; ++i) {
    if (!read_in_all(i)) continue;
    double mean = 0.0;
    for (std::size_t p = 0; p < passes; ++p) mean += test.pass_mass_kg[p][i] / pass_total_kg[p];
    mean /= static_cast<double>(passes);
    double squares = 0.0;
    for (std::size_t p = 0; p < passes; ++p) {
      const double d = test.pass_mass_kg[p][i] / pass_total_kg[p] - mean;
      squares += d * d;
    }
    sum_of_variances += squares / static_cast<double>(passes - 1);
  }
  // Over the layout's trays, as the fit's residual rms is (padded and missing trays add nothing).
  const double n = static_cast<double>(test.layout.tray_count - test.missing_trays());
  double mean_pass_kg = 0.0;
  for (double total : pass_total_kg) mean_pass_kg += total / static_cast<double>(passes);
  r.rms_one_pass_fraction = std::sqrt(sum_of_variances / n);
  r.rms_mean_fraction = r.rms_one_pass_fraction / std::sqrt(static_cast<double>(passes));
  r.rms_one_pass_g = 1e3 * r.rms_one_pass_fraction * mean_pass_kg;
  r.available = true;
  return r;
}

}  // namespace spread::calibration
