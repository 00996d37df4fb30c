#include "libspread/analysis/predict/launch_landing_keys.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "libspread/core/vec3.hpp"

namespace spread::predict {

void landing_rank_keys(std::span<const tables::LaunchSample> samples, double rpm, double disc_radius_m,
                       double disc_height_m, double density_kg_m3, const flight::Settings& settings,
                       std::span<double> radius_m, std::span<double> transverse_x_m) {
  if (transverse_x_m.size() != samples.size() || radius_m.size() != samples.size()) {
    throw std::invalid_argument("landing_rank_keys: key outputs differ in size from the row");
  }
  // Stored samples are normalised (docs/design.md §4): velocity / ωR, spin / ω.
  const double omega_rad_s = rpm * 2.0 * kPi / 60.0;
  const double rim_speed_m_s = omega_rad_s * disc_radius_m;
  const flight::Air still_air;
  const flight::EffectSet effects = flight::kDrag | flight::kMagnus | flight::kSpinDecay;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const tables::LaunchSample& s = samples[k];
    const flight::Granule granule{s.diameter_m, density_kg_m3};
    flight::State launch;
    // A disc placed so low that a sample starts below the ground is refused per request (Predictor); for
    // the order, start it at the ground.
    launch.position_m = Vec3(s.x_m, s.y_m, std::max(0.0, s.z_m + disc_height_m));
    launch.velocity_m_s = rim_speed_m_s * Vec3(s.vx_norm, s.vy_norm, s.vz_norm);
    launch.spin_rad_s = omega_rad_s * Vec3(s.wx_norm, s.wy_norm, s.wz_norm);
    const flight::Landing landing = flight::fly_to_ground(granule, launch, 0.0, still_air, effects, settings);
    double x = landing.state.position_m.x(), y = landing.state.position_m.y();
    if (!std::isfinite(x) || !std::isfinite(y)) {  // keys must be finite: fall back to the launch point
      x = s.x_m;
      y = s.y_m;
    }
    transverse_x_m[k] = x;
    radius_m[k] = std::hypot(x, y);
  }
}

}  // namespace spread::predict
