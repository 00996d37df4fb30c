#pragma once
// Legacy-VTK (ASCII POLYDATA) snapshots for ParaView: the particles as points with radius and velocity,
// and the walls as triangles placed where they are at time t (a spinning disc is drawn turned).
#include <string>

#include "libspread/physics/dem/particles.hpp"
#include "libspread/physics/dem/wall_set.hpp"

namespace spread::dem {

// Active particles only. Throws std::runtime_error naming the path when it cannot be written.
void write_particles_vtk(const ParticleArrays& particles, const std::string& path);

// Every wall group at time t_s in the inertial frame: mesh triangles as they are; analytic pieces
// tessellated (surfaces of revolution in `segments` sectors, rectangles as two triangles, planes as a
// square of `plane_half_size_m` about their origin). Bead walls (rough linings) are not drawn. Cell
// data `group` gives each triangle's wall-group index. Throws std::runtime_error naming the path.
void write_walls_vtk(const WallSet& walls, double t_s, const std::string& path, int segments = 72,
                     double plane_half_size_m = 0.5);

}  // namespace spread::dem
