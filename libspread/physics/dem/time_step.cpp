#include "libspread/physics/dem/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/particles.hpp"

namespace spread::dem {

double hertz_contact_time_s(double m_eff_kg, double r_eff_m, double e_star_pa, double impact_speed_m_s) {
  return 2.87 * std::pow(m_eff_kg * m_eff_kg / (r_eff_m * e_star_pa * e_star_pa * impact_speed_m_s), 0.2);
}

double linear_contact_time_s(double m_eff_kg, double stiffness_n_m) {
  return kPi / std::sqrt(stiffness_n_m / m_eff_kg);
}

double stable_step_bound_s(const ContactLaw& law, const PairParams& pair, double m_eff_kg, double r_eff_m,
                           double impact_speed_m_s, bool rotation) {
  // The stiffest the springs get: Hertz's at the largest overlap of an elastic impact at this speed.
  double k_n = 0.0, k_t = 0.0;
  double delta_max = 0.0;
  if (law.normal == NormalModel::kHertz)
    delta_max = std::pow(15.0 * m_eff_kg * impact_speed_m_s * impact_speed_m_s / (16.0 * pair.e_star_pa * std::sqrt(r_eff_m)), 0.4);
  if (law.normal == NormalModel::kHertz) k_n = 2.0 * pair.e_star_pa * std::sqrt(r_eff_m * delta_max);
  else if (law.normal == NormalModel::kLinear) k_n = pair.kn_linear_n_m;
  if (law.tangential == TangentialModel::kThornton) k_t = 8.0 * pair.g_star_pa * std::sqrt(r_eff_m * delta_max);
  else if (law.tangential == TangentialModel::kLinear) k_t = pair.kt_linear_n_m;
  // A solid sphere: I = 2/5 m R², so 1 + m R²/I = 3.5 (tangential motion drives rotation too).
  const double tangential_factor = rotation ? 3.5 : 1.0;
  const double w2 = std::max(k_n, k_t * tangential_factor) / m_eff_kg;
  return 2.0 / std::sqrt(w2);
}

StepChoice choose_time_step(const std::vector<Material>& materials, const PairTable& pair_table,
                            const EngineParams& params, double fastest_wall_speed_m_s) {
  // Contact time and stability over every material pair at the smallest radius (t_c ∝ R): as particle
  // against a wall (R* = r, M* = m) and against an equal particle (R* = r/2, M* = m/2).
  const double v = params.impact_speed_m_s > 0.0 ? params.impact_speed_m_s
                                                 : std::max(1.0, fastest_wall_speed_m_s + 5.0);
  const double r = params.min_particle_radius_m;
  double tc = std::numeric_limits<double>::infinity();
  double bound = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < materials.size(); ++a) {
    if (materials[a].rigid) continue;
    const double m = sphere_mass(materials[a].density_kg_m3, r);
    for (std::size_t b = 0; b < materials.size(); ++b) {
      const PairParams& pp = pair_table(static_cast<int>(a), static_cast<int>(b));
      for (int partner = 0; partner < 2; ++partner) {
        const double r_eff = partner == 0 ? r : 0.5 * r;
        const double m_eff = partner == 0 ? m : 0.5 * m;
        const double t = params.contact_law.normal == NormalModel::kHertz
                             ? hertz_contact_time_s(m_eff, r_eff, pp.e_star_pa, v)
                             : linear_contact_time_s(m_eff, pp.kn_linear_n_m);
        tc = std::min(tc, t);
        bound = std::min(bound, stable_step_bound_s(params.contact_law, pp, m_eff, r_eff, v, params.has(effect::kRotation)));
      }
    }
  }
  StepChoice choice;
  choice.contact_time_s = tc;
  choice.stable_bound_s = bound;
  // 0 means "automatic"; a NaN (or a negative step) must not quietly become that.
  if (!(params.dt_s >= 0.0)) {
    std::ostringstream os;
    os << "dt_s (scene: numerics.dt_contact_s) = " << params.dt_s
       << " s: must be 0 (automatic, t_c/N_c) or a finite step > 0";
    throw std::invalid_argument(os.str());
  }
  if (params.dt_s > 0.0) {
    if (params.dt_s > bound) {
      std::ostringstream os;
      os << "dt_s (scene: numerics.dt_contact_s) = " << params.dt_s << " s exceeds the stable bound " << bound
         << " s of the stiffest contact (impact speed " << v << " m/s); use at most that, or leave it 0 for t_c/N_c = "
         << tc / params.contact_steps << " s";
      throw std::invalid_argument(os.str());
    }
    choice.dt_s = params.dt_s;
  } else {
    choice.dt_s = std::min(tc / params.contact_steps, bound);
  }
  return choice;
}

}  // namespace spread::dem
