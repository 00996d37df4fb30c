#pragma once
// Summary statistics of launch samples (Run::stats_json of a table, the `launch` block of simulate).
#include <span>
#include <string>

#include "libspread/core/vec3.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::launch {

struct LaunchStatistics {
  int count = 0;
  double speed_mean_m_s = 0.0;                 // |v| at launch, inertial frame
  double speed_sd_m_s = 0.0;                   // sample standard deviation
  double angle_from_tangent_deg_mean = 0.0;    // atan2(v·e_r, |v·e_θ|): 0 = tangential, 90 = radial
  double elevation_deg_mean = 0.0;             // atan2(v_z, |v_horizontal|)
  double launch_time_mean_s = 0.0;
  double diameter_mean_m = 0.0;
  double total_mass_kg = 0.0;
};

// rim_speed_m_s = ω R to undo the normalisation of the samples.
LaunchStatistics launch_statistics(std::span<const tables::LaunchSample> samples, double rim_speed_m_s);

// {"count":…, "speed_mean":…, "speed_sd":…, "angle_from_tangent_deg_mean":…, "elevation_deg_mean":…,
//  "launch_time_mean_s":…, "diameter_mean_m":…, "total_mass_kg":…} (speeds in m/s).
std::string to_json(const LaunchStatistics& stats);

}  // namespace spread::launch
