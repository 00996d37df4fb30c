#include "libspread/physics/dem/wall_set.hpp"

#include <algorithm>
#include <cmath>

namespace spread::dem {

void WallSet::set_time(double t_s) {
  poses_.resize(groups.size());
  first_mesh_.resize(groups.size());
  std::size_t meshes = 0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    first_mesh_[g] = meshes;
    meshes += groups[g].meshes.size();
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const double angle = groups[g].initial_angle_rad + groups[g].angular_velocity_rad_s * t_s;
    poses_[g] = {std::cos(angle), std::sin(angle)};
  }
}

std::size_t WallSet::mesh_count() const {
  std::size_t meshes = 0;
  for (const auto& g : groups) meshes += g.meshes.size();
  return meshes;
}

int WallSet::mesh_contacts(const MeshCollider& mesh, std::size_t list, const Vec3& local, double radius_m, MeshNearOfParticle near,
                           MeshContact* out, int max_out) const {
  if (near.lists == nullptr) return mesh.query(local, radius_m, out, max_out);
  MeshNear& l = near.lists[list];
  // Complete while the centre is within the skin of where the list was made (a hair less, and a hair more
  // reach, so that rounding in the distances cannot drop a triangle).
  const double dx = local.x() - l.origin_m[0], dy = local.y() - l.origin_m[1], dz = local.z() - l.origin_m[2];
  const double keep_m = (1.0 - 1e-9) * near.skin_m;
  if (l.owner != near.owner || !(dx * dx + dy * dy + dz * dz <= keep_m * keep_m)) {
    l.owner = near.owner;
    l.origin_m[0] = local.x(); l.origin_m[1] = local.y(); l.origin_m[2] = local.z();
    l.count = mesh.triangles_within(local, (1.0 + 1e-9) * (radius_m + near.skin_m), l.triangle, MeshNear::kCapacity);
  }
  if (l.count == MeshNear::kOverflow) return mesh.query(local, radius_m, out, max_out);
  return mesh.query_listed(local, radius_m, l.triangle, l.count, out, max_out);
}

int WallSet::collect(const Vec3& centre_m, double radius_m, WallContact* out, int max_out, std::uint64_t group_mask,
                     MeshNearOfParticle near) const {
  int n = 0;
  for (std::size_t g = 0; g < groups.size() && n < max_out; ++g) {
    if (g < 64 && ((group_mask >> g) & 1u) == 0) continue;
    const WallGroup& grp = groups[g];
    const Pose& pose = poses_[g];
    // Inertial → group frame: rotate by −θ about z.
    const Vec3 rel = centre_m - grp.centre_m;
    const Vec3 local(pose.c * rel.x() + pose.s * rel.y(), -pose.s * rel.x() + pose.c * rel.y(), rel.z());
    auto to_inertial_dir = [&](const Vec3& v) {
      return Vec3(pose.c * v.x() - pose.s * v.y(), pose.s * v.x() + pose.c * v.y(), v.z());
    };
    auto emit = [&](const Vec3& point_local, const Vec3& normal_local, double dist, std::uint32_t key, int material) {
      WallContact& wc = out[n++];
      const Vec3 arm = to_inertial_dir(point_local);
      wc.point_m = grp.centre_m + arm;
      wc.normal = to_inertial_dir(normal_local);
      wc.distance_m = dist;
      // ω ẑ × r, r from the axis.
      wc.wall_velocity_m_s = Vec3(-grp.angular_velocity_rad_s * arm.y(), grp.angular_velocity_rad_s * arm.x(), 0.0);
      wc.key = key;
      wc.material = material;
      wc.group = static_cast<int>(g);
    };
    for (std::size_t p = 0; p < grp.pieces.size() && n < max_out; ++p) {
      WallHit hit;
      if (closest_point(grp.pieces[p], local, radius_m, hit))
        emit(hit.point, hit.normal, hit.distance_m, wall_feature_key(static_cast<int>(g), false, static_cast<std::uint32_t>(p)), grp.material);
    }
    for (std::size_t m = 0; m < grp.meshes.size() && n < max_out; ++m) {
      MeshContact mc[8];
      const int k = mesh_contacts(grp.meshes[m], first_mesh_[g] + m, local, radius_m, near, mc, 8);
      for (int i = 0; i < k && n < max_out; ++i)
        emit(mc[i].point, mc[i].normal, mc[i].distance_m,
             wall_feature_key(static_cast<int>(g), true, (static_cast<std::uint32_t>(m) << 20) + mc[i].triangle), grp.material);
    }
    std::uint32_t bead_offset = 0;  // bead keys run on over the group's bead walls
    for (std::size_t b = 0; b < grp.bead_walls.size() && n < max_out; ++b) {
      const SphereWall& beads = grp.bead_walls[b];
      BeadContact bc[8];
      const int k = beads.query(local, radius_m, bc, 8);
      const int material = beads.material_for(radius_m, grp.material);
      for (int i = 0; i < k && n < max_out; ++i)
        emit(bc[i].point, bc[i].normal, bc[i].distance_m,
             wall_feature_key(static_cast<int>(g), false, kBeadKeyFlag | ((bead_offset + bc[i].bead) & (kBeadKeyFlag - 1u))), material);
      bead_offset += static_cast<std::uint32_t>(beads.size());
    }
  }
  return n;
}

std::uint64_t WallSet::groups_within(const Vec3& centre_m, double radius_m) const {
  std::uint64_t mask = 0;
  WallContact one;
  for (std::size_t g = 0; g < std::min<std::size_t>(groups.size(), 64); ++g)
    if (collect(centre_m, radius_m, &one, 1, 1ull << g) > 0) mask |= 1ull << g;
  // Groups past 63 are looked at whatever the mask; any of them within reach sets bit 63.
  if (groups.size() > 64 && collect(centre_m, radius_m, &one, 1, 0) > 0) mask |= 1ull << 63;
  return mask;
}

double WallSet::max_surface_speed_m_s() const {
  double v = 0.0;
  for (const auto& g : groups) {
    double r = 0.0;
    for (const auto& p : g.pieces) {
      if (p.kind == PieceKind::kRevolution) r = std::max({r, p.rho0_m, p.rho1_m});
      if (p.kind == PieceKind::kRectangle) {
        for (double s : {0.0, p.length_u_m})
          for (double t : {0.0, p.length_v_m}) {
            const Vec3 q = p.origin + s * p.axis_u + t * p.axis_v;
            r = std::max(r, std::hypot(q.x(), q.y()));
          }
      }
    }
    for (const auto& m : g.meshes)
      for (const auto& vtx : m.mesh().vertices) r = std::max(r, std::hypot(vtx.x(), vtx.y()));
    for (const auto& b : g.bead_walls) r = std::max(r, b.max_axis_distance_m());
    v = std::max(v, std::abs(g.angular_velocity_rad_s) * r);
  }
  return v;
}

}  // namespace spread::dem
