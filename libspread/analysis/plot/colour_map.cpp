#include "libspread/analysis/plot/colour_map.hpp"

#include <cmath>

namespace spread::plot::detail {

Rgb colour_at(double t) {
  // Anchors sampled from the viridis map at t = 0, 0.25, 0.5, 0.75, 1.
  static constexpr Rgb kAnchors[] = {
      {0.267, 0.005, 0.329}, {0.230, 0.322, 0.546}, {0.128, 0.567, 0.551}, {0.369, 0.789, 0.383}, {0.993, 0.906, 0.144}};
  constexpr int kLast = 4;
  if (!(t > 0.0)) return kAnchors[0];
  if (t >= 1.0) return kAnchors[kLast];
  const double position = t * kLast;
  const int i = static_cast<int>(position);
  const double f = position - i;
  const Rgb& a = kAnchors[i];
  const Rgb& b = kAnchors[i + 1];
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

}  // namespace spread::plot::detail
