#pragma once
// Golden-section search for the lowest value of a one-dimensional function over an interval, as the
// setting searches (setting_chart, wind_compensation) refine a grid's best point.
#include <algorithm>
#include <utility>

namespace spread::predict {

// The lowest f over [low, high], narrowed down to `tolerance`, against the best so far (best_x, best_f):
// returns the lower of the two as (x, f(x)). Each step costs one evaluation of f.
template <typename F>
std::pair<double, double> golden_section_minimum(F f, double low, double high, double best_x, double best_f,
                                                 double tolerance) {
  constexpr double kInverseGolden = 0.6180339887498949;  // (√5 − 1)/2
  if (!(high - low > tolerance)) return {best_x, best_f};
  double a = low, b = high;
  double c = b - kInverseGolden * (b - a), d = a + kInverseGolden * (b - a);
  double fc = f(c), fd = f(d);
  while (b - a > tolerance) {
    if (fc <= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - kInverseGolden * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + kInverseGolden * (b - a);
      fd = f(d);
    }
  }
  const double x = fc <= fd ? c : d, value = std::min(fc, fd);
  return value < best_f ? std::pair{x, value} : std::pair{best_x, best_f};
}

}  // namespace spread::predict
