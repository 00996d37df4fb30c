#pragma once
// Machine and validation parameters of the simulated ECU. Every field states its unit.
#include <chrono>
#include <cstdint>

#include "libspread/control/rpm_for_width_solver.hpp"
#include "libspread/core/clock.hpp"

namespace spread::firmware {

inline constexpr int kMaxSections = 16;  // ISO 11783-11 condensed work state 1-16 (DDI 161/290)

struct EcuParameters {
  double disc_time_constant_s = 0.8;   // first-order lag of the disc drive [s]
  // Each metering gate's actuator: from shut to the field's flow in this time (gate_response.hpp); 0: an
  // ideal gate, the flow follows the command at once.
  double gate_full_travel_s = 0.0;     // [s]
  double rpm_max = 1200.0;             // highest accepted disc speed set-point [r/min]
  double auto_rpm_min = 300.0;         // automatic mode search range, low end [r/min]
  double auto_rpm_max = 1100.0;        // automatic mode search range, high end [r/min]
  double rate_max_kg_ha = 3000.0;      // highest accepted application rate set-point [kg/ha]
  double width_max_m = 54.0;           // maximum working width of the machine (DDI 70) [m]
  double speed_max_m_s = 20.0;         // highest accepted ground speed [m/s] (72 km/h)
  double wind_max_m_s = 30.0;          // highest accepted wind component [m/s]
  int section_count = 8;               // sections installed, 1..16 (a command may use fewer, never more)
  // Spinning discs, 1 or 2. With two, the sections left of the centre line are the left disc's and
  // those right of it the right disc's (with an odd count the middle one is both's); switching a side's
  // outer sections off narrows that disc's throw (section_planner.hpp), all of them closes its flow.
  int disc_count = 2;
  // Section control through the discs: the border threshold a narrowed side is searched with (of the
  // pass's mass beyond the last section on, as docs/field-calibration.md "Border and edge spreading"),
  // and the mean rate, of the field's, at which each of a narrowed side's sections counts as spread.
  double section_max_beyond_percent = 0.1;  // [%]
  double section_on_rate_percent = 10.0;    // [%]
  Nanoseconds fault_hold = std::chrono::seconds(2);       // event faults stay visible this long
  // The LCM controller that switched the work state on must repeat its command within this time, or the
  // ECU switches the work state off (0 = off). A speed in a command is valid for the same time.
  Nanoseconds command_timeout = std::chrono::seconds(2);
  // ISO 11783-10: a task controller sends its status every 2 s; three missed (6 s) and the client treats
  // it as lost. The work state it switched on is switched off then.
  Nanoseconds task_controller_timeout = std::chrono::seconds(6);
  // Metering interlock with the disc: granules dropped on a stopped or slow disc fall in a heap behind
  // the machine, and a disc off its target throws a different pattern. Metering opens only while the
  // disc target is at least `spreading_rpm_min` and the disc is within `disc_speed_tolerance` of it.
  double spreading_rpm_min = 200.0;    // [r/min]
  double disc_speed_tolerance = 0.05;  // |rpm - target| / target [-]
  double reprediction_rpm_step = 2.0;  // re-predict the status pattern when the disc moved this much [r/min]
  std::int64_t sequence_reorder_window = 1000;  // older sequence numbers within this window are stale
  // A sequence number further ahead than this is refused unless the next command continues from it (a
  // sender that really jumped); one corrupt or hostile number cannot make every later command stale.
  std::int64_t sequence_max_jump = 100;
  RpmSolverSettings solver{};          // automatic mode solver
};

// Throws std::invalid_argument naming the first bad field.
void validate(const EcuParameters& parameters);

}  // namespace spread::firmware
