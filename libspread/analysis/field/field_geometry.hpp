#pragma once
// Plane geometry of a field in metres: x east, y north of a projected coordinate reference system
// (projection.hpp), or of a local frame already in metres. A ring is a polygon's vertices in order, not
// repeated at the end (the GeoJSON reader checks and drops the closing vertex).
#include <cmath>
#include <vector>

namespace spread::field {

struct Point {
  double x_m = 0.0;
  double y_m = 0.0;
};
using Ring = std::vector<Point>;

inline Point operator+(Point a, Point b) { return {a.x_m + b.x_m, a.y_m + b.y_m}; }
inline Point operator-(Point a, Point b) { return {a.x_m - b.x_m, a.y_m - b.y_m}; }
inline Point operator*(double s, Point a) { return {s * a.x_m, s * a.y_m}; }
inline double dot(Point a, Point b) { return a.x_m * b.x_m + a.y_m * b.y_m; }
inline double cross(Point a, Point b) { return a.x_m * b.y_m - a.y_m * b.x_m; }
inline double length(Point a) { return std::hypot(a.x_m, a.y_m); }

// Signed area (m²) by the shoelace formula: positive for a counter-clockwise ring.
double signed_area_m2(const Ring& ring);

// Whether segments [a, b] and [c, d] share a point (touching counts).
bool segments_meet(Point a, Point b, Point c, Point d);

// The first pair of non-adjacent edges of the ring that meet (edge i runs from vertex i to i + 1), or
// {-1, -1} when the ring is simple. O(n²): a field boundary has at most a few thousand vertices.
struct EdgePair {
  int first = -1;
  int second = -1;
};
EdgePair first_self_intersection(const Ring& ring);

// Even–odd rule: whether the point lies inside the ring.
bool contains(const Ring& ring, Point p);

}  // namespace spread::field
