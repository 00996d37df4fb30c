#pragma once
// Walls grouped by motion: each group is fixed in its own frame, which turns about the vertical axis
// through `centre_m` at a prescribed rate (0 = static). Contacts are detected in the group's
// co-rotating frame — the particle is transformed, never the mesh — and the wall's surface velocity
// ω×r at the contact point is reported so the contact law sees the true relative velocity.
#include <cstdint>
#include <string>
#include <vector>

#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/analytic_wall.hpp"
#include "libspread/physics/dem/mesh_near_list.hpp"
#include "libspread/physics/dem/sphere_wall.hpp"
#include "libspread/physics/dem/triangle_mesh.hpp"

namespace spread::dem {

struct WallGroup {
  std::string name = "wall";
  std::vector<AnalyticPiece> pieces;   // exact pieces, in the group frame
  std::vector<MeshCollider> meshes;    // triangle meshes, in the group frame
  std::vector<SphereWall> bead_walls;  // fixed beads (rough walls), in the group frame
  Vec3 centre_m = Vec3::Zero();        // origin of the group frame (inertial)
  double angular_velocity_rad_s = 0.0; // about +z (counter-clockwise seen from above)
  double initial_angle_rad = 0.0;      // frame angle at t = 0
  int material = 0;                    // index into the engine's material table
};

struct WallContact {
  Vec3 point_m = Vec3::Zero();            // closest wall point (inertial)
  Vec3 normal = Vec3::UnitZ();            // unit, wall → particle centre (inertial)
  double distance_m = 0.0;                // centre to wall
  Vec3 wall_velocity_m_s = Vec3::Zero();  // at point_m
  std::uint32_t key = 0;                  // stable id of the wall feature (history key), never 0
  int material = 0;
  int group = 0;
};

class WallSet {
 public:
  std::vector<WallGroup> groups;

  // Caches each group's rotation at time t (call once per force evaluation).
  void set_time(double t_s);
  // Contacts of a sphere at time set_time(); at most max_out, returns the count. group_mask: bit g set to
  // look at group g (groups past 63 always looked at); the contacts of the groups looked at come in the
  // same order as with all of them. near: the particle's mesh lists (mesh_near_list.hpp), read and rebuilt
  // here; the contacts are the same with or without them.
  int collect(const Vec3& centre_m, double radius_m, WallContact* out, int max_out, std::uint64_t group_mask = ~0ull,
              MeshNearOfParticle near = {}) const;
  // The mesh walls of every group, numbered as the mesh lists are.
  std::size_t mesh_count() const;
  // Bit g set when group g has a surface within radius_m of the centre (groups past 63: bit 63).
  std::uint64_t groups_within(const Vec3& centre_m, double radius_m) const;
  // Largest surface speed of any moving wall piece (m/s), for the time-step estimate.
  double max_surface_speed_m_s() const;

 private:
  struct Pose { double c = 1.0, s = 0.0; };
  std::vector<Pose> poses_;
  std::vector<std::size_t> first_mesh_;  // per group, the number of its first mesh over all groups
  // Mesh m of group g's contacts of a sphere in the group frame, through the particle's list when it has
  // one (rebuilt when the centre has left its skin).
  int mesh_contacts(const MeshCollider& mesh, std::size_t list, const Vec3& local, double radius_m, MeshNearOfParticle near,
                    MeshContact* out, int max_out) const;
};

// Bead contacts: index = kBeadKeyFlag | (bead index over the group's bead walls), beads < 2^22.
inline constexpr std::uint32_t kBeadKeyFlag = 1u << 22;
inline std::uint32_t wall_feature_key(int group, bool mesh, std::uint32_t index) {
  return (static_cast<std::uint32_t>(group + 1) << 24) | (mesh ? (1u << 23) : 0u) | (index & 0x7FFFFFu);
}

}  // namespace spread::dem
