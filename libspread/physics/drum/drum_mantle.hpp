#pragma once
// The drum mantle as engine walls: the analytic cylinder of radius R, and for wall = "rough_particles"
// a lining of fixed beads in front of it (seed 001 Sect. 9) — the cylinder stays behind the beads as the
// mantle a small particle may reach through a gap. Bead contacts use the particle–particle law with the
// wall friction: one bead-contact material per species (dem::bead_contact_material) so that a Hertz
// contact against a bead equals the contact against a fixed particle of the bead's size.
#include <vector>

#include "libspread/physics/dem/material.hpp"
#include "libspread/physics/dem/wall_set.hpp"
#include "libspread/physics/drum/drum_scene.hpp"

namespace spread::drum {

// Adds the mantle to `drum` (the group turning with the drum, material `wall_material`). Species
// materials are materials[0 .. species−1]; bead-contact materials and their pair values (restitution,
// wall friction, rolling friction per dem::bead_rolling_friction) are appended.
void add_drum_mantle(const DrumScene& s, int wall_material, dem::WallGroup& drum, std::vector<dem::Material>& materials,
                     std::vector<dem::PairOverride>& overrides);

}  // namespace spread::drum
