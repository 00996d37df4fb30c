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
  // Poisson deviate of mean `mean` >= 0: Knuth's product of uniforms below 30, above it the normal
  // approximation rounded (its relative error in the sd is < 2 % there, and it is never below 0 in
  // practice: 30 is 5.5 sd above 0).
  long poisson(double mean);

 private:
  double uniform_open();  // (-1, 1) from 53 random bits
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace spread::calibration
