#include "libspread/dem/time_step.hpp"

#include <algorithm>
#include <cmath>

#include "libspread/core/vec3.hpp"

namespace spread::dem {

double hertz_contact_time_s(double m_eff_kg, double r_eff_m, double e_star_pa, double impact_speed_m_s) {
  return 2.87 * std::pow(m_eff_kg * m_eff_kg / (r_eff_m * e_star_pa * e_star_pa * impact_speed_m_s), 0.2);
}

double linear_contact_time_s(double m_eff_kg, double stiffness_n_m) {
  return kPi / std::sqrt(stiffness_n_m / m_eff_kg);
}

double stable_step_bound_s(ContactModel model, const PairParams& pair, double m_eff_kg, double r_eff_m,
                           double impact_speed_m_s, bool rotation) {
  double k_n = 0.0, k_t = 0.0;
  if (model == ContactModel::kHertzThornton) {
    const double delta_max = std::pow(15.0 * m_eff_kg * impact_speed_m_s * impact_speed_m_s /
                                          (16.0 * pair.e_star_pa * std::sqrt(r_eff_m)), 0.4);
    k_n = 2.0 * pair.e_star_pa * std::sqrt(r_eff_m * delta_max);
    k_t = 8.0 * pair.g_star_pa * std::sqrt(r_eff_m * delta_max);
  } else {
    k_n = pair.kn_linear_n_m;
    k_t = pair.kt_linear_n_m;
  }
  // A solid sphere: I = 2/5 m R², so 1 + m R²/I = 3.5 (tangential motion drives rotation too).
  const double tangential_factor = rotation ? 3.5 : 1.0;
  const double w2 = std::max(k_n, k_t * tangential_factor) / m_eff_kg;
  return 2.0 / std::sqrt(w2);
}

}  // namespace spread::dem
