#pragma once
// Snapshot of the ECU after a loop step: what status_t and the CAN actual values report.
#include <array>
#include <cstdint>
#include <string_view>

#include "libspread/control/ecu_command.hpp"
#include "libspread/control/fault.hpp"

namespace spread::firmware {

struct EcuStatus {
  Nanoseconds time{};                  // ECU clock at the snapshot
  std::int64_t steps = 0;              // loop steps since start
  Mode mode = Mode::kManual;
  double rpm_actual = 0.0;             // disc speed [r/min]
  double rpm_target = 0.0;             // set-point the disc drive follows (manual or solved) [r/min]
  double rate_setpoint_kg_ha = 0.0;    // [kg/ha]
  double rate_actual_kg_ha = 0.0;      // rate delivered to the ground now [kg/ha] (0 while not metering)
  double width_setpoint_m = 0.0;       // [m]
  double width_actual_m = 0.0;         // width of the sections switched on [m]
  double ground_speed_m_s = 0.0;       // [m/s]
  double mass_flow_kg_s = 0.0;         // metered mass flow, all sections [kg/s]
  double throw_width_m = 0.0;          // predicted at rpm_actual [m]; NaN when no prediction
  double effective_width_m = 0.0;      // predicted at rpm_actual and the CV target [m]; NaN when none
  double cv_percent = 0.0;             // predicted CV at the set-point width [%]; NaN when none
  // Standard errors of the three predictions above (sampling of the launch table); NaN when none.
  double throw_width_se_m = 0.0;       // [m]
  double effective_width_se_m = 0.0;   // [m]
  double cv_se_percent = 0.0;          // [percentage points]
  bool width_reachable = true;         // automatic mode: set-point width reachable at the CV target
  bool work_state_setpoint = false;    // master switch as commanded
  bool work_state_actual = false;      // actually spreading (master on, a section on, metering open)
  std::int32_t section_count = 0;
  std::uint16_t section_mask = 0;      // bit i = section i+1 on, as commanded
  // Sections actually spread now (0 while metering is closed): the set-point, unless the discs cannot
  // narrow a side that far (yet) — a narrowing still being planned, no tables to plan it with, or a strip
  // beyond the edge line still receiving at least EcuParameters::section_on_rate_percent of the field's
  // rate — or a disc is still changing speed (its flow waits). Inner sections off between sections on
  // cannot be skipped by a spinning disc and stay on.
  std::uint16_t section_actual_mask = 0;
  // Each disc (kLeftDisc, kRightDisc as the driver sees them; a one-disc machine: the left only).
  std::array<double, 2> disc_rpm_actual{};           // [r/min]
  std::array<double, 2> disc_rpm_target{};           // [r/min]
  std::array<double, 2> disc_drop_point_turn_rad{};  // from the table's drop point [rad]
  std::array<double, 2> disc_flow_fraction{};        // of the field's flow to that disc [-] (0: closed)
  // What each gate delivers now, of the field's flow to that disc [-]: disc_flow_fraction followed at the
  // gate's speed (EcuParameters::gate_full_travel_s; equal to it with an ideal gate).
  std::array<double, 2> disc_flow_delivered{};
  std::uint8_t sides_pending = 0;      // plans still searched: bit d disc d's side, bit 2 the wind's
  BorderMode border_mode = BorderMode::kOff;
  double border_gap_m = 0.0;           // [m]
  bool border_applied = false;         // the border side runs its border setting
  bool wind_compensation = false;      // asked for
  bool wind_compensated = false;       // the discs run a setting made for the wind
  double wind_x_m_s = 0.0;             // measured wind across the travel, to the right [m/s]
  double wind_y_m_s = 0.0;             // along the travel, forward [m/s]
  std::string_view material;           // valid until the next command
  std::int64_t last_command_sequence = -1;
  std::uint32_t fault_codes = 0;       // active faults, bit = Fault value
  std::array<std::uint64_t, kFaultCount> fault_counts{};
};

}  // namespace spread::firmware
