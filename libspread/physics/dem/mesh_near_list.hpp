#pragma once
// Per particle and per mesh wall, the mesh's triangles near the particle: those within its radius plus a
// skin of where its centre stood, in the mesh's own frame, when the list was made. A mesh is fixed in its
// wall group's frame (a disc turns rigidly; the particle is moved into that frame, never the mesh), so the
// list stays complete while the centre has moved less than the skin in that frame: a triangle within r of
// the centre now is within r + |Δx| ≤ r + skin of the centre then (triangle inequality). The wall pass then
// tests only the listed triangles instead of the mesh's grid cells, every step, and rebuilds a particle's
// list from the grid when its centre has left the skin. The contacts are the grid query's to the bit: the
// same triangle test on a superset of the same touching triangles, ordered by distance, feature and
// triangle (MeshCollider::query), never by where they were found.
//
// The records move with the particles when the engine compacts its arrays (compact()), and each names the
// particle it was made for, so a record in a slot now held by another particle is never used.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace spread::dem {

struct alignas(64) MeshNear {
  // 24 triangles fill the record's two cache lines; on the Case-1 disc (ξ 5 mm and R/100) a granule's list
  // at a skin of half its radius holds 2–12 of them (a vane's foot the most). More: the grid is queried.
  static constexpr int kCapacity = 24;
  static constexpr std::int32_t kOverflow = kCapacity + 1;
  double origin_m[3] = {0.0, 0.0, 0.0};  // the centre in the mesh frame at the build (m)
  std::uint32_t owner = 0;               // id of the particle it was made for; 0: none (ids start at 1)
  std::int32_t count = 0;                // triangles listed, or kOverflow
  std::uint32_t triangle[kCapacity] = {};
};
static_assert(sizeof(MeshNear) == 128);

// The lists of one particle, as the wall set reads them: one record per mesh wall, numbered over the wall
// groups in order (group 0's meshes first).
struct MeshNearOfParticle {
  MeshNear* lists = nullptr;  // nullptr: no lists, every query goes to the grid
  std::uint32_t owner = 0;    // the particle's id
  double skin_m = 0.0;
};

class MeshNearLists {
 public:
  // meshes: the mesh walls of every group; skin_m > 0. No meshes: off (of() gives no lists).
  void configure(std::size_t meshes, double skin_m);
  bool enabled() const { return meshes_ > 0; }
  double skin_m() const { return skin_m_; }
  // One record set per particle slot; slots added have no list yet.
  void resize(std::size_t particles);
  // Drops the records of the inactive slots keeping the order of the others, as ParticleArrays::compact.
  void compact(const std::vector<std::uint8_t>& active);
  MeshNearOfParticle of(std::size_t particle, std::uint32_t id) {
    if (meshes_ == 0) return {};
    return {records_.data() + particle * meshes_, id, skin_m_};
  }
 private:
  std::size_t meshes_ = 0;
  double skin_m_ = 0.0;
  std::vector<MeshNear> records_;
};

}  // namespace spread::dem
