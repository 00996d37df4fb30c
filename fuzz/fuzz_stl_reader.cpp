// Fuzz harness: the STL reader (libspread/physics/dem read_stl, ASCII and binary) and the mesh wall build
// (MeshCollider) on arbitrary file bytes. Seeds are tiny real STL files of both kinds, so mutations reach
// the facet records, the binary triangle count and the ASCII number parsing.
// Contract checked: read_stl returns a mesh or throws std::runtime_error naming the file — never another
// exception, never a crash — and an accepted mesh is usable as a wall: at least one triangle, every vertex
// finite, every index in range, no triangle with a repeated vertex, and sphere queries at its vertices and
// centroids give finite contacts (point, unit normal, distance within the sphere).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz/fuzz_input.hpp"
#include "fuzz/temp_input_file.hpp"
#include "libspread/physics/dem/triangle_mesh.hpp"

namespace {

constexpr const char* kHarness = "fuzz_stl_reader";
constexpr int kMaxContacts = 8;
constexpr std::size_t kMaxQueriedTriangles = 64;  // bounds the time per input on large meshes

void check_contact(const spread::dem::MeshContact& c, double radius_m, std::size_t triangle_count) {
  using spread::fuzz::fail;
  if (c.triangle >= triangle_count) fail(kHarness, "contact names a triangle beyond the mesh");
  if (!c.point.allFinite() || !c.normal.allFinite() || !std::isfinite(c.distance_m))
    fail(kHarness, "non-finite contact from a finite mesh");
  if (std::abs(c.normal.norm() - 1.0) > 1e-6) fail(kHarness, "contact normal is not a unit vector");
  if (c.distance_m < 0.0 || c.distance_m >= radius_m) fail(kHarness, "contact distance outside [0, radius)");
}

void check_mesh(const spread::dem::TriangleMesh& mesh) {
  using spread::fuzz::fail;
  if (mesh.triangles.empty()) fail(kHarness, "accepted a mesh without triangles");
  for (const auto& v : mesh.vertices)
    if (!v.allFinite()) fail(kHarness, "accepted a non-finite vertex");
  for (const auto& t : mesh.triangles) {
    for (const std::uint32_t k : t)
      if (k >= mesh.vertices.size()) fail(kHarness, "triangle index beyond the vertex list");
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) fail(kHarness, "accepted a triangle with a repeated vertex");
  }
  // The wall build (the grid over the triangles), then spheres at vertices and centroids: a radius of a
  // hundredth of the triangle's longest edge (or 1 mm for a tiny mesh), as a granule on a wall mesh.
  const spread::dem::MeshCollider collider(mesh, 1e-3);
  const std::size_t queried = mesh.triangles.size() < kMaxQueriedTriangles ? mesh.triangles.size() : kMaxQueriedTriangles;
  for (std::size_t ti = 0; ti < queried; ++ti) {
    const auto& t = mesh.triangles[ti];
    const spread::Vec3& a = mesh.vertices[t[0]];
    const spread::Vec3& b = mesh.vertices[t[1]];
    const spread::Vec3& c = mesh.vertices[t[2]];
    const double longest = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
    const double radius_m = std::isfinite(longest) && longest > 0.0 ? std::max(1e-3, 0.01 * longest) : 1e-3;
    const spread::Vec3 normal = (b - a).cross(c - a).normalized();
    const spread::Vec3 centroid = (a + b + c) / 3.0;
    const spread::Vec3 above = centroid + 0.5 * radius_m * normal;
    for (const spread::Vec3* at_ptr : {&centroid, &a, &above}) {
      const spread::Vec3& at = *at_ptr;
      if (!at.allFinite()) continue;  // a centroid of huge coordinates may overflow; the mesh itself is finite
      spread::dem::MeshContact out[kMaxContacts];
      const int n = collider.query(at, radius_m, out, kMaxContacts);
      if (n < 0 || n > kMaxContacts) fail(kHarness, "query returned an impossible contact count");
      for (int k = 0; k < n; ++k) check_contact(out[k], radius_m, mesh.triangles.size());
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static spread::fuzz::TempInputFile file("spread_fuzz_stl");
  if (!file.write(data, size)) spread::fuzz::fail(kHarness, "cannot write " + file.path());
  try {
    check_mesh(spread::dem::read_stl(file.path(), 1.0));
  } catch (const std::runtime_error& e) {
    // The documented refusal: it must say which file.
    if (std::string(e.what()).find(file.path()) == std::string::npos)
      spread::fuzz::fail(kHarness, std::string("refusal does not name the file: ") + e.what());
  }
  return 0;
}
