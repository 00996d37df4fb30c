#pragma once
// Packed-bed start (seed 001 Sect. 4): the particle count from the fill fraction, then an orthogonal grid
// of cells one (largest) diameter wide inside the drum, each particle at a cell centre — no overlaps —
// filled from the bottom up. Settling under gravity (drum_simulation.cpp) then packs the bed.
#include <vector>

#include "libspread/core/vec3.hpp"
#include "libspread/physics/drum/drum_scene.hpp"

namespace spread::drum {

struct PlacedParticle {
  Vec3 position_m = Vec3::Zero();
  double radius_m = 0.0;
  int species = 0;
};

// N = fill · πR_f²L · bed_solid_fraction / V̄, V̄ the number-weighted mean particle volume, R_f the free
// radius (R, or R − d_b inside a bead lining).
std::size_t particle_count(const DrumScene& s);

// Grid spacing = spacing_factor × largest diameter (> 1: gaps, the seed's placement; 0.999: every
// neighbour just touching, a dense start for throughput benchmarks). Species 0 fills the lower part,
// species 1 the upper (a segregated start for the mixing index). Throws std::invalid_argument naming
// drum.fill_fraction when the grid has too few cells.
std::vector<PlacedParticle> grid_packing(const DrumScene& s, double spacing_factor = 1.02);

}  // namespace spread::drum
