#pragma once
// The simulated spreader ECU without any I/O: set-points in (validated, counted when bad), one loop
// step at a time (disc dynamics, automatic rpm solving, metering, pattern prediction), a status out.
// Transports (LCM, CAN) translate their messages into these calls and nothing else.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "libspread/control/disc_speed_model.hpp"
#include "libspread/control/ecu_command.hpp"
#include "libspread/control/ecu_parameters.hpp"
#include "libspread/control/ecu_status.hpp"
#include "libspread/control/fault.hpp"
#include "libspread/control/gate_response.hpp"
#include "libspread/control/rpm_for_width_solver.hpp"
#include "libspread/control/section_planner.hpp"
#include "libspread/control/spread_predictor.hpp"
#include "libspread/core/clock.hpp"

namespace spread::firmware {

// nullopt: accepted and applied. A Fault: rejected, counted, state unchanged.
using Rejection = std::optional<Fault>;

inline constexpr std::size_t kMaxMaterialNameLength = 63;  // bytes

class Ecu {
 public:
  // `clock`, `predictor` (may be null: no tables, no automatic mode) and `planner` (may be null: no
  // section control through the discs) must outlive the ECU. With a predictor, the constructor samples
  // each material's width curve (the automatic mode's search space): materials x (range /
  // curve_rpm_step) predictions, done once here rather than in the loop.
  Ecu(const Clock& clock, const EcuParameters& parameters, SpreadPredictor* predictor = nullptr,
      SectionPlanner* planner = nullptr);

  // A whole command: applied entirely or not at all.
  Rejection apply_command(const EcuCommand& command);

  // Single set-values from a task controller (ISOBUS process data); each validated on its own.
  Rejection set_rate_setpoint(double rate_kg_ha);
  Rejection set_width_setpoint(double width_m);
  Rejection set_rpm_setpoint(double rpm);
  // The task controller switches the work state; it is then supervised (note_task_controller_alive).
  Rejection set_work_state(bool on);
  Rejection set_section_mask(std::uint32_t mask);  // bit i = section i+1; only installed sections
  // Border or field-edge spreading on one side (BorderMode, raw: validated), the edge line `gap_m` [m]
  // inside the bout's edge (0: at it; water: 1 m with a border spreading device, 3 m without).
  Rejection set_border(std::int32_t mode, double gap_m);
  // Wind compensation: each disc set apart for the measured wind (needs the tables and the planner).
  Rejection set_wind_compensation(bool on);
  // The measured wind: across the travel, to the right, and along it, forward [m/s].
  Rejection set_wind(double wind_x_m_s, double wind_y_m_s);
  // The material in the hopper when no LCM command names it (a CAN-only machine: chosen at the terminal).
  Rejection set_material(std::string_view material);

  // A measured ground speed, valid for `valid_for` (the source's own timeout) unless renewed.
  Rejection set_ground_speed(double speed_m_s, TravelDirection direction, Nanoseconds valid_for);
  // The speed source reports "error" or "not available": there is no valid speed from now on.
  void set_ground_speed_unavailable();
  // The task controller is alive: its status message (ISO 11783-10, every 2 s) or a set-value from it.
  void note_task_controller_alive();
  // The task controller is gone without falling silent (its address taken by another NAME, or released,
  // or it refuses our working set): handled as a task controller whose status stopped (work state off,
  // task_controller_lost), at once; the fault holds until a task controller switches the work state.
  void task_controller_gone();
  // The CAN link's address claim (ISO 11783-5): without a standing claim nobody can address or supervise
  // the ECU, so metering stays closed; losing the claim also switches the work state off.
  void set_bus_address(bool has_address);

  // Faults found by a transport before anything reached the ECU (undecodable frames, ...).
  void record_fault(Fault fault);

  // One loop step of dt_s [s] (> 0). Allocation-free.
  void step(double dt_s);

  // Current state; cheap, allocation-free. `material` views the ECU's own string.
  EcuStatus status() const;

  const EcuParameters& parameters() const { return parameters_; }
  const FaultLog& faults() const { return faults_; }
  bool has_predictor() const { return predictor_ != nullptr; }
  // The materials of the launch table, in its order (empty without tables): the products it can spread.
  std::vector<std::string> material_names() const;

 private:
  // Which controller last changed the master work state; that one is supervised.
  enum class WorkStateOwner : std::uint8_t { kNone, kLcm, kTaskController };

  Rejection reject(Fault fault);
  Rejection check_finite(double value);
  Rejection check_range(double value, double min, double max);
  Rejection check_material(std::string_view material, Mode mode) const;
  Rejection check_sequence(std::int64_t sequence);
  void supervise_controllers(Nanoseconds now);
  bool disc_at_speed(int disc) const;  // within tolerance of its own target, itself fast enough to spread
  void solve_rpm_for_width();
  void predict_pattern();
  void check_achieved_width();
  std::uint32_t installed_mask() const;
  // Whether `mask` narrows a side (its outermost section off, one nearer the centre on).
  bool needs_narrowing(std::uint32_t mask) const;
  // Tables loaded but no material known: a narrowing, border or wind plan cannot be made.
  bool needs_planning_without_material() const { return predictor_ != nullptr && material_.empty(); }
  const WidthCurve* curve_for(std::string_view material) const;
  void plan_sides();
  void step_gates(double dt_s);
  double field_rpm_actual() const;

