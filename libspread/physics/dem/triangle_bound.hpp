#pragma once
// A lower bound of the squared distance from a point to a triangle, from four planes: the triangle's own
// and, normal to it, one through each edge facing away from the triangle. The offset from a point p to its
// closest point on the triangle splits into the part along the normal, h = |n·(p − a)|, and the part in the
// plane, which is at least how far p lies past the edge line it is furthest outside of, s = max_e m_e·(p − v_e)
// (the triangle lies on the inner side of each edge plane):  d² ≥ h² + max(0, s)².  Four dot products and
// no branch on the region, where the exact closest point (closest_point_on_triangle) walks the Voronoi
// regions; the mesh queries test a triangle exactly only when this bound lets it touch.
#include <cmath>
#include <limits>

#include <Eigen/Geometry>  // cross products

#include "libspread/core/vec3.hpp"

namespace spread::dem {

struct TriangleBound {
  double normal[3] = {0.0, 0.0, 0.0};  // unit; zero for a triangle without a defined normal
  double normal_offset_m = 0.0;        // normal · a
  double edge_normal[3][3] = {};       // unit, in the plane, outward from edge e (vertices e, e + 1)
  // normal · the edge's first vertex; +∞ for a triangle without a defined normal: then the bound is 0,
  // and the triangle is always tested exactly.
  double edge_offset_m[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::infinity()};
};

inline TriangleBound triangle_bound(const Vec3& a, const Vec3& b, const Vec3& c) {
  TriangleBound t;
  const Vec3 cross = (b - a).cross(c - a);
  const double length = cross.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return t;
  const Vec3 n = cross / length;
  const Vec3 v[3] = {a, b, c};
  for (int e = 0; e < 3; ++e) {
    // (v_{e+1} − v_e) × n points away from the triangle for counter-clockwise vertices about n.
    const Vec3 m = (v[(e + 1) % 3] - v[e]).cross(n).normalized();
    if (!m.allFinite()) return TriangleBound{};
    for (int k = 0; k < 3; ++k) t.edge_normal[e][k] = m[k];
    t.edge_offset_m[e] = m.dot(v[e]);
  }
  for (int k = 0; k < 3; ++k) t.normal[k] = n[k];
  t.normal_offset_m = n.dot(a);
  return t;
}

inline double distance2_lower_bound_m2(const TriangleBound& t, const Vec3& p) {
  const double h = t.normal[0] * p.x() + t.normal[1] * p.y() + t.normal[2] * p.z() - t.normal_offset_m;
  double s = 0.0;
  for (int e = 0; e < 3; ++e)
    s = std::max(s, t.edge_normal[e][0] * p.x() + t.edge_normal[e][1] * p.y() + t.edge_normal[e][2] * p.z() - t.edge_offset_m[e]);
  return h * h + s * s;
}

}  // namespace spread::dem
