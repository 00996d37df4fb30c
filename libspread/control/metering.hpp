#pragma once
// Metering: the mass flow the metering gates must deliver so that the ground receives the set-point
// rate over the width being worked. docs/design.md §3:
//   Q [kg/s] = rate [kg/ha] * W [m] * v [km/h] / 36000
// (1 ha = 10^4 m², 1 km/h = 1/3.6 m/s: rate/10^4 * W * v/3.6 = rate * W * v / 36000.)

namespace spread::firmware {

inline constexpr double kKmPerHourPerMeterPerSecond = 3.6;

// rate_kg_ha: application rate [kg/ha]; working_width_m: width actually spread [m];
// ground_speed_m_s: forward speed [m/s]. Returns mass flow [kg/s]; never negative.
double mass_flow_kg_s(double rate_kg_ha, double working_width_m, double ground_speed_m_s);

// 1 kg/ha = 10^6 mg / 10^4 m² = 100 mg/m² (ISO 11783-11 DDI 6/7 unit).
inline constexpr double kMilligramPerSquareMetrePerKgPerHa = 100.0;

}  // namespace spread::firmware
