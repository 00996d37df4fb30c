#pragma once
// The field spread with the machine in the loop: the spreader ECU's own logic (libspread/control, the code
// firmware_sim runs) driven along the passes, and each moment's ground put down with the discs' state at
// that moment.
//
// Every loop period (the ECU's, 50 ms) the machine moves speed · period along its pass, and
//   1. the task controller (this module: the terminal's part, ISO 11783-10) decides each section: on where
//      the ground its strip will reach — the section's lateral band at the pattern's mass centre behind the
//      machine, moved ahead by what the machine covers in the look-ahead time — lies inside the boundary
//      and is not worked yet (coverage_map.hpp); without section control every section is on over the
//      pass. Border mode is asked for on the outermost headland round (a border on the right: rounds are
//      driven with the boundary on the driver's right), wind compensation when a wind blows;
//   2. the ECU gets the command a controller sends (Ecu::apply_command: rate, bout width, speed, disc speed,
//      sections, border, wind in the machine frame) and steps: its section planner narrows a side through
//      its disc (the border search over the C API, spread_find_edge_setting), wind compensation
//      (spread_compensate_wind), the discs follow their set-points with their lag, the metering interlock
//      and the gates with their travel time;
//   3. each disc's gate delivers rate · W / discs · distance · its opening (docs/design.md §3), stamped with
//      that disc's ground pattern at its actual speed, drop point and the wind (disc_stamps.hpp);
//   4. the sections actually spread mark their strips worked.
// Between passes the machine turns with the feed shut (the gates still closing deliver on a straight run-out
// first); with section control the tramlines are driven on to the innermost headland round's track, where
// a tractor turns, and the sections switch off over the worked headland.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "libspread/analysis/field/as_applied.hpp"
#include "libspread/analysis/field/boundary.hpp"
#include "libspread/analysis/field/pass.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/control/spread_predictor.hpp"

namespace spread::field {

struct MachineSettings {
  double target_rate_kg_ha = 200.0;
  double bout_width_m = 24.0;
  double rpm = 0.0;                 // the field's disc speed [r/min]
  double cell_m = 0.5;              // the grid's cell; stamps at most this far apart [m]
  double speed_m_s = 12.0 / 3.6;    // ground speed [m/s]
  double loop_period_s = 0.05;      // the ECU's loop (firmware_sim runs it at 20 Hz) [s]
  int section_count = 8;
  bool section_control = true;
  bool border = false;              // border mode on the outermost headland round
  double border_gap_m = 0.0;        // the border's line this far inside the bout's edge [m]
  double wind_east_m_s = 0.0;       // wind over the field [m/s]
  double wind_north_m_s = 0.0;
  bool wind_compensation = true;    // with a wind: the ECU sets the discs apart for it
  // Section switching ahead of the ground, as a task controller's turn-on and turn-off times: half the
  // gate's travel puts the delivered flow's middle on the switch line.
  double look_ahead_on_s = 0.5;     // [s]
  double look_ahead_off_s = 0.5;    // [s]
  double disc_time_constant_s = 2.0 / 3.0;  // a disc within 5 % of a new speed in 2 s (3 τ) [s]
  double gate_full_travel_s = 1.0;  // shut to the field's flow [s]
  double turn_s = 8.0;              // a headland turn, feed shut [s]
  double rpm_step_rpm = 10.0;       // the discs' speeds stamped to this step (disc_stamps.hpp) [r/min]
  // Called every kProgressSteps loop steps and at the end with (steps done, steps in all).
  std::function<void(std::size_t, std::size_t)> progress;
};

struct MachineRun {
  AsApplied applied;
  std::vector<Pass> passes;          // as driven (tramlines drawn on to the headland track with section control)
  std::size_t loop_steps = 0;
  std::size_t section_switches = 0;  // commanded section changes
  std::size_t stamps_built = 0;      // disc states met (disc_stamps.hpp)
  std::int64_t planner_searches = 0; // the ECU's narrowing, border and wind searches
  bool border_applied = false;       // the ECU ran its border setting on some step
};

// Throws spread::Error (kArgument, "field machine") for settings out of range (rate, bout, speed, period,
// section count, look-ahead, lags), a field disc speed outside the ECU's, or a command the ECU rejects
// (naming the fault); the predictor's refusals as disc_stamps.hpp.
MachineRun run_machine(const Boundary& boundary, std::vector<Pass> passes, firmware::SpreadPredictor& ecu_predictor,
                       predict::Predictor& predictor, const predict::PredictionRequest& field,
                       const MachineSettings& settings);

}  // namespace spread::field
