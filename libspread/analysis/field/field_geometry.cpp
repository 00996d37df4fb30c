// Plane geometry of field rings: area, simplicity and point location.
#include "libspread/analysis/field/field_geometry.hpp"

#include <algorithm>

namespace spread::field {

double signed_area_m2(const Ring& ring) {
  double twice = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    twice += cross(ring[i], ring[(i + 1) % ring.size()]);
  }
  return 0.5 * twice;
}

namespace {
// Orientation of c relative to the directed line a→b: +1 left, −1 right, 0 on it (to a tolerance of
// 1e-9 of the squared lengths involved: vertices a few kilometres from the origin keep 1e-7 m).
int orientation(Point a, Point b, Point c) {
  const Point ab = b - a, ac = c - a;
  const double value = cross(ab, ac);
  const double scale = 1e-12 * (dot(ab, ab) + dot(ac, ac));
  return value > scale ? 1 : (value < -scale ? -1 : 0);
}
bool on_segment(Point a, Point b, Point p) {
  return std::min(a.x_m, b.x_m) <= p.x_m && p.x_m <= std::max(a.x_m, b.x_m) && std::min(a.y_m, b.y_m) <= p.y_m &&
         p.y_m <= std::max(a.y_m, b.y_m);
}
}  // namespace

bool segments_meet(Point a, Point b, Point c, Point d) {
  const int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  const int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) || (o3 == 0 && on_segment(c, d, a)) ||
         (o4 == 0 && on_segment(c, d, b));
}

EdgePair first_self_intersection(const Ring& ring) {
  const int n = static_cast<int>(ring.size());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      // Neighbouring edges share a vertex by construction; only their overlap along a line would count,
      // and a repeated or back-tracking vertex is caught as a zero-length or folded edge elsewhere.
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;
      if (segments_meet(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n])) return {i, j};
    }
  }
  return {};
}

bool contains(const Ring& ring, Point p) {
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Point a = ring[i], b = ring[j];
    if ((a.y_m > p.y_m) != (b.y_m > p.y_m) &&
        p.x_m < (b.x_m - a.x_m) * (p.y_m - a.y_m) / (b.y_m - a.y_m) + a.x_m) {
      inside = !inside;
    }
  }
  return inside;
}

}  // namespace spread::field
