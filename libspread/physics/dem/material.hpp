#pragma once
// Materials and the contact parameters derived once per material pair (docs/design.md §7: "parameters derived
// once"). Particles and walls both refer to materials by index into one table.
#include <cstdint>
#include <string>
#include <vector>

#include "libspread/physics/dem/contact_law.hpp"

namespace spread::dem {

struct Material {
  std::string name;
  double density_kg_m3 = 1500.0;
  double youngs_modulus_pa = 5e7;   // E
  double poisson_ratio = 0.25;     // ν
  double restitution = 0.5;        // normal coefficient of restitution e (–), in (0, 1]
  // Coulomb μ (–), seed Eq. 6, one per kind of partner (the scene's material keys of the same names):
  double friction_particle = 0.35;  // against another particle (pairs of two non-rigid materials)
  double friction_wall = 0.35;      // against a wall (pairs with a rigid material)
  double rolling_friction = 0.0;   // μ_r (–), used only when the rolling effect is on
  bool rigid = false;              // walls: infinitely stiff, E* is the particle's alone
};

// Per-pair values replacing the mixing rule (particle–particle or particle–wall pairs).
struct PairOverride {
  int material_a = 0;
  int material_b = 0;
  double restitution = 0.5;
  double friction = 0.35;          // the pair's μ (PairParams::friction)
  double rolling_friction = 0.0;
};

// The linear sub-models' springs (seed 001); damping comes from the pair restitution.
struct LinearSprings {
  double normal_stiffness_n_m = 1e4;   // k_n
  double tangential_ratio = 2.0 / 7.0; // k_t / k_n
};

// Everything a contact evaluation needs that depends only on the two materials.
struct PairParams {
  double e_star_pa = 0.0;        // E* = (1/E_a* + 1/E_b*)^-1, E_i* = E_i/(1-ν_i²)  (Eq. 16)
  double g_star_pa = 0.0;        // G* = (1/G_a* + 1/G_b*)^-1, G_i* = G_i/(2-ν_i)... see contact_params.cpp
  double damping_ratio = 0.0;    // from the pair restitution: γ of Eqs. 18/24 (damping 'hertz'), ζ ('linear_viscous'), 0 ('none')
  double restitution = 0.5;
  double friction = 0.35;        // the pair's μ: mean friction_particle of two particles, mean friction_wall with a wall
  double rolling_friction = 0.0;
  double share_a = 0.5;          // E*/E_a*: share of the indentation taken by body a (Eq. 10, corrected)
  double share_b = 0.5;          // E*/E_b*
  double kn_linear_n_m = 0.0;    // linear normal spring k_n (LinearSprings); 0 unless the law uses it
  double kt_linear_n_m = 0.0;    // linear tangential spring k_t = tangential_ratio · k_n
};

// Table of PairParams for every ordered material pair; lookups are inline.
class PairTable {
 public:
  PairTable() = default;
  // Throws std::invalid_argument naming the material and the bad value.
  PairTable(const std::vector<Material>& materials, const std::vector<PairOverride>& overrides,
            const ContactLaw& law, const LinearSprings& springs);
  const PairParams& operator()(int a, int b) const {
    return pairs_[static_cast<std::size_t>(a) * count_ + static_cast<std::size_t>(b)];
  }
  std::size_t material_count() const { return count_; }

 private:
  std::size_t count_ = 0;
  std::vector<PairParams> pairs_;
};

// Checks one material; throws std::invalid_argument("material 'name': youngs_modulus_pa must be > 0 ...").
void validate_material(const Material& material);

}  // namespace spread::dem
