#pragma once
// Standard normal deviates from std::mt19937_64 by the Marsaglia polar method: std::normal_distribution
// differs between standard libraries, and synthetic tray tests must be the same everywhere.
#include <cstdint>
#include <random>

namespace spread::calibration {

class NormalNoise {
 public:
  explicit NormalNoise(std::uint64_t seed) : engine_(seed) {}
  double next();  // mean 0, sd 1

 private:
  double uniform_open();  // (-1, 1) from 53 random bits
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace spread::calibration
