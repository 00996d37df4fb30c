#pragma once
// Synthetic tray tests (docs/field-calibration.md, "Example data"): the pattern model's prediction at
// known parameters, spread over the trays in grams, plus seeded measurement noise per pass. For tests of
// the pattern fit (does it recover what made the data, within its reported uncertainty?) and for the
// example files, which are made with `spread calibrate synth` so their answers are known.
//
// Noise of one tray reading in one pass, in grams (independent between trays and passes), m being the
// tray's expected mass in that pass:
//   reading = granule_mass_g · N + sqrt((relative_sd · m)² + floor_sd_g²) · Z,  N ~ Poisson(m / granule_mass_g)
// a counting part (the tray catches a whole number of granules; variance granule_mass_g · m; with
// granule_mass_g = 0 the reading is centred on m exactly), a relative part (the stream's pass-to-pass
// variation) and an additive floor (scale error, stray dust). A reading below 0 is written as 0 — the tray
// CSV refuses negative masses, and a technician writes 0 for an empty tray — so a floor biases empty
// trays upwards by about 0.4 floor_sd_g, as in real data; the relative and counting parts vanish with
// m and bias nothing. Readings are rounded to resolution_g.
#include <cstdint>
#include <vector>

#include "libspread/analysis/calibration/pattern_model.hpp"

namespace spread::calibration {

struct TrayNoise {
  double relative_sd = 0.08;      // fraction of the tray's mass
  double granule_mass_g = 0.0;    // g per granule; 0 = no counting noise
  double floor_sd_g = 0.0;        // g, additive
  double resolution_g = 0.001;    // g; readings are rounded to this (0 = not rounded)
};

struct SyntheticTrayTest {
  std::vector<double> position_m;              // tray centres of the model's layout
  std::vector<double> expected_g;              // noise-free mass per tray and pass
  std::vector<std::vector<double>> pass_mass_g;  // [pass][tray], noisy readings
};

// `total_mass_g`: expected mass caught by all trays in one pass. Throws std::invalid_argument for
// passes < 1, a total <= 0, negative noise parameters, or parameters the model refuses.
SyntheticTrayTest synthetic_tray_test(const PatternModel& model, const PatternParameters& truth,
                                      double total_mass_g, int passes, const TrayNoise& noise,
                                      std::uint64_t seed);

}  // namespace spread::calibration
