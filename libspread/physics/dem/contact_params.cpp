#include <cmath>
#include <sstream>
#include <stdexcept>

#include "libspread/physics/dem/material.hpp"
#include "libspread/physics/dem/restitution.hpp"

namespace spread::dem {

namespace {
[[noreturn]] void bad(const Material& m, const char* field, double value, const char* rule) {
  std::ostringstream os;
  os << "material '" << m.name << "': " << field << " = " << value << " " << rule;
  throw std::invalid_argument(os.str());
}
// E_i* = E_i / (1 − ν_i²)   (Eq. 16). Rigid bodies: 1/E* = 0.
double inv_e_star(const Material& m) {
  return m.rigid ? 0.0 : (1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus_pa;
}
// Shear: G_i = E_i / (2 + 2ν_i); Thornton's tangential stiffness k_t = 8 G* sqrt(R δ) with
// 1/G* = (2 − ν_a)/G_a + (2 − ν_b)/G_b (equal materials: G* = G/(4 − 2ν), as the seed states).
double inv_g_star(const Material& m) {
  if (m.rigid) return 0.0;
  const double g = m.youngs_modulus_pa / (2.0 + 2.0 * m.poisson_ratio);
  return (2.0 - m.poisson_ratio) / g;
}
}  // namespace

void validate_material(const Material& m) {
  if (!(m.density_kg_m3 > 0.0) || !std::isfinite(m.density_kg_m3)) bad(m, "density_kg_m3", m.density_kg_m3, "must be > 0");
  if (!m.rigid && (!(m.youngs_modulus_pa > 0.0) || !std::isfinite(m.youngs_modulus_pa)))
    bad(m, "youngs_modulus_pa", m.youngs_modulus_pa, "must be > 0");
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5)) bad(m, "poisson_ratio", m.poisson_ratio, "must be in (-1, 0.5)");
  if (!(m.restitution > 0.0 && m.restitution <= 1.0)) bad(m, "restitution", m.restitution, "must be in (0, 1]");
  if (!(m.friction_particle >= 0.0) || !std::isfinite(m.friction_particle))
    bad(m, "friction_particle", m.friction_particle, "must be >= 0");
  if (!(m.friction_wall >= 0.0) || !std::isfinite(m.friction_wall)) bad(m, "friction_wall", m.friction_wall, "must be >= 0");
  if (!(m.rolling_friction >= 0.0) || !std::isfinite(m.rolling_friction))
    bad(m, "rolling_friction", m.rolling_friction, "must be >= 0");
}

PairTable::PairTable(const std::vector<Material>& materials, const std::vector<PairOverride>& overrides,
                     const ContactLaw& law, const LinearSprings& springs)
    : count_(materials.size()), pairs_(materials.size() * materials.size()) {
  for (const auto& m : materials) validate_material(m);
  const bool linear_springs = law.normal == NormalModel::kLinear || law.tangential == TangentialModel::kLinear;
  if (linear_springs && (!(springs.normal_stiffness_n_m > 0.0) || !(springs.tangential_ratio >= 0.0)))
    throw std::invalid_argument("linear normal or tangential model: normal_stiffness_n_m must be > 0 and tangential_ratio >= 0");
  for (const auto& o : overrides) {
    if (o.material_a < 0 || o.material_b < 0 || static_cast<std::size_t>(o.material_a) >= count_ ||
        static_cast<std::size_t>(o.material_b) >= count_)
      throw std::invalid_argument("pair override refers to an unknown material index");
    if (!(o.restitution > 0.0 && o.restitution <= 1.0) || !(o.friction >= 0.0) || !(o.rolling_friction >= 0.0))
      throw std::invalid_argument("pair override: restitution must be in (0, 1], friction and rolling_friction >= 0");
  }
  for (std::size_t a = 0; a < count_; ++a) {
    for (std::size_t b = 0; b < count_; ++b) {
      const Material& ma = materials[a];
      const Material& mb = materials[b];
      PairParams p;
      const double inv_e = inv_e_star(ma) + inv_e_star(mb);
      if (inv_e <= 0.0) {  // rigid–rigid never meet (walls do not touch walls)
        pairs_[a * count_ + b] = p;
        continue;
      }
      p.e_star_pa = 1.0 / inv_e;
      p.g_star_pa = 1.0 / (inv_g_star(ma) + inv_g_star(mb));
      // Eq. 10 as corrected: body i takes the share E*/E_i* of the indentation; rigid walls take none.
      p.share_a = p.e_star_pa * inv_e_star(ma);
      p.share_b = p.e_star_pa * inv_e_star(mb);
      // Mixing rule: arithmetic mean of the two materials unless an override names the pair. Friction is
      // the partner's kind: a pair with a rigid material (a wall) takes the materials' friction_wall, two
      // particles their friction_particle.
      p.restitution = 0.5 * (ma.restitution + mb.restitution);
      p.friction = ma.rigid || mb.rigid ? 0.5 * (ma.friction_wall + mb.friction_wall)
                                        : 0.5 * (ma.friction_particle + mb.friction_particle);
      p.rolling_friction = 0.5 * (ma.rolling_friction + mb.rolling_friction);
      for (const auto& o : overrides) {
        if ((static_cast<std::size_t>(o.material_a) == a && static_cast<std::size_t>(o.material_b) == b) ||
            (static_cast<std::size_t>(o.material_a) == b && static_cast<std::size_t>(o.material_b) == a)) {
          p.restitution = o.restitution;
          p.friction = o.friction;
          p.rolling_friction = o.rolling_friction;
        }
      }
      // The damping ratio fitted to the damping model's own decay (restitution.hpp); none: elastic.
      if (law.damping == DampingModel::kHertz) p.damping_ratio = hertz_damping_ratio(p.restitution);
      else if (law.damping == DampingModel::kLinearViscous) p.damping_ratio = linear_damping_ratio(p.restitution);
      if (linear_springs) {
        p.kn_linear_n_m = springs.normal_stiffness_n_m;
        p.kt_linear_n_m = springs.normal_stiffness_n_m * springs.tangential_ratio;
      }
      pairs_[a * count_ + b] = p;
    }
  }
}

}  // namespace spread::dem
