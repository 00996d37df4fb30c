// Exports libspread's own Case-1 disc mesh (the one bench_dem uses: cone 0.157 rad, R 0.29 m, two radial
// vanes 0.036 m high, ξ 5 mm, apex below so the rim is at z = 0) as ASCII STL for LIGGGHTS.
//   see bench/peers/README.md for the compile line; writes disc_case1.stl into the current directory
#include <cmath>
#include <cstdio>

#include "libspread/physics/dem/disc_generator.hpp"

int main() {
  spread::dem::DiscGeometry g;
  g.radius_m = 0.29;
  g.cone_angle_rad = 0.157;
  g.z_apex_m = -0.29 * std::tan(0.157);
  g.vane_count = 2;
  g.vane_height_m = 0.036;
  g.mesh_size_m = 0.005;
  const auto mesh = spread::dem::mesh_disc_with_vanes(g);
  spread::dem::write_stl_ascii(mesh, "disc_case1.stl");
  std::printf("%zu vertices, %zu triangles\n", mesh.vertices.size(), mesh.triangles.size());
}
