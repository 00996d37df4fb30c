#pragma once
// A rough wall made of fixed spheres ("beads"), seed 001 Sect. 9: "rough walls by an array of particles
// … possessing the same material constants as the grains … the motion of the wall spheres is not
// affected by the impacts but is strictly governed by the continuous rotation of the cylinder".
//
// The beads are fixed in their wall group's frame; WallSet transforms the particle into that frame (the
// co-rotating frame of a turning drum), so the bead positions are never updated — exact at any time and
// free of cost per step. Each bead contact is reported as a wall contact whose distance is measured to
// the bead's surface, so the engine's wall overlap R_a − distance equals the particle–particle overlap
// δ = R_a + R_b − |x_a − x_b| (seed 000 Eq. 4), with the normal along the line of centres.
//
// Lookup: a uniform grid (CSR) over the bead centres, cells at least one bead diameter wide, plus an
// exact radial early-out: a sphere with ρ + r below min(ρ_b − R_b) (ρ = distance from the frame's z
// axis) touches no bead — the bulk of a drum bed never enters the grid.
#include <cstdint>
#include <vector>

#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/material.hpp"

namespace spread::dem {

struct BeadContact {
  Vec3 point = Vec3::Zero();   // middle of the overlap on the line of centres (group frame)
  Vec3 normal = Vec3::UnitZ(); // unit, bead centre → particle centre (group frame)
  double distance_m = 0.0;     // particle centre to the bead surface, |x − x_b| − R_b
  std::uint32_t bead = 0;      // bead index in the wall's own (cell) order, as centre()/radius(); stable
};

// Bead contacts of particles of a given radius use this material (see bead_contact_material()).
struct BeadMaterialByRadius {
  double particle_radius_m = 0.0;
  int material = 0;
};

class SphereWall {
 public:
  // Beads are addressed in contact keys by 22 bits.
  static constexpr std::size_t kMaxBeads = std::size_t{1} << 22;

  SphereWall() = default;
  // Throws std::invalid_argument naming the bad bead (non-finite centre, radius <= 0), an empty set,
  // sizes that differ, or more than kMaxBeads beads.
  SphereWall(const std::vector<Vec3>& centres_m, const std::vector<double>& radii_m);

  // Beads overlapping a sphere, closest first; at most max_out written, returns the count.
  int query(const Vec3& centre_m, double radius_m, BeadContact* out, int max_out) const;

  std::size_t size() const { return radius_m_.size(); }
  // Bead `bead` in the wall's own order (cell order, not the order given to the constructor).
  Vec3 centre(std::size_t bead) const { return {x_m_[bead], y_m_[bead], z_m_[bead]}; }
  double radius(std::size_t bead) const { return radius_m_[bead]; }
  // Largest ρ + R_b of any bead (m): the fastest bead surface point is ω times this.
  double max_axis_distance_m() const { return max_axis_distance_m_; }

  // Material of the contacts of a particle of radius r: the entry with the nearest radius, else
  // `fallback` (the group material) when the list is empty.
  std::vector<BeadMaterialByRadius> materials_by_radius;
  int material_for(double particle_radius_m, int fallback) const;

 private:
  // Bead arrays in grid-cell order (flat, for the query loop); bead indices refer to this order.
  std::vector<double> x_m_, y_m_, z_m_, radius_m_;
  Vec3 lo_m_ = Vec3::Zero();
  double cell_m_ = 1.0;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<std::uint32_t> cell_start_;  // CSR over cells: beads of cell c are [start[c], start[c+1])
  double max_radius_m_ = 0.0;
  double min_inner_axis_distance_m_ = 0.0;  // min over beads of ρ_b − R_b
  double max_axis_distance_m_ = 0.0;
};

// Beads lining the inside of a cylinder of radius R about z, from z = 0 to z = L: rings of equal beads
// touching the mantle (centres at ρ = R − R_b), as many per ring as fit without overlap (chord
// 2(R − R_b) sin(π/n) ≥ d_b), n_z = max(1, ⌊L/d_b⌋) rings evenly spaced along z, alternate rings turned by
// half a pitch (a staggered, roughly hexagonal layer with no straight channel along z).
// Throws std::invalid_argument when d_b is not in (0, R/2] or is larger than L.
SphereWall make_cylinder_bead_lining(double cylinder_radius_m, double length_m, double bead_diameter_m);

// The engine's wall path evaluates a contact with R* = r (the particle radius: a flat wall) and M* = m.
// A fixed bead of radius R_b is a particle of infinite mass, so M* = m is right, but its Hertz contact
// has R* = r R_b/(r + R_b). Every Hertz–Thornton term depends on E* and R* only through E*·sqrt(R*) and
// G*·sqrt(R*) (seed 000 Eqs. 16, 18, 19, 24), so a bead material whose pair moduli with the particle are
// E*_pp·s and G*_pp·s, s = sqrt(R_b/(r + R_b)), gives exactly the particle–particle force against an
// equal-material bead. With the particle's Poisson ratio: E_b = E_p f/(1 − f), f = s/2 (from
// 1/E*_pw = 1/E*_p + 1/E*_b with E*_pw = f E*_p; the G* relation follows with the same ν).
// The linear model does not use the moduli, so this material is right for both laws. Remaining
// difference (Hertz only): the torque lever takes the share f instead of 1/2 of the overlap (Eq. 10),
// a relative change of the lever of (1/2 − f) δ/r.
Material bead_contact_material(const Material& particle, double particle_radius_m, double bead_radius_m);
// Rolling resistance M_r = μ_r F_n R* (contact_laws.hpp): the wall path uses R* = r, so the bead pair
// takes μ_r R_b/(r + R_b) to give the particle–particle torque.
double bead_rolling_friction(double rolling_friction, double particle_radius_m, double bead_radius_m);

}  // namespace spread::dem
