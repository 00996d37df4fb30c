// Validation of a field boundary: what a GIS export, a hand-drawn polygon or a wrong unit gets wrong.
#include "libspread/analysis/field/boundary.hpp"

#include <algorithm>
#include <sstream>

#include "libspread/core/error.hpp"

namespace spread::field {
namespace {

[[noreturn]] void refuse_boundary(const std::string& where, const std::string& what) {
  throw Error(ErrorKind::kArgument, where, where + ": " + what);
}

void require_distinct_vertices(const Ring& ring, const std::string& where) {
  if (ring.size() < 3) {
    refuse_boundary(where, "the boundary has " + std::to_string(ring.size()) + " distinct vertices; a polygon needs at least 3");
  }
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point a = ring[i], b = ring[(i + 1) % ring.size()];
    if (length(b - a) < 1e-6) {
      refuse_boundary(where, "vertices " + std::to_string(i) + " and " + std::to_string((i + 1) % ring.size()) +
                        " of the boundary are the same point (a zero-length edge)");
    }
  }
}

void require_simple(const Ring& ring, const std::string& where) {
  const EdgePair crossing = first_self_intersection(ring);
  if (crossing.first < 0) return;
  const auto edge = [&](int i) {
    std::ostringstream out;
    const Point a = ring[static_cast<std::size_t>(i)], b = ring[(static_cast<std::size_t>(i) + 1) % ring.size()];
    out << "edge " << i << " (" << a.x_m << ", " << a.y_m << ")–(" << b.x_m << ", " << b.y_m << ")";
    return out.str();
  };
  refuse_boundary(where, "the boundary is self-intersecting: " + edge(crossing.first) + " crosses " + edge(crossing.second) +
                    " (vertices out of order, or a figure-of-eight)");
}

void require_field_size(double area_m2, const std::string& crs, const std::string& where) {
  std::ostringstream out;
  if (area_m2 < kMinFieldArea_m2) {
    out << "the boundary encloses " << area_m2 << " m² (in " << crs
        << "), less than a field's " << kMinFieldArea_m2
        << " m²: wrong units? (coordinates in degrees read as metres: give them as longitude/latitude)";
    refuse_boundary(where, out.str());
  }
  if (area_m2 > kMaxFieldArea_m2) {
    out << "the boundary encloses " << area_m2 / 1e4 << " ha (in " << crs << "), more than a field's "
        << kMaxFieldArea_m2 / 1e4 << " ha: wrong units? (centimetres or feet read as metres, or the wrong CRS)";
    refuse_boundary(where, out.str());
  }
}

}  // namespace

Boundary make_boundary(Ring ring, std::string crs, const std::string& where) {
  require_distinct_vertices(ring, where);
  require_simple(ring, where);
  double area_m2 = signed_area_m2(ring);
  if (area_m2 < 0.0) {
    std::reverse(ring.begin(), ring.end());
    area_m2 = -area_m2;
  }
  require_field_size(area_m2, crs, where);
  Boundary b;
  b.ring = std::move(ring);
  b.crs = std::move(crs);
  b.area_m2 = area_m2;
  b.min_x_m = b.max_x_m = b.ring[0].x_m;
  b.min_y_m = b.max_y_m = b.ring[0].y_m;
  for (const Point& p : b.ring) {
    b.min_x_m = std::min(b.min_x_m, p.x_m);
    b.max_x_m = std::max(b.max_x_m, p.x_m);
    b.min_y_m = std::min(b.min_y_m, p.y_m);
    b.max_y_m = std::max(b.max_y_m, p.y_m);
  }
  return b;
}

}  // namespace spread::field
