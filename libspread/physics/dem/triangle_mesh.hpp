#pragma once
// Triangle-mesh walls (seed Sect. 2.3): STL input (ASCII and binary), welded vertices so triangles know
// their neighbours, a uniform grid over the triangles for the sphere query, and sphere–triangle contacts
// with face, edge and vertex features reduced to ONE contact per touching surface patch.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>  // cross products

#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/triangle_bound.hpp"

namespace spread::dem {

struct TriangleMesh {
  std::vector<Vec3> vertices;                       // welded (shared) vertices, m
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

struct MeshLoadReport {
  std::size_t triangles_read = 0;
  std::size_t degenerate_dropped = 0;  // zero-area (or collapsed after welding) triangles removed
  std::string message;                 // human-readable summary naming the file
};

// Builds a mesh from a triangle soup, welding vertices closer than weld_tolerance_m and dropping
// degenerate triangles (area < 1e-12 of the squared longest edge, or collapsed by welding).
TriangleMesh weld_triangle_soup(const std::vector<std::array<Vec3, 3>>& soup, double weld_tolerance_m,
                                MeshLoadReport* report = nullptr);

// Reads an STL file (binary when its size matches 84 + 50·n, ASCII otherwise), scaling coordinates by
// `scale` (e.g. 0.001 for millimetres). Throws std::runtime_error naming the file when it cannot be read
// or parsed, or when no valid triangle remains.
TriangleMesh read_stl(const std::string& path, double scale = 1.0, MeshLoadReport* report = nullptr);
void write_stl_binary(const TriangleMesh& mesh, const std::string& path);
void write_stl_ascii(const TriangleMesh& mesh, const std::string& path);

enum class Feature : std::uint8_t { kFace, kEdge, kVertex };

struct MeshContact {
  std::uint32_t triangle = 0;
  Feature feature = Feature::kFace;
  Vec3 point = Vec3::Zero();    // closest point on the mesh
  Vec3 normal = Vec3::UnitZ();  // from the mesh to the sphere centre
  double distance_m = 0.0;
};

// Closest point on one triangle with the feature it lies on (Ericson, Real-Time Collision Detection
// §5.1.5). `feature_vertices` gets the triangle-local vertex indices of the feature (1–2 used).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Feature& feature,
                               int feature_vertices[2]);

// A mesh with its search grid, fixed in its own frame (the query point is moved, never the mesh).
class MeshCollider {
 public:
  MeshCollider() = default;
  // cell_m <= 0: chosen from the mean triangle size and `max_particle_radius_m`.
  MeshCollider(TriangleMesh mesh, double max_particle_radius_m, double cell_m = 0.0);

  // Contacts of a sphere, one per touching surface patch, written to out (at most max_out); returns
  // the count. Rule: candidates are taken closest first; an edge or vertex contact is dropped when a
  // closer accepted contact's triangle contains that edge or vertex (it is then not a local minimum of
  // the distance, e.g. the shared edge of coplanar neighbours or a concave fold) or shares one of its
  // vertices with a normal within 45° (a fan of triangles around a vertex); any contact whose normal
  // matches an accepted one within 0.26° is dropped (the same patch seen through another triangle).
  int query(const Vec3& centre, double radius_m, MeshContact* out, int max_out) const;
  // query() over the given triangles only (ascending, no repeats): the same contacts, to the bit, when they
  // include every triangle within radius_m of the centre (mesh_near_list.hpp).
  int query_listed(const Vec3& centre, double radius_m, const std::uint32_t* triangles, int count, MeshContact* out,
                   int max_out) const;
  // The triangles whose closest point lies within reach_m of the centre, ascending, into triangles (at most
  // capacity); returns their count, or capacity + 1 when there are more.
  int triangles_within(const Vec3& centre, double reach_m, std::uint32_t* triangles, int capacity) const;

  const TriangleMesh& mesh() const { return mesh_; }
  std::size_t triangle_count() const { return mesh_.triangles.size(); }
  bool empty() const { return mesh_.triangles.empty(); }

 private:
  TriangleMesh mesh_;
  Vec3 lo_ = Vec3::Zero();
  double cell_m_ = 1.0;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<std::uint32_t> cell_start_;  // CSR over cells
  std::vector<std::uint32_t> cell_items_;
  std::vector<TriangleBound> bounds_;  // per triangle, the cheap test before the exact one

  // The grid cells a box of half-width reach_m about the centre overlaps (inclusive); false when none.
  bool cell_range(const Vec3& centre, double reach_m, int lo[3], int hi[3]) const;
};

}  // namespace spread::dem
