#include "libspread/physics/drum/drum_mantle.hpp"

#include "libspread/physics/dem/sphere_wall.hpp"

namespace spread::drum {

void add_drum_mantle(const DrumScene& s, int wall_material, dem::WallGroup& drum, std::vector<dem::Material>& materials,
                     std::vector<dem::PairOverride>& overrides) {
  drum.material = wall_material;
  drum.pieces.push_back(dem::make_cylinder_inner(s.radius_m, 0.0, s.length_m));
  if (s.wall != DrumWall::kRoughParticles) return;
  const double bead_radius = 0.5 * bead_diameter_m(s);
  dem::SphereWall beads = dem::make_cylinder_bead_lining(s.radius_m, s.length_m, 2.0 * bead_radius);
  for (std::size_t i = 0; i < s.species.size(); ++i) {
    const double r = 0.5 * s.species[i].diameter_m;
    const int bead_material = static_cast<int>(materials.size());
    materials.push_back(dem::bead_contact_material(materials[i], r, bead_radius));
    const int species = static_cast<int>(i);
    overrides.push_back({species, bead_material, s.restitution, s.friction_wall,
                         dem::bead_rolling_friction(s.rolling_friction, r, bead_radius)});
    beads.materials_by_radius.push_back({r, bead_material});
  }
  drum.bead_walls.push_back(std::move(beads));
}

}  // namespace spread::drum
