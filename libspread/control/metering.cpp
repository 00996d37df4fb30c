#include "libspread/control/metering.hpp"

namespace spread::firmware {

double mass_flow_kg_s(double rate_kg_ha, double working_width_m, double ground_speed_m_s) {
  if (!(rate_kg_ha > 0.0) || !(working_width_m > 0.0) || !(ground_speed_m_s > 0.0)) return 0.0;
  const double speed_km_h = ground_speed_m_s * kKmPerHourPerMeterPerSecond;
  return rate_kg_ha * working_width_m * speed_km_h / 36000.0;
}

}  // namespace spread::firmware
