#pragma once
// Spinning-disc generator: a flat or conical disc with N vanes, as exact analytic pieces or as a
// triangle mesh of element size ξ (seed Sect. 3.3 studies exactly this choice).
#include <memory>

#include "libspread/physics/dem/triangle_mesh.hpp"
#include "libspread/physics/dem/wall_set.hpp"

namespace spread::dem {

struct DiscGeometry {
  double radius_m = 0.29;
  double cone_angle_rad = 0.0;        // surface z = z_apex + tan(α) ρ (α > 0: rises towards the rim)
  double z_apex_m = 0.0;              // height of the disc surface at the centre
  int vane_count = 0;
  double vane_start_radius_m = 0.0;
  double vane_end_radius_m = 0.0;     // 0: the disc radius
  double vane_height_m = 0.03;
  double vane_pitch_rad = 0.0;        // vane direction from the radial at its start; > 0 leans forward
                                      // (towards the direction of rotation)
  double first_vane_angle_rad = 0.0;  // polar angle of the first vane's start at t = 0
  double mesh_size_m = 0.0;           // ξ (m); 0: analytic pieces
  // A given disc (e.g. a machine's own disc read from STL, scene key machine.stl_path): when set, this
  // mesh — disc and vanes, in the disc frame (axis z, rim at z = 0 as z_apex_m assumes) — is the wall
  // and the generator's vane and mesh-size values are not used. Shared: configs are copied per run.
  std::shared_ptr<const TriangleMesh> mesh;
};

// Disc as a wall group spinning at `rpm` (counter-clockwise seen from above) about its centre.
// Throws std::invalid_argument naming the bad geometry value.
WallGroup make_disc(const DiscGeometry& geometry, double rpm, int material, double max_particle_radius_m);

// The meshes used by make_disc (exposed for tests and STL export); mesh_disc_with_vanes returns the
// given mesh when geometry.mesh is set.
TriangleMesh mesh_cone_disc(double radius_m, double cone_angle_rad, double z_apex_m, double mesh_size_m);
TriangleMesh mesh_disc_with_vanes(const DiscGeometry& geometry);

}  // namespace spread::dem
