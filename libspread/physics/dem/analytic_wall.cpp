#include "libspread/physics/dem/analytic_wall.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spread::dem {

AnalyticPiece make_plane(const Vec3& point, const Vec3& normal) {
  if (!(normal.norm() > 0.0)) throw std::invalid_argument("plane wall: normal must be non-zero");
  AnalyticPiece p;
  p.kind = PieceKind::kPlane;
  p.origin = point;
  p.normal = normal.normalized();
  return p;
}

AnalyticPiece make_cone_disc(double radius_m, double cone_angle_rad, double z_apex_m) {
  if (!(radius_m > 0.0)) throw std::invalid_argument("disc wall: radius must be > 0");
  if (!(std::abs(cone_angle_rad) < 0.5 * kPi)) throw std::invalid_argument("disc wall: |cone angle| must be < π/2");
  AnalyticPiece p;
  p.kind = PieceKind::kRevolution;
  p.rho0_m = 0.0;
  p.z0_m = z_apex_m;
  p.rho1_m = radius_m;
  p.z1_m = z_apex_m + radius_m * std::tan(cone_angle_rad);
  // Upper side of the generator (cos α, sin α) is (−sin α, cos α).
  p.side_rho = -std::sin(cone_angle_rad);
  p.side_z = std::cos(cone_angle_rad);
  return p;
}

AnalyticPiece make_cylinder_inner(double radius_m, double z_min_m, double z_max_m) {
  if (!(radius_m > 0.0) || !(z_max_m > z_min_m)) throw std::invalid_argument("cylinder wall: need radius > 0 and z_max > z_min");
  AnalyticPiece p;
  p.kind = PieceKind::kRevolution;
  p.rho0_m = radius_m;
  p.z0_m = z_min_m;
  p.rho1_m = radius_m;
  p.z1_m = z_max_m;
  p.side_rho = -1.0;
  p.side_z = 0.0;
  return p;
}

AnalyticPiece make_rectangle(const Vec3& origin, const Vec3& axis_u, double length_u_m, const Vec3& axis_v,
                             double length_v_m) {
  if (!(length_u_m > 0.0) || !(length_v_m > 0.0)) throw std::invalid_argument("rectangle wall: side lengths must be > 0");
  AnalyticPiece p;
  p.kind = PieceKind::kRectangle;
  p.origin = origin;
  p.axis_u = axis_u.normalized();
  // Orthogonalise v against u so the clamp below is a true closest-point projection.
  p.axis_v = (axis_v - axis_v.dot(p.axis_u) * p.axis_u).normalized();
  p.length_u_m = length_u_m;
  p.length_v_m = length_v_m;
  p.normal = p.axis_u.cross(p.axis_v);
  return p;
}

bool closest_point(const AnalyticPiece& piece, const Vec3& c, double radius_m, WallHit& hit) {
  switch (piece.kind) {
    case PieceKind::kPlane: {
      const double d = (c - piece.origin).dot(piece.normal);
      if (d >= radius_m || d < 0.0) return false;
      hit.distance_m = d;
      hit.normal = piece.normal;
      hit.point = c - d * piece.normal;
      return true;
    }
    case PieceKind::kRevolution: {
      // Work in the meridian half-plane of the centre: (ρ, z). Exact for a surface of revolution.
      const double rho = std::sqrt(c.x() * c.x() + c.y() * c.y());  // not std::hypot: no overflow at these sizes, and it is a hot path
      const double er_x = rho > 1e-15 ? c.x() / rho : 1.0;
      const double er_y = rho > 1e-15 ? c.y() / rho : 0.0;
      const double gr = piece.rho1_m - piece.rho0_m, gz = piece.z1_m - piece.z0_m;
      const double len2 = gr * gr + gz * gz;
      double s = ((rho - piece.rho0_m) * gr + (c.z() - piece.z0_m) * gz) / len2;
      s = std::clamp(s, 0.0, 1.0);
      const double qr = piece.rho0_m + s * gr, qz = piece.z0_m + s * gz;
      const double dr = rho - qr, dz = c.z() - qz;
      // One-sided: a centre behind the surface is not in contact (it fell past the rim, say).
      if (dr * piece.side_rho + dz * piece.side_z < 0.0) return false;
      const double dist2 = dr * dr + dz * dz;
      if (dist2 >= radius_m * radius_m) return false;
      const double dist = std::sqrt(dist2);
      hit.distance_m = dist;
      double nr = piece.side_rho, nz = piece.side_z;
      if (dist > 1e-12 * radius_m) { nr = dr / dist; nz = dz / dist; }
      hit.normal = Vec3(nr * er_x, nr * er_y, nz);
      hit.point = Vec3(qr * er_x, qr * er_y, qz);
      return true;
    }
    case PieceKind::kRectangle: {
      const Vec3 rel = c - piece.origin;
      const double s = std::clamp(rel.dot(piece.axis_u), 0.0, piece.length_u_m);
      const double t = std::clamp(rel.dot(piece.axis_v), 0.0, piece.length_v_m);
      const Vec3 q = piece.origin + s * piece.axis_u + t * piece.axis_v;
      const Vec3 d = c - q;
      const double dist2 = d.squaredNorm();
      if (dist2 >= radius_m * radius_m) return false;
      const double dist = std::sqrt(dist2);
      hit.distance_m = dist;
      if (dist > 1e-12 * radius_m) {
        hit.normal = d / dist;
      } else {
        hit.normal = piece.normal;
      }
      hit.point = q;
      return true;
    }
  }
  return false;
}

}  // namespace spread::dem
