// spread_trajectory: one flight with the prediction's integrator settings. Inputs are checked here so
// that every bad input has its status code (the flight module would throw std::invalid_argument).
#include <cmath>
#include <initializer_list>

#include "capi/src/tables_handle.hpp"
#include "libspread/predict/flight_defaults.hpp"

namespace {

spread::Vec3 vec(const double (&v)[3]) { return spread::Vec3(v[0], v[1], v[2]); }
void put(const spread::Vec3& v, double (&out)[3]) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

bool all_finite(const spread_trajectory_def& d) {
  for (double v : {d.diameter_m, d.density_kg_m3, d.ground_z_m, d.air_density_kg_m3, d.air_viscosity_pa_s}) {
    if (!std::isfinite(v)) return false;
  }
  for (int i = 0; i < 3; ++i) {
    for (double v : {d.position_m[i], d.velocity_m_s[i], d.spin_rad_s[i], d.wind_m_s[i]}) {
      if (!std::isfinite(v)) return false;
    }
  }
  return true;
}

}  // namespace

extern "C" spread_status spread_trajectory(const spread_trajectory_def* def, spread_landing* out_landing) {
  if (def == nullptr || out_landing == nullptr) return SPREAD_ERROR_NULL_POINTER;
  if (def->struct_size < spread::capi::kTrajectoryDefV1Size) return SPREAD_ERROR_OUT_OF_RANGE;
  if (!all_finite(*def)) return SPREAD_ERROR_NOT_FINITE;
  if (!(def->diameter_m > 0.0) || !(def->density_kg_m3 > 0.0) || def->air_density_kg_m3 < 0.0 ||
      !(def->air_viscosity_pa_s > 0.0) || def->position_m[2] < def->ground_z_m) {
    return SPREAD_ERROR_OUT_OF_RANGE;
  }
  if ((def->effects & ~uint32_t{SPREAD_EFFECT_ALL}) != 0) return SPREAD_ERROR_UNKNOWN_EFFECT;
  try {
    spread::flight::Granule granule;
    granule.diameter_m = def->diameter_m;
    granule.density_kg_m3 = def->density_kg_m3;
    spread::flight::State launch;
    launch.position_m = vec(def->position_m);
    launch.velocity_m_s = vec(def->velocity_m_s);
    launch.spin_rad_s = vec(def->spin_rad_s);
    spread::flight::Air air;
    air.density_kg_m3 = def->air_density_kg_m3;
    air.viscosity_pa_s = def->air_viscosity_pa_s;
    air.wind_m_s = vec(def->wind_m_s);
    const auto landing = spread::flight::fly_to_ground(granule, launch, def->ground_z_m, air, def->effects,
                                                       spread::predict::default_flight_settings());
    put(landing.state.position_m, out_landing->position_m);
    put(landing.state.velocity_m_s, out_landing->velocity_m_s);
    put(landing.state.spin_rad_s, out_landing->spin_rad_s);
    out_landing->flight_time_s = landing.flight_time_s;
    out_landing->steps = landing.steps;
    return landing.landed ? SPREAD_OK : SPREAD_ERROR_NOT_LANDED;
  } catch (const std::bad_alloc&) {
    return SPREAD_ERROR_OUT_OF_MEMORY;
  } catch (...) {
    return SPREAD_ERROR_INTERNAL;
  }
}
