#include "libspread/physics/launch/launch_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace spread::launch {

LaunchStatistics launch_statistics(std::span<const tables::LaunchSample> samples, double rim_speed_m_s) {
  LaunchStatistics st;
  st.count = static_cast<int>(samples.size());
  if (samples.empty()) return st;
  constexpr double kDeg = 180.0 / kPi;
  double sum_speed = 0.0, sum_speed2 = 0.0;
  for (const tables::LaunchSample& s : samples) {
    const double vx = s.vx_norm * rim_speed_m_s, vy = s.vy_norm * rim_speed_m_s, vz = s.vz_norm * rim_speed_m_s;
    const double speed = std::sqrt(vx * vx + vy * vy + vz * vz);
    sum_speed += speed;
    sum_speed2 += speed * speed;
    const double rho = std::hypot(static_cast<double>(s.x_m), static_cast<double>(s.y_m));
    const double er_x = rho > 0.0 ? s.x_m / rho : 1.0, er_y = rho > 0.0 ? s.y_m / rho : 0.0;
    const double v_radial = vx * er_x + vy * er_y;
    const double v_tangential = -vx * er_y + vy * er_x;
    st.angle_from_tangent_deg_mean += std::atan2(v_radial, std::abs(v_tangential)) * kDeg;
    st.elevation_deg_mean += std::atan2(vz, std::hypot(vx, vy)) * kDeg;
    st.launch_time_mean_s += s.t_s;
    st.diameter_mean_m += s.diameter_m;
    st.total_mass_kg += s.mass_kg;
  }
  const double n = static_cast<double>(samples.size());
  st.speed_mean_m_s = sum_speed / n;
  st.speed_sd_m_s = samples.size() > 1 ? std::sqrt(std::max(0.0, (sum_speed2 - n * st.speed_mean_m_s * st.speed_mean_m_s) / (n - 1.0))) : 0.0;
  st.angle_from_tangent_deg_mean /= n;
  st.elevation_deg_mean /= n;
  st.launch_time_mean_s /= n;
  st.diameter_mean_m /= n;
  return st;
}

std::string to_json(const LaunchStatistics& st) {
  char text[512];
  std::snprintf(text, sizeof text,
                "{\"count\":%d,\"speed_mean\":%.9g,\"speed_sd\":%.9g,\"angle_from_tangent_deg_mean\":%.9g,"
                "\"elevation_deg_mean\":%.9g,\"launch_time_mean_s\":%.9g,\"diameter_mean_m\":%.9g,"
                "\"total_mass_kg\":%.9g}",
                st.count, st.speed_mean_m_s, st.speed_sd_m_s, st.angle_from_tangent_deg_mean,
                st.elevation_deg_mean, st.launch_time_mean_s, st.diameter_mean_m, st.total_mass_kg);
  return text;
}

}  // namespace spread::launch
