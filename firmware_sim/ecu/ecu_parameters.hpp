#pragma once
// Machine and validation parameters of the simulated ECU. Every field states its unit.
#include <chrono>
#include <cstdint>

#include "firmware_sim/ecu/clock.hpp"
#include "firmware_sim/ecu/rpm_for_width_solver.hpp"

namespace spread::firmware {

inline constexpr int kMaxSections = 16;  // ISO 11783-11 condensed work state 1-16 (DDI 161/290)

struct EcuParameters {
  double disc_time_constant_s = 0.8;   // first-order lag of the disc drive [s]
  double rpm_max = 1200.0;             // highest accepted disc speed set-point [r/min]
  double auto_rpm_min = 300.0;         // automatic mode search range, low end [r/min]
  double auto_rpm_max = 1100.0;        // automatic mode search range, high end [r/min]
  double rate_max_kg_ha = 3000.0;      // highest accepted application rate set-point [kg/ha]
  double width_max_m = 54.0;           // maximum working width of the machine (DDI 70) [m]
  double speed_max_m_s = 20.0;         // highest accepted ground speed [m/s] (72 km/h)
  int section_count = 8;               // sections installed at start, 1..16 (a command may change it)
  Nanoseconds fault_hold = std::chrono::seconds(2);       // event faults stay visible this long
  Nanoseconds command_timeout = std::chrono::seconds(2);  // no valid input this long -> metering closed; 0 = off
  double reprediction_rpm_step = 2.0;  // re-predict the status pattern when the disc moved this much [r/min]
  std::int64_t sequence_reorder_window = 1000;  // older sequence numbers within this window are stale
  RpmSolverSettings solver{};          // automatic mode solver
};

// Throws std::invalid_argument naming the first bad field.
void validate(const EcuParameters& parameters);

}  // namespace spread::firmware
