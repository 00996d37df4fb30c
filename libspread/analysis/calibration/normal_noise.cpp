#include "libspread/analysis/calibration/normal_noise.hpp"

#include <algorithm>
#include <cmath>

#include "libspread/core/unit_uniform.hpp"

namespace spread::calibration {

double NormalNoise::uniform_open() {
  return 2.0 * unit_uniform(engine_()) - 1.0;
}

double NormalNoise::next() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u = 0.0, v = 0.0, s = 0.0;
  do {
    u = uniform_open();
    v = uniform_open();
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * factor;
  has_spare_ = true;
  return u * factor;
}

long NormalNoise::poisson(double mean) {
  if (!(mean > 0.0)) return 0;
  if (mean < 30.0) {
    const double limit = std::exp(-mean);
    long count = 0;
    double product = 0.5 * (uniform_open() + 1.0);
    while (product > limit) {
      ++count;
      product *= 0.5 * (uniform_open() + 1.0);
    }
    return count;
  }
  return std::max(0L, std::lround(mean + std::sqrt(mean) * next()));
}

}  // namespace spread::calibration
