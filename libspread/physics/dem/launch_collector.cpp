// The collector: a particle beyond the collector cylinder has launched; its state is recorded and it
// leaves the DEM (the partitioned scheme hands it to the flight module).
#include <limits>

#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"

namespace spread::dem {

using detail::Clock;
using detail::seconds_since;

bool DemEngine::collects() const {
  return collector_.enabled || collector_.lost_below_z_m != -std::numeric_limits<double>::infinity();
}

void DemEngine::collect() {
  // Neither a collector nor a loss plane (a drum): no particle can leave, and the pass is not run.
  if (!collects()) return;
  const auto t0 = Clock::now();
  const std::size_t n = p_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!p_.active[i]) continue;
    bool remove = false;
    if (collector_.enabled) {
      const double dx = p_.x[i] - collector_.axis_point_m.x(), dy = p_.y[i] - collector_.axis_point_m.y();
      if (dx * dx + dy * dy > collector_.radius_m * collector_.radius_m) {
        LaunchRecord rec;
        rec.time_s = time_s_;
        rec.residence_s = time_s_ - p_.birth_time_s[i];
        rec.position_m = p_.position(i);
        rec.velocity_m_s = p_.velocity(i);
        rec.spin_rad_s = p_.spin(i);
        rec.diameter_m = 2.0 * p_.radius_m[i];
        rec.mass_kg = p_.mass_kg[i];
        rec.material = p_.material[i];
        rec.id = p_.id[i];
        launches_.push_back(rec);
        remove = true;
      }
    }
    if (!remove && p_.z[i] < collector_.lost_below_z_m) {
      ++stats_.lost;
      remove = true;
    }
    if (remove) {
      p_.active[i] = 0;
      ++inactive_;
    }
  }
  stats_.collector_s += seconds_since(t0);
}

}  // namespace spread::dem
