#include "libspread/analysis/calibration/synthetic_tray_test.hpp"

#include <cmath>
#include <stdexcept>

#include "libspread/analysis/calibration/normal_noise.hpp"

namespace spread::calibration {

SyntheticTrayTest synthetic_tray_test(const PatternModel& model, const PatternParameters& truth,
                                      double total_mass_g, int passes, const TrayNoise& noise,
                                      std::uint64_t seed) {
  if (passes < 1) throw std::invalid_argument("synthetic tray test: passes must be >= 1");
  if (!std::isfinite(total_mass_g) || !(total_mass_g > 0.0)) {
    throw std::invalid_argument("synthetic tray test: total mass must be > 0 g");
  }
  for (double v : {noise.relative_sd, noise.granule_mass_g, noise.floor_sd_g, noise.resolution_g}) {
    if (!std::isfinite(v) || v < 0.0) throw std::invalid_argument("synthetic tray test: noise parameters must be >= 0");
  }
  const std::vector<double> fraction = model.tray_fractions(truth);
  double caught = 0.0;
  for (double f : fraction) caught += f;
  if (!(caught > 0.0)) throw std::invalid_argument("synthetic tray test: the pattern misses every tray");

  SyntheticTrayTest test;
  const metrics::TrayLayout& layout = model.trays();
  NormalNoise normal(seed);
  for (int k = 0; k < layout.tray_count; ++k) {
    test.position_m.push_back(layout.centre_m(k));
    test.expected_g.push_back(total_mass_g * fraction[static_cast<std::size_t>(k)] / caught);
  }
  test.pass_mass_g.assign(static_cast<std::size_t>(passes), std::vector<double>(test.expected_g.size()));
  for (auto& pass : test.pass_mass_g) {
    for (std::size_t k = 0; k < pass.size(); ++k) {
      const double m = test.expected_g[k];
      // Granules caught: a Poisson count (never negative, so no clipping bias at the sparse edges).
      double granules_g = m;
      if (noise.granule_mass_g > 0.0) granules_g = noise.granule_mass_g * static_cast<double>(normal.poisson(m / noise.granule_mass_g));
      const double sd = std::sqrt(noise.relative_sd * noise.relative_sd * m * m + noise.floor_sd_g * noise.floor_sd_g);
      double reading = std::max(0.0, granules_g + sd * normal.next());
      if (noise.resolution_g > 0.0) reading = noise.resolution_g * std::round(reading / noise.resolution_g);
      pass[k] = reading;
    }
  }
  return test;
}

}  // namespace spread::calibration