  // What one disc does on this pass (section control through the discs, section_planner.hpp).
  enum class SideKind : std::uint8_t {
    kField,      // the field's setting: all its sections out to the bout's edge (or it cannot be narrowed)
    kOff,        // every section of its side off: no flow
    kNarrowed,   // its own setting from the planner, thrown no further than the last section on
    kPending,    // a narrowing asked for and not yet planned: the field's setting meanwhile
  };
  struct SideState {
    SideKind kind = SideKind::kField;
    double rpm_target = 0.0;           // [r/min]
    double drop_point_turn_rad = 0.0;  // from the table's drop point [rad]
    double flow_fraction = 1.0;        // of the field's flow to this disc [-]
    std::uint32_t sections = 0;        // the sections this disc spreads while it meters (bit i = section i+1)
    bool border = false;               // its edge is a border or field edge: nothing may land beyond it
  };
  // Whether disc `disc`, metering on the last step, may go on metering while it changes speed to a new
  // setting of its side (a side change, a border engaged or left): see step().
  bool keeps_metering_while_changing_speed(int disc) const;

  const Clock& clock_;
  EcuParameters parameters_;
  SpreadPredictor* predictor_;
  SectionPlanner* planner_;
  RpmForWidthSolver solver_;
  std::vector<WidthCurve> curves_;  // one per predictor material, sampled at construction
  FaultLog faults_;
  std::array<DiscSpeedModel, 2> discs_;  // kLeftDisc, kRightDisc (a one-disc machine uses the left)
  std::array<GateResponse, 2> gates_;    // each disc's metering gate

  // Commanded state.
  Mode mode_ = Mode::kManual;
  double rate_setpoint_kg_ha_ = 0.0;
  double width_setpoint_m_ = 0.0;
  double rpm_setpoint_manual_ = 0.0;
  std::string material_;
  BorderMode border_mode_ = BorderMode::kOff;
  double border_gap_m_ = 0.0;     // [m]
  bool wind_compensation_ = false;
  double wind_x_m_s_ = 0.0;       // measured wind across the travel, to the right [m/s]
  double wind_y_m_s_ = 0.0;       // along the travel, forward [m/s]
  std::int32_t section_count_;
  std::uint32_t section_mask_ = 0;  // set to all installed sections by the constructor
  bool work_state_setpoint_ = false;
  WorkStateOwner work_state_owner_ = WorkStateOwner::kNone;
  std::optional<bool> lcm_work_state_;  // last work state an LCM command asked for (none: first is an edge)
  std::int64_t last_sequence_ = -1;
  bool has_sequence_ = false;
  std::optional<std::int64_t> jump_sequence_;  // a refused jump; the command after it confirms it
  std::optional<Nanoseconds> last_command_time_;
  std::optional<Nanoseconds> last_task_controller_time_;
  bool lcm_lost_ = false;  // the LCM controller owned the work state and fell silent (until heard again)
  bool tc_lost_ = false;   // the same for the task controller
  bool tc_gone_ = false;   // the TC's session ended without silence (task_controller_gone), until it switches again
  bool has_bus_address_ = true;  // no CAN link, or one with a standing address claim

  // Ground speed as last measured; usable only until `speed_valid_until_` (none: no valid speed).
  double ground_speed_m_s_ = 0.0;
  TravelDirection direction_ = TravelDirection::kUnknown;
  std::optional<Nanoseconds> speed_valid_until_;
  bool speed_never_expires_ = false;  // a command's speed with the command timeout off

  // Derived state, updated by step().
  std::array<SideState, 2> sides_{};
  static constexpr std::uint8_t kWindPending = 4;  // pending_: bit 0 left, 1 right, 2 the wind's plan
  std::uint8_t pending_ = 0;
  bool wind_compensated_ = false;  // the discs run a wind plan
  bool border_applied_ = false;    // the border side runs its border plan
  std::array<SideNarrowing, 2> last_wind_plan_{};
  std::optional<SidePlanKey> last_wind_key_;
  std::uint32_t middle_bit_ = 0;           // odd count: the section on the centre line, spread by either disc
  std::array<bool, 2> disc_metering_{};    // each disc receiving fertiliser now
  // Each disc metering through a new setting of its side, until it reaches that setting's speed (step()).
  std::array<bool, 2> side_changing_{};
  std::uint32_t section_actual_mask_ = 0;  // sections actually spread now (ecu_status.hpp)
  std::optional<SidePlanKey> prepared_;    // the field setting whose narrowings were last prepared
  double rpm_target_ = 0.0;
  bool solve_pending_ = false;
  bool width_reachable_ = true;
  double width_margin_m_ = 0.0;   // automatic mode: extra width asked of the solver after a miss [m]
  bool metering_open_ = false;
  double speed_in_use_m_s_ = 0.0;  // valid ground speed, 0 when there is none [m/s]
  double mass_flow_kg_s_ = 0.0;
  bool prediction_pending_ = true;
  double predicted_at_rpm_ = 0.0;
  bool predicted_settled_ = false;  // the last prediction was made with the disc at its target
  SpreadPrediction prediction_{};
  bool prediction_valid_ = false;
  std::int64_t steps_ = 0;
};

}  // namespace spread::firmware
