#pragma once
// Exact analytic wall pieces, expressed in their wall group's own frame (the co-rotating frame of a
// spinning disc). Each piece yields at most one contact per particle: its closest point is found by
// clamping, so face, edge and rim contacts come out of the same formula.
#include <cstdint>

#include <Eigen/Geometry>  // cross products

#include "libspread/core/vec3.hpp"

namespace spread::dem {

enum class PieceKind : std::uint8_t {
  kPlane,       // infinite plane through `origin` with unit `normal`; one-sided (particle on the + side)
  kRevolution,  // surface of revolution about the frame's z axis swept by the segment (ρ0,z0)→(ρ1,z1)
                // in the meridian half-plane; one-sided: the particle side is +`side_normal_rz`.
                // Flat disc: (0,z)→(R,z); cone of angle α: (0,z)→(R, z+R tanα); cylinder: (R,z0)→(R,z1).
  kRectangle,   // rectangle origin + s·u + t·v, s∈[0,len_u], t∈[0,len_v]; two-sided (vanes)
};

struct AnalyticPiece {
  PieceKind kind = PieceKind::kPlane;
  Vec3 origin = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();     // plane
  Vec3 axis_u = Vec3::UnitX();     // rectangle (unit)
  Vec3 axis_v = Vec3::UnitZ();     // rectangle (unit, orthogonal to axis_u)
  double length_u_m = 0.0;
  double length_v_m = 0.0;
  double rho0_m = 0.0, z0_m = 0.0, rho1_m = 0.0, z1_m = 0.0;  // revolution segment
  double side_rho = 0.0, side_z = 1.0;                        // revolution: unit normal (ρ, z) on the particle side
};

AnalyticPiece make_plane(const Vec3& point, const Vec3& normal);
// Flat (cone_angle 0) or conical disc, surface z = z_apex + tan(α) ρ for ρ <= radius, particle above.
AnalyticPiece make_cone_disc(double radius_m, double cone_angle_rad, double z_apex_m);
// Inner side of a cylinder of radius R about z, from z_min to z_max (particles inside).
AnalyticPiece make_cylinder_inner(double radius_m, double z_min_m, double z_max_m);
AnalyticPiece make_rectangle(const Vec3& origin, const Vec3& axis_u, double length_u_m, const Vec3& axis_v,
                             double length_v_m);

struct WallHit {
  Vec3 point = Vec3::Zero();   // closest point on the wall (wall frame)
  Vec3 normal = Vec3::UnitZ(); // unit, from the wall towards the particle centre
  double distance_m = 0.0;     // centre to closest point
};

// Closest point of `piece` to a sphere centred at `centre`; true when distance < radius.
bool closest_point(const AnalyticPiece& piece, const Vec3& centre, double radius_m, WallHit& hit);

}  // namespace spread::dem
