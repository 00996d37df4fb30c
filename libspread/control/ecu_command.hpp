#pragma once
// A complete command as received (LCM command_t), before validation: raw values, so that the ECU
// itself decides what is out of range and counts it.
#include <array>
#include <cstdint>
#include <string_view>

#include "libspread/control/ecu_parameters.hpp"

namespace spread::firmware {

enum class Mode : std::int8_t { kManual = 0, kAutomatic = 1 };

// Direction of travel as a speed source reports it (ISO 11783-7 machine direction).
enum class TravelDirection : std::int8_t { kForward = 0, kReverse = 1, kUnknown = 2 };

// Border and edge spreading on the last pass along a field edge (docs/field-calibration.md "Border and
// edge spreading"): a border (road, path, water: nothing over the edge line) or another field (full rate
// to the line), on the driver's left or right.
enum class BorderMode : std::int8_t {
  kOff = 0,
  kLeftBorder = 1,
  kRightBorder = 2,
  kLeftFieldEdge = 3,
  kRightFieldEdge = 4,
};

struct EcuCommand {
  std::int64_t sequence = 0;          // strictly increasing per sender
  std::int32_t mode = 0;              // 0 manual, 1 automatic (raw: validated by the ECU)
  double rate_setpoint_kg_ha = 0.0;   // application rate [kg/ha]
  double width_setpoint_m = 0.0;      // working (bout) width [m]
  double ground_speed_m_s = 0.0;      // forward speed [m/s]
  double rpm_setpoint = 0.0;          // disc speed in manual mode [r/min]; ignored in automatic
  // Master work state this sender asks for. Applied when it differs from the sender's previous one (or
  // is its first): repeating a command does not undo another controller's switch-off.
  bool work_state = false;
  std::string_view material;          // material name as in the tables
  std::int32_t section_count = 0;     // sections in use, 1..16
  std::array<bool, kMaxSections> section_on{};  // first section_count entries are meaningful
  std::int32_t border_mode = 0;       // BorderMode (raw: validated by the ECU)
  double border_gap_m = 0.0;          // the edge line this far inside the bout's edge [m]
  bool wind_compensation = false;     // set the discs apart for the wind
  double wind_x_m_s = 0.0;            // measured wind across the travel, to the right [m/s]
  double wind_y_m_s = 0.0;            // along the travel, forward [m/s]
};

}  // namespace spread::firmware
