#include "libspread/calibration/normal_noise.hpp"

#include <cmath>

namespace spread::calibration {

double NormalNoise::uniform_open() {
  const double unit = static_cast<double>(engine_() >> 11) * 0x1.0p-53;  // [0, 1)
  return 2.0 * unit - 1.0;
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

}  // namespace spread::calibration
