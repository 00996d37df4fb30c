#include "libspread/physics/flight/flight_parameters.hpp"

namespace spread::flight::detail {

FlightParameters make_flight_parameters(const Granule& granule, const State& launch, const Air& air,
                                        const Settings& settings) {
  FlightParameters p;
  const double d = granule.diameter_m;
  const double mu = air.viscosity_pa_s;
  const double mass_kg = granule_mass_kg(granule);
  p.drag_rate_per_s = 3.0 * mu / (4.0 * granule.density_kg_m3 * d * d);
  p.reynolds_per_speed_s_m = air.density_kg_m3 * d / mu;
  p.magnus_rate_per_m = 3.0 * air.density_kg_m3 / (4.0 * granule.density_kg_m3 * d);
  p.diameter_m = d;
  p.lift = settings.lift;
  p.spin_decay_rate_per_s = 10.0 * mu * d / mass_kg;
  p.spin_reynolds_per_rad_s = air.density_kg_m3 * d * d / (4.0 * mu);
  for (int i = 0; i < 3; ++i) {
    p.wind_m_s[i] = air.wind_m_s[i];
    p.constant_spin_rad_s[i] = launch.spin_rad_s[i];
  }
  p.constant_spin_norm_rad_s = launch.spin_rad_s.norm();
  p.gravity_m_s2 = settings.gravity_m_s2;
  p.terms = derive_term_parameters(granule, launch, air, settings);
  return p;
}

}  // namespace spread::flight::detail
