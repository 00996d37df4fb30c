#pragma once
// Mean and sample standard deviation (n − 1) of repeated measurements of one figure, for the studies'
// replicate and subset spreads. The standard deviation is NaN below two values (no spread is measured),
// the mean NaN for none.
#include <cmath>
#include <limits>
#include <vector>

namespace spread::accuracy::detail {

struct MeanSd {
  double mean = std::numeric_limits<double>::quiet_NaN();
  double sd = std::numeric_limits<double>::quiet_NaN();
};

inline MeanSd mean_sd(const std::vector<double>& values) {
  MeanSd r;
  if (values.empty()) return r;
  double sum = 0.0;
  for (double x : values) sum += x;
  r.mean = sum / static_cast<double>(values.size());
  if (values.size() < 2) return r;
  double squares = 0.0;
  for (double x : values) squares += (x - r.mean) * (x - r.mean);
  r.sd = std::sqrt(squares / static_cast<double>(values.size() - 1));
  return r;
}

}  // namespace spread::accuracy::detail
