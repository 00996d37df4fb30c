// The wind in the machine frame at a binned heading (field_wind.hpp).
#include "libspread/analysis/field/field_wind.hpp"

#include <cmath>
#include <numbers>

namespace spread::field {
namespace {

// The heading bin of a direction (unit vector, east and north components): bin k is centred on the
// compass heading k · 360°/kHeadingBins.
int heading_bin(Point forward) {
  const double compass = std::atan2(forward.x_m, forward.y_m);  // clockwise from north
  const double turns = compass / (2.0 * std::numbers::pi);
  return static_cast<int>(std::lround(turns * kHeadingBins + kHeadingBins)) % kHeadingBins;
}
Point bin_forward(int bin) {
  const double compass = 2.0 * std::numbers::pi * bin / kHeadingBins;
  return {std::sin(compass), std::cos(compass)};
}

}  // namespace

Point wind_in_machine_frame(Point forward, double wind_east_m_s, double wind_north_m_s) {
  const Point f = bin_forward(heading_bin(forward));
  const Point w{wind_east_m_s, wind_north_m_s};
  return {dot(w, {f.y_m, -f.x_m}), dot(w, f)};
}

}  // namespace spread::field
