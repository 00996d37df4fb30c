#include "libspread/control/ecu.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "libspread/control/metering.hpp"

namespace spread::firmware {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const EcuParameters& validated(const EcuParameters& p) {
  validate(p);
  return p;
}

}  // namespace

Ecu::Ecu(const Clock& clock, const EcuParameters& parameters, SpreadPredictor* predictor, SectionPlanner* planner)
    : clock_(clock),
      parameters_(validated(parameters)),
      predictor_(predictor),
      planner_(planner),
      solver_(parameters.solver),
      faults_(parameters.fault_hold),
      discs_{DiscSpeedModel(parameters.disc_time_constant_s), DiscSpeedModel(parameters.disc_time_constant_s)},
      gates_{GateResponse(parameters.gate_full_travel_s), GateResponse(parameters.gate_full_travel_s)},
      section_count_(parameters.section_count) {
  material_.reserve(kMaxMaterialNameLength);  // later assignments never allocate
  // Sections start open and the master switch closed, as on a machine just switched on: the work
  // state set-point (LCM command or DDI 289) alone then starts spreading.
  section_mask_ = installed_mask();
  if (predictor_ != nullptr) {
    for (std::size_t i = 0; i < predictor_->material_count(); ++i) {
      const std::string_view name = predictor_->material_name(i);
      RpmRange range = predictor_->rpm_range(name);
      // Search the overlap of what the machine allows and what the tables cover.
      range.min_rpm = std::max(range.min_rpm, parameters_.auto_rpm_min);
      range.max_rpm = std::min(range.max_rpm, parameters_.auto_rpm_max);
      if (range.max_rpm >= range.min_rpm) {
        curves_.push_back(sample_width_curve(*predictor_, name, range, parameters_.solver.curve_rpm_step));
      } else {
        curves_.push_back(WidthCurve{std::string(name), {}, {}});  // no overlap: never reachable
      }
    }
  }
}

const WidthCurve* Ecu::curve_for(std::string_view material) const {
  for (const WidthCurve& c : curves_) {
    if (c.material == material) return &c;
  }
  return nullptr;
}

Rejection Ecu::reject(Fault fault) {
  faults_.record(fault, clock_.now());
  return fault;
}

Rejection Ecu::check_finite(double value) {
  if (!std::isfinite(value)) return Fault::kNotANumber;
  return std::nullopt;
}

Rejection Ecu::check_range(double value, double min, double max) {
  if (!std::isfinite(value)) return Fault::kNotANumber;
  if (value < min || value > max) return Fault::kSetpointOutOfRange;
  return std::nullopt;
}

Rejection Ecu::check_material(std::string_view material, Mode mode) const {
  if (material.size() > kMaxMaterialNameLength) return Fault::kUnknownMaterial;
  if (material.empty()) {
    // Manual mode may run without naming the material (no prediction then); automatic cannot.
    return mode == Mode::kAutomatic ? Rejection{Fault::kUnknownMaterial} : std::nullopt;
  }
  if (predictor_ != nullptr && !predictor_->has_material(material)) return Fault::kUnknownMaterial;
  return std::nullopt;
}

std::uint32_t Ecu::installed_mask() const { return (std::uint32_t{1} << section_count_) - 1u; }

Rejection Ecu::check_sequence(std::int64_t sequence) {
  if (!has_sequence_) return std::nullopt;
  // Distances in unsigned arithmetic: any two int64 values, no overflow.
  const auto last = static_cast<std::uint64_t>(last_sequence_);
  const auto seq = static_cast<std::uint64_t>(sequence);
  // A replayed or reordered old command must not roll the state back.
  if (sequence <= last_sequence_ && last - seq <= static_cast<std::uint64_t>(parameters_.sequence_reorder_window)) {
    return Fault::kStaleSequence;
  }
  const bool in_step = sequence > last_sequence_ && seq - last <= static_cast<std::uint64_t>(parameters_.sequence_max_jump);
  if (in_step) return std::nullopt;
  // Far ahead, or far behind (a restarted sender): believed only when the next command continues from it.
  if (jump_sequence_ && sequence > *jump_sequence_ &&
      seq - static_cast<std::uint64_t>(*jump_sequence_) == 1u) {
    return std::nullopt;
  }
  jump_sequence_ = sequence;
  return Fault::kSequenceJump;
}

Rejection Ecu::apply_command(const EcuCommand& c) {
  if (auto bad = check_sequence(c.sequence)) return reject(*bad);
  for (const double v : {c.rate_setpoint_kg_ha, c.width_setpoint_m, c.ground_speed_m_s, c.rpm_setpoint}) {
    if (auto bad = check_finite(v)) return reject(*bad);
  }
  if (c.mode != static_cast<std::int32_t>(Mode::kManual) && c.mode != static_cast<std::int32_t>(Mode::kAutomatic)) {
    return reject(Fault::kUnknownMode);
  }
  const auto mode = static_cast<Mode>(c.mode);
  if (auto bad = check_range(c.rate_setpoint_kg_ha, 0.0, parameters_.rate_max_kg_ha)) return reject(*bad);
  if (auto bad = check_range(c.width_setpoint_m, 0.0, parameters_.width_max_m)) return reject(*bad);
  if (auto bad = check_range(c.ground_speed_m_s, 0.0, parameters_.speed_max_m_s)) return reject(*bad);
  if (auto bad = check_range(c.rpm_setpoint, 0.0, parameters_.rpm_max)) return reject(*bad);
  // A command may use fewer sections than the machine has, never more.
  if (c.section_count < 1 || c.section_count > parameters_.section_count) return reject(Fault::kSetpointOutOfRange);
  if (mode == Mode::kAutomatic && predictor_ == nullptr) return reject(Fault::kAutomaticUnavailable);
  // Automatic mode solves for a width: zero width has no disc speed.
  if (mode == Mode::kAutomatic && !(c.width_setpoint_m > 0.0)) return reject(Fault::kSetpointOutOfRange);
  if (auto bad = check_material(c.material, mode)) return reject(*bad);
  if (c.border_mode < static_cast<std::int32_t>(BorderMode::kOff) ||
      c.border_mode > static_cast<std::int32_t>(BorderMode::kRightFieldEdge)) {
    return reject(Fault::kUnknownMode);
  }
  if (auto bad = check_range(c.border_gap_m, 0.0, 0.5 * parameters_.width_max_m)) return reject(*bad);
  if (c.border_mode != static_cast<std::int32_t>(BorderMode::kOff) && parameters_.disc_count < 2) {
    return reject(Fault::kSetpointOutOfRange);
  }
  for (const double v : {c.wind_x_m_s, c.wind_y_m_s}) {
    if (auto bad = check_range(v, -parameters_.wind_max_m_s, parameters_.wind_max_m_s)) return reject(*bad);
  }
  if (c.wind_compensation && (predictor_ == nullptr || planner_ == nullptr || parameters_.disc_count < 2)) {
    return reject(Fault::kAutomaticUnavailable);
  }

  const Nanoseconds now = clock_.now();
  const bool material_changed = c.material != material_;
  const bool width_changed = c.width_setpoint_m != width_setpoint_m_;
  if (mode == Mode::kAutomatic && (mode_ != Mode::kAutomatic || material_changed || width_changed)) {
    solve_pending_ = true;
    width_margin_m_ = parameters_.solver.width_margin_m;
  }
  if (material_changed || width_changed) prediction_pending_ = true;
  mode_ = mode;
  rate_setpoint_kg_ha_ = c.rate_setpoint_kg_ha;
  width_setpoint_m_ = c.width_setpoint_m;
  rpm_setpoint_manual_ = c.rpm_setpoint;
  material_.assign(c.material);
  border_mode_ = static_cast<BorderMode>(c.border_mode);
  border_gap_m_ = c.border_gap_m;
  wind_compensation_ = c.wind_compensation;
  wind_x_m_s_ = c.wind_x_m_s;
  wind_y_m_s_ = c.wind_y_m_s;
  section_count_ = c.section_count;
  section_mask_ = 0;
  for (int i = 0; i < c.section_count; ++i) {
    if (c.section_on[static_cast<std::size_t>(i)]) section_mask_ |= std::uint32_t{1} << i;
  }
  // The work state follows a change of this sender's request (or its first request), so a repeated
  // command cannot undo a task controller's switch-off.
  if (!lcm_work_state_ || *lcm_work_state_ != c.work_state) {
    work_state_setpoint_ = c.work_state;
    work_state_owner_ = WorkStateOwner::kLcm;
  }
  lcm_work_state_ = c.work_state;
  // The command's speed carries no direction (LCM clients send forward speed) and is as fresh as the command.
  ground_speed_m_s_ = c.ground_speed_m_s;
  direction_ = TravelDirection::kForward;
  speed_never_expires_ = parameters_.command_timeout == Nanoseconds::zero();
  speed_valid_until_ = now + parameters_.command_timeout;
  if (mode_ == Mode::kManual) {
    width_reachable_ = true;
    faults_.set_state(Fault::kWidthOutOfReach, false, now);
  }
  last_sequence_ = c.sequence;
  has_sequence_ = true;
  jump_sequence_.reset();
  last_command_time_ = now;
  return std::nullopt;
}

Rejection Ecu::set_rate_setpoint(double rate_kg_ha) {
  if (auto bad = check_range(rate_kg_ha, 0.0, parameters_.rate_max_kg_ha)) return reject(*bad);
  rate_setpoint_kg_ha_ = rate_kg_ha;
  return std::nullopt;
}

Rejection Ecu::set_width_setpoint(double width_m) {
  if (auto bad = check_range(width_m, 0.0, parameters_.width_max_m)) return reject(*bad);
  if (mode_ == Mode::kAutomatic && !(width_m > 0.0)) return reject(Fault::kSetpointOutOfRange);
  if (width_m != width_setpoint_m_) {
    prediction_pending_ = true;
    if (mode_ == Mode::kAutomatic) {
      solve_pending_ = true;
      width_margin_m_ = parameters_.solver.width_margin_m;
    }
  }
  width_setpoint_m_ = width_m;
  return std::nullopt;
}

Rejection Ecu::set_rpm_setpoint(double rpm) {
  if (auto bad = check_range(rpm, 0.0, parameters_.rpm_max)) return reject(*bad);
  // In automatic mode the ECU owns the disc speed: a manual set-point would be silently overridden.
  if (mode_ == Mode::kAutomatic) return reject(Fault::kCanNotSettable);
  rpm_setpoint_manual_ = rpm;
  return std::nullopt;
}

Rejection Ecu::set_work_state(bool on) {
  work_state_setpoint_ = on;
  work_state_owner_ = WorkStateOwner::kTaskController;
  tc_gone_ = false;
  return std::nullopt;
}

bool Ecu::needs_narrowing(std::uint32_t mask) const {
  if (parameters_.disc_count < 2) return false;
  const int n = section_count_;
  const int h = side_geometry(width_setpoint_m_ > 0.0 ? width_setpoint_m_ : 1.0, n).side_sections;
  // Section 1 is the leftmost: the left side's outermost section is 0, the right side's n − 1; a side is
  // narrowed when its outermost section is off while one nearer the centre is on (plan_sides).
  const auto side_bits = [&](int first, int count) { return ((1u << count) - 1u) << first; };
  const std::uint32_t left = side_bits(0, h);
  const std::uint32_t right = side_bits(n - h, h);
  const bool left_narrowed = (mask & left) != 0 && (mask & 1u) == 0;
  const bool right_narrowed = (mask & right) != 0 && (mask & (1u << (n - 1))) == 0;
  return left_narrowed || right_narrowed;
}

Rejection Ecu::set_section_mask(std::uint32_t mask) {
  if ((mask & ~installed_mask()) != 0) return reject(Fault::kSetpointOutOfRange);
  // A narrowed side is planned from the material's launch samples: with tables but no material the ECU
  // would keep spreading those sections and say so only in the actual state. Refused instead, so that the
  // controller learns it at once (PDACK, DM1) rather than after the first pass over the border.
  if (needs_planning_without_material() && needs_narrowing(mask)) return reject(Fault::kUnknownMaterial);
  // Without tables no side can be narrowed, only closed (all its sections off): a mask that narrows one
  // would be acknowledged and spread anyway. Refused, as wind compensation is without tables.
  if (predictor_ == nullptr && needs_narrowing(mask)) return reject(Fault::kAutomaticUnavailable);
  section_mask_ = mask;
  return std::nullopt;
}

std::vector<std::string> Ecu::material_names() const {
  std::vector<std::string> names;
  if (predictor_ == nullptr) return names;
  for (std::size_t i = 0; i < predictor_->material_count(); ++i) names.emplace_back(predictor_->material_name(i));
  return names;
}

Rejection Ecu::set_material(std::string_view material) {
  if (auto bad = check_material(material, mode_)) return reject(*bad);
  if (material != material_) {
    prediction_pending_ = true;
    if (mode_ == Mode::kAutomatic) {
      solve_pending_ = true;
      width_margin_m_ = parameters_.solver.width_margin_m;
    }
  }
  material_.assign(material);
  return std::nullopt;
}

Rejection Ecu::set_border(std::int32_t mode, double gap_m) {
  if (mode < static_cast<std::int32_t>(BorderMode::kOff) || mode > static_cast<std::int32_t>(BorderMode::kRightFieldEdge)) {
    return reject(Fault::kUnknownMode);
  }
  // The edge line lies inside the bout: the gap stays below half the widest bout the machine has.
  if (auto bad = check_range(gap_m, 0.0, 0.5 * parameters_.width_max_m)) return reject(*bad);
  if (mode != static_cast<std::int32_t>(BorderMode::kOff) && parameters_.disc_count < 2) {
    return reject(Fault::kSetpointOutOfRange);  // one disc: no side to set apart
  }
  // The border setting is searched on the material's launch samples: none known, nothing to search with.
  if (mode != static_cast<std::int32_t>(BorderMode::kOff) && needs_planning_without_material()) {
    return reject(Fault::kUnknownMaterial);
  }
  border_mode_ = static_cast<BorderMode>(mode);
  border_gap_m_ = gap_m;
  return std::nullopt;
}

Rejection Ecu::set_wind_compensation(bool on) {
  if (on && (predictor_ == nullptr || planner_ == nullptr || parameters_.disc_count < 2)) {
    return reject(Fault::kAutomaticUnavailable);  // nothing to compensate with
  }
  if (on && material_.empty()) return reject(Fault::kUnknownMaterial);  // whose flight to compensate
  wind_compensation_ = on;
  return std::nullopt;
}

Rejection Ecu::set_wind(double wind_x_m_s, double wind_y_m_s) {
  for (const double v : {wind_x_m_s, wind_y_m_s}) {
    if (auto bad = check_range(v, -parameters_.wind_max_m_s, parameters_.wind_max_m_s)) return reject(*bad);
  }
  wind_x_m_s_ = wind_x_m_s;
  wind_y_m_s_ = wind_y_m_s;
  return std::nullopt;
}

Rejection Ecu::set_ground_speed(double speed_m_s, TravelDirection direction, Nanoseconds valid_for) {
  if (auto bad = check_range(speed_m_s, 0.0, parameters_.speed_max_m_s)) return reject(*bad);
  ground_speed_m_s_ = speed_m_s;
  direction_ = direction;
  speed_never_expires_ = false;
  speed_valid_until_ = clock_.now() + valid_for;
  return std::nullopt;
}

void Ecu::set_ground_speed_unavailable() {
  speed_never_expires_ = false;
  speed_valid_until_.reset();
}

void Ecu::note_task_controller_alive() { last_task_controller_time_ = clock_.now(); }

// No time of life left, and the work state it switched on goes off now: its status may keep coming (a TC
// that refuses us is still on the bus), so waiting for the next step's supervision could be too late.
void Ecu::task_controller_gone() {
  last_task_controller_time_.reset();
  if (work_state_setpoint_ && work_state_owner_ == WorkStateOwner::kTaskController) {
    work_state_setpoint_ = false;
    work_state_owner_ = WorkStateOwner::kNone;
    // The fault stays until a task controller switches the work state again: a TC that is still alive
    // would clear it with its next status, before a DM1 had carried it.
    tc_gone_ = true;
    faults_.set_state(Fault::kTaskControllerLost, true, clock_.now());
  }
}

void Ecu::set_bus_address(bool has_address) {
  if (has_bus_address_ && !has_address) {
    work_state_setpoint_ = false;
    work_state_owner_ = WorkStateOwner::kNone;
  }
  has_bus_address_ = has_address;
  faults_.set_state(Fault::kNoBusAddress, !has_address, clock_.now());
}

void Ecu::record_fault(Fault fault) { faults_.record(fault, clock_.now()); }

void Ecu::solve_rpm_for_width() {
  solve_pending_ = false;
  const WidthCurve* curve = curve_for(material_);
  if (curve == nullptr || curve->rpm.empty()) {
    // The machine's speed range and the tables do not overlap for this material.
    width_reachable_ = false;
    faults_.set_state(Fault::kWidthOutOfReach, true, clock_.now());
    return;
  }
  // Aim past the set-point by the margin: a speed exactly at the edge of what reaches the width misses it
  // as soon as the disc settles a hair below the target.
  const RpmSolution solution = solver_.solve(*predictor_, *curve, width_setpoint_m_ + width_margin_m_);
  // A failed refinement still leaves a curve sample known to reach the width: use it, but say so.
  if (solution.prediction_failed) faults_.record(Fault::kPredictionFailed, clock_.now());
  rpm_target_ = solution.rpm;
  width_reachable_ = solution.reachable;
  faults_.set_state(Fault::kWidthOutOfReach, !solution.reachable, clock_.now());
  predicted_settled_ = false;  // judge the new speed once the disc has reached it
}

void Ecu::predict_pattern() {
  prediction_valid_ = false;
  if (predictor_ == nullptr || material_.empty()) return;
  const double rpm = field_rpm_actual();
  predicted_at_rpm_ = rpm;
  predicted_settled_ = std::abs(rpm - rpm_target_) < parameters_.reprediction_rpm_step;
  prediction_pending_ = false;
  const RpmRange range = predictor_->rpm_range(material_);
  // Outside the tables (e.g. while the disc spins up) there is simply no prediction: not a fault. A disc
  // settling on a target at the table's edge approaches it exponentially and may stay a hair outside it
  // for ever: within the re-prediction step of the edge it is predicted at the edge.
  const double slack = parameters_.reprediction_rpm_step;
  if (rpm < range.min_rpm - slack || rpm > range.max_rpm + slack) return;
  const double bout_width_m = width_setpoint_m_ > 0.0 ? width_setpoint_m_ : parameters_.width_max_m;
  const PredictionOutcome outcome =
      predictor_->predict(material_, std::clamp(rpm, range.min_rpm, range.max_rpm), bout_width_m, prediction_);
  if (outcome == PredictionOutcome::kOk) {
    prediction_valid_ = true;
  } else if (outcome == PredictionOutcome::kFailed) {
    faults_.record(Fault::kPredictionFailed, clock_.now());
  }
}

void Ecu::check_achieved_width() {
  // Automatic mode, disc settled: the pattern actually thrown at this speed is the answer that counts,
  // not the solver's curve. It misses when its effective width falls short of the set-point or its CV
  // at the set-point exceeds the target (the effective width is found on the tray grid; a set-point
  // between grid widths can miss the target although the grid width next above meets it). A miss asks
  // the solver for a wider margin; out of margin, the width is out of reach and the status says so.
  if (mode_ != Mode::kAutomatic || !prediction_valid_ || !predicted_settled_) return;
  const bool misses = prediction_.first_band_width_m < width_setpoint_m_ ||
                      prediction_.cv_percent > predictor_->cv_target_percent();
  if (!misses) return;
  const RpmSolverSettings& solver = parameters_.solver;
  if (width_margin_m_ + solver.width_margin_step_m <= solver.max_width_margin_m + 1e-9) {
    width_margin_m_ += solver.width_margin_step_m;
    solve_pending_ = true;
  } else {
    width_reachable_ = false;
    faults_.set_state(Fault::kWidthOutOfReach, true, clock_.now());
  }
}

// A disc that meters and is given a new speed for its side (the narrowed side moves to the other one, a
// narrowing ends, a border is engaged or left) needs a second or two to get there (disc_speed_model.hpp).
// Closing it meanwhile leaves the strip behind it unspread although every section it still serves is on.
// It goes on metering, at its new drop point and share of the flow, while its speed cannot throw past the
// edge its new setting keeps:
// - it is coming up to its new speed from below: it throws shorter than that setting, inside its edge;
// - it is slowing down to a setting without a border (a narrowing of its sections, or the field's after
//   a faster narrowing): what it still throws beyond that setting's edge lands on sections the task
//   controller switched off as spread already (section control, ISO 11783-10) or on the next bout, an
//   overlap for that second, never over a border.
// Slowing down to a border or field edge it stays closed until at speed: nothing may land beyond the edge
// line. A disc that was not metering (spin-up, work state just switched on) waits for its speed as before.
bool Ecu::keeps_metering_while_changing_speed(int disc) const {
  const auto i = static_cast<std::size_t>(disc);
  const double target = sides_[i].rpm_target;
  const double rpm = discs_[i].rpm();
  if (!side_changing_[i] || !disc_metering_[i] || !(target >= parameters_.spreading_rpm_min) ||
      !(rpm >= parameters_.spreading_rpm_min)) {
    return false;
  }
  if (rpm <= target) return true;
  return !sides_[i].border;
}

bool Ecu::disc_at_speed(int disc) const {
  const double target = sides_[static_cast<std::size_t>(disc)].rpm_target;
  if (!(target >= parameters_.spreading_rpm_min) || !(target > 0.0)) return false;
  return std::abs(discs_[static_cast<std::size_t>(disc)].rpm() - target) <= parameters_.disc_speed_tolerance * target;
}

// The speed of a disc at the field's setting (the status pattern is the field's), or the field's target
// while both discs run settings of their own.
double Ecu::field_rpm_actual() const {
  for (int d = 0; d < parameters_.disc_count; ++d) {
    const SideKind kind = sides_[static_cast<std::size_t>(d)].kind;
    if (kind == SideKind::kField || kind == SideKind::kPending) return discs_[static_cast<std::size_t>(d)].rpm();
  }
  return rpm_target_;
}

void Ecu::plan_sides() {
  const std::uint32_t mask = section_mask_ & installed_mask();
  for (SideState& side : sides_) side = SideState{SideKind::kField, rpm_target_, 0.0, 1.0, 0u};
  middle_bit_ = 0;
  pending_ = 0;
  wind_compensated_ = false;
  border_applied_ = false;
  if (parameters_.disc_count == 1) {
    // One disc throws the whole width: it cannot leave a side out, so every section spreads while any is on.
    sides_[kLeftDisc].sections = mask != 0 ? installed_mask() : 0u;
    sides_[kRightDisc] = SideState{SideKind::kOff, 0.0, 0.0, 0.0, 0u};
    return;
  }
  const SideGeometry g = side_geometry(width_setpoint_m_, section_count_);
  const int n = section_count_, h = g.side_sections;
  const bool odd = n % 2 == 1;
  const bool middle_on = odd && ((mask >> h) & 1u) != 0;
  // Section 1 is the leftmost as the driver sees it: the left side's j-th section from the centre is
  // h − 1 − j, the right side's n − h + j.
  const auto index = [&](int side, int j) { return side == kLeftDisc ? h - 1 - j : n - h + j; };
  SidePlanKey key;
  const std::size_t length = std::min(material_.size(), kMaxPlanMaterialLength);
  std::copy_n(material_.data(), length, key.material.begin());
  key.rpm = rpm_target_;
  key.bout_width_m = width_setpoint_m_;
  key.section_count = n;
  // Every plan is made in the measured wind, to a tenth of a metre per second (a reading that wanders
  // within it asks for nothing new).
  key.wind_x_m_s = std::round(wind_x_m_s_ * 10.0) / 10.0;
  key.wind_y_m_s = std::round(wind_y_m_s_ * 10.0) / 10.0;
  const bool can_plan = planner_ != nullptr && !material_.empty() && width_setpoint_m_ > 0.0 && rpm_target_ > 0.0;
  if (can_plan && (!prepared_ || !(*prepared_ == key))) {
    planner_->prepare(key);
    prepared_ = key;
  }

  // The field's setting of each disc: the speed set-point, or, with wind compensation, the discs set apart
  // for the wind. While a new wind's plan is searched the last one made for this field setting stays.
  std::array<SideState, 2> field{};
  for (SideState& f : field) f = SideState{SideKind::kField, rpm_target_, 0.0, 1.0, 0u};
  if (wind_compensation_ && can_plan) {
    SidePlanKey wind = key;
    wind.kind = PlanKind::kWind;
    wind.side = 0;
    const std::optional<SidePlan> plan = planner_->lookup(wind);
    if (!plan) pending_ |= kWindPending;
    SidePlanKey field_only = wind;  // the last wind plan still fits when only the wind moved
    if (plan && plan->known) {
      last_wind_plan_ = plan->wind_discs;
      last_wind_key_ = wind;
    }
    if (last_wind_key_) {
      SidePlanKey last_field = *last_wind_key_;
      last_field.wind_x_m_s = field_only.wind_x_m_s;
      last_field.wind_y_m_s = field_only.wind_y_m_s;
      if (last_field == field_only && (!plan || plan->known)) {
        for (std::size_t d = 0; d < 2; ++d) {
          field[d].rpm_target = last_wind_plan_[d].rpm;
          field[d].drop_point_turn_rad = last_wind_plan_[d].drop_point_turn_rad;
        }
        wind_compensated_ = true;
      }
    }
  }

  const int border_side = border_mode_ == BorderMode::kLeftBorder || border_mode_ == BorderMode::kLeftFieldEdge
                              ? kLeftDisc
                          : border_mode_ == BorderMode::kRightBorder || border_mode_ == BorderMode::kRightFieldEdge
                              ? kRightDisc
                              : -1;
  std::array<std::optional<SidePlan>, 2> plans;
  for (const int side : {kLeftDisc, kRightDisc}) {
    SideState& state = sides_[static_cast<std::size_t>(side)];
    state = field[static_cast<std::size_t>(side)];
    int outer = 0;  // the side's sections out to the outermost one on
    for (int j = 0; j < h; ++j) {
      if (((mask >> index(side, j)) & 1u) != 0) outer = j + 1;
    }
    const auto on_through = [&](int count) {
      for (int j = 0; j < count; ++j) state.sections |= std::uint32_t{1} << index(side, j);
    };
    if (outer == 0 && !middle_on) {
      state = SideState{SideKind::kOff, state.rpm_target, state.drop_point_turn_rad, 0.0, 0u};
      continue;
    }
    // The narrowest edge this side must keep: its last section on, or the border's line inside it.
    const double section_line_m = outer == h ? 0.5 * width_setpoint_m_ : g.edge_line_m(outer);
    const bool border_here = side == border_side && 0.5 * width_setpoint_m_ - border_gap_m_ < section_line_m + 1e-9;
    if (outer == h && !border_here) {  // out to the bout's edge; sections off inside it cannot be skipped
      on_through(h);
      continue;
    }
    key.side = side;
    if (border_here) {
      key.kind = border_mode_ == BorderMode::kLeftFieldEdge || border_mode_ == BorderMode::kRightFieldEdge
                     ? PlanKind::kFieldEdge
                     : PlanKind::kBorder;
      key.sections_on = 0;
      key.gap_m = border_gap_m_;
    } else {
      key.kind = PlanKind::kSections;
      key.sections_on = outer;
      key.gap_m = 0.0;
    }
    if (can_plan) plans[static_cast<std::size_t>(side)] = planner_->lookup(key);
    const std::optional<SidePlan>& plan = plans[static_cast<std::size_t>(side)];
    if (!can_plan || (plan && !plan->known)) {  // cannot be narrowed: the whole side keeps spreading
      on_through(h);
      continue;
    }
    if (!plan) {
      state.kind = SideKind::kPending;
      state.border = border_here;
      pending_ |= static_cast<std::uint8_t>(1u << side);
      on_through(h);
      continue;
    }
    state = SideState{SideKind::kNarrowed, plan->narrowing.rpm, plan->narrowing.drop_point_turn_rad,
                      plan->narrowing.flow_fraction, 0u, border_here};
    border_applied_ = border_applied_ || border_here;
    // Spread is what the narrowed pass puts there: each of the side's sections whose strip still gets the
    // section-on share of the field's rate, inside the edge line or beyond it (both discs' throw counted).
    for (int j = 0; j < h; ++j) {
      if (plan->section_rate_percent[static_cast<std::size_t>(j)] >= parameters_.section_on_rate_percent) {
        state.sections |= std::uint32_t{1} << index(side, j);
      }
    }
  }
  // The other disc's drop point on this pass, where the search turned it and that disc runs the field's
  // setting (a disc narrowed itself keeps its own).
  for (const int side : {kLeftDisc, kRightDisc}) {
    const std::optional<SidePlan>& plan = plans[static_cast<std::size_t>(side)];
    SideState& other = sides_[static_cast<std::size_t>(1 - side)];
    if (sides_[static_cast<std::size_t>(side)].kind == SideKind::kNarrowed && other.kind == SideKind::kField &&
        std::isfinite(plan->narrowing.other_drop_point_turn_rad)) {
      other.drop_point_turn_rad = plan->narrowing.other_drop_point_turn_rad;
    }
  }
  // The section on the centre line is spread by whichever disc throws.
  if (odd && mask != 0) middle_bit_ = std::uint32_t{1} << h;
}

void Ecu::supervise_controllers(Nanoseconds now) {
  // The controller that switched the work state on must stay alive; when it falls silent the work state
  // goes off and stays off until a controller switches it on again (a fresh request: the silent LCM
  // sender's next command counts as its first). The fault shows until that controller is heard again.
  const bool lcm_silent = parameters_.command_timeout > Nanoseconds::zero() && last_command_time_.has_value() &&
                          now - *last_command_time_ > parameters_.command_timeout;
  const bool tc_silent = !last_task_controller_time_.has_value() ||
                         now - *last_task_controller_time_ > parameters_.task_controller_timeout;
  if (work_state_setpoint_ && work_state_owner_ == WorkStateOwner::kLcm && lcm_silent) {
    work_state_setpoint_ = false;
    work_state_owner_ = WorkStateOwner::kNone;
    lcm_work_state_.reset();
    lcm_lost_ = true;
  }
  if (work_state_setpoint_ && work_state_owner_ == WorkStateOwner::kTaskController && tc_silent) {
    work_state_setpoint_ = false;
    work_state_owner_ = WorkStateOwner::kNone;
    tc_lost_ = true;
  }
  if (!lcm_silent) lcm_lost_ = false;
  if (!tc_silent) tc_lost_ = false;
  faults_.set_state(Fault::kCommandTimeout, lcm_lost_, now);
  faults_.set_state(Fault::kTaskControllerLost, tc_lost_ || tc_gone_, now);
}

// The gates follow what each disc should receive now, at their actuator's speed.
void Ecu::step_gates(double dt_s) {
  for (int d = 0; d < parameters_.disc_count; ++d) {
    const auto i = static_cast<std::size_t>(d);
    gates_[i].step(disc_metering_[i] ? sides_[i].flow_fraction : 0.0, dt_s);
  }
}

void Ecu::step(double dt_s) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) return;
  ++steps_;
  const Nanoseconds now = clock_.now();
  supervise_controllers(now);
  if (mode_ == Mode::kAutomatic && solve_pending_ && predictor_ != nullptr) solve_rpm_for_width();
  if (mode_ == Mode::kManual) rpm_target_ = rpm_setpoint_manual_;
  const std::array<SideState, 2> sides_before = sides_;
  plan_sides();
  // A new setting of a side: it narrows or widens, moves, or meets or leaves a border (an operator's new
  // disc speed for the field is not one: the discs wait for it as before).
  for (std::size_t i = 0; i < 2; ++i) {
    const SideState& was = sides_before[i];
    const SideState& now_side = sides_[i];
    const bool narrowed_both = was.kind == SideKind::kNarrowed && now_side.kind == SideKind::kNarrowed;
    if (was.kind != now_side.kind || was.border != now_side.border ||
        (narrowed_both && was.rpm_target != now_side.rpm_target)) {
      side_changing_[i] = true;
    }
  }
  for (int d = 0; d < parameters_.disc_count; ++d) {
    discs_[static_cast<std::size_t>(d)].step(sides_[static_cast<std::size_t>(d)].rpm_target, dt_s);
  }

  const bool speed_valid = speed_never_expires_ || (speed_valid_until_.has_value() && now <= *speed_valid_until_);
  const bool reverse = speed_valid && direction_ == TravelDirection::kReverse;
  speed_in_use_m_s_ = speed_valid ? ground_speed_m_s_ : 0.0;
  const std::uint32_t active = section_mask_ & installed_mask();
  // What the operator asks for: the master switch, an open section of non-zero width and a rate.
  const bool requested =
      work_state_setpoint_ && active != 0 && width_setpoint_m_ > 0.0 && rate_setpoint_kg_ha_ > 0.0;
  // Each disc meters its half of the bout's flow times its own share (a one-disc machine: all of it), and
  // only while it runs at its own target: one disc changing speed for a narrowed side does not stop the
  // other one spreading — nor a disc that was metering and changes speed for a new setting of its side,
  // while that is safe (keeps_metering_while_changing_speed).
  bool any_at_speed = false;
  double flow_share = 0.0;
  std::array<bool, 2> changing{};
  for (int d = 0; d < parameters_.disc_count; ++d) {
    const auto i = static_cast<std::size_t>(d);
    if (disc_at_speed(d)) side_changing_[i] = false;
    changing[i] = !disc_at_speed(d) && keeps_metering_while_changing_speed(d);
    if (!changing[i]) side_changing_[i] = false;
  }
  for (int d = 0; d < parameters_.disc_count; ++d) {
    const auto i = static_cast<std::size_t>(d);
    disc_metering_[i] = false;
    if (!(sides_[i].flow_fraction > 0.0) || !(disc_at_speed(d) || changing[i])) continue;
    any_at_speed = disc_metering_[i] = true;
    flow_share += sides_[i].flow_fraction;
  }
  flow_share /= parameters_.disc_count;
  const bool moving_forward = speed_valid && !reverse && speed_in_use_m_s_ > 0.0;
  metering_open_ = requested && moving_forward && any_at_speed && has_bus_address_;
  if (!metering_open_) disc_metering_ = {false, false};
  section_actual_mask_ = middle_bit_ != 0 && metering_open_ ? middle_bit_ : 0u;
  for (int d = 0; d < parameters_.disc_count; ++d) {
    const auto i = static_cast<std::size_t>(d);
    // A side whose disc the search turned off is spread by the other disc's throw alone (its rates say
    // how far): it counts while that disc meters.
    const bool thrown_by_other = sides_[i].kind == SideKind::kNarrowed && !(sides_[i].flow_fraction > 0.0) &&
                                 parameters_.disc_count == 2 && disc_metering_[1 - i];
    if (disc_metering_[i] || thrown_by_other) section_actual_mask_ |= sides_[i].sections;
  }
  step_gates(dt_s);
  mass_flow_kg_s_ =
      metering_open_ ? mass_flow_kg_s(rate_setpoint_kg_ha_, width_setpoint_m_ * flow_share, speed_in_use_m_s_) : 0.0;
  faults_.set_state(Fault::kSpeedUnavailable, work_state_setpoint_ && !speed_valid, now);
  faults_.set_state(Fault::kDrivingReverse, work_state_setpoint_ && reverse, now);
  // A disc that should throw fertiliser and is not at its speed: its flow stays closed.
  bool every_flowing_disc_at_speed = true;
  for (int d = 0; d < parameters_.disc_count; ++d) {
    const auto i = static_cast<std::size_t>(d);
    if (sides_[i].flow_fraction > 0.0 && !disc_at_speed(d) && !changing[i]) every_flowing_disc_at_speed = false;
  }
  faults_.set_state(Fault::kDiscNotAtSpeed, requested && moving_forward && !every_flowing_disc_at_speed, now);

  const bool settled_now = std::abs(field_rpm_actual() - rpm_target_) < parameters_.reprediction_rpm_step;
  if (prediction_pending_ || std::abs(field_rpm_actual() - predicted_at_rpm_) >= parameters_.reprediction_rpm_step ||
      (settled_now && !predicted_settled_)) {
    predict_pattern();
    check_achieved_width();
  }
}

EcuStatus Ecu::status() const {
  EcuStatus s;
  s.time = clock_.now();
  s.steps = steps_;
  s.mode = mode_;
  s.rpm_actual = field_rpm_actual();
  s.rpm_target = mode_ == Mode::kManual ? rpm_setpoint_manual_ : rpm_target_;
  s.rate_setpoint_kg_ha = rate_setpoint_kg_ha_;
  s.rate_actual_kg_ha = metering_open_ ? rate_setpoint_kg_ha_ : 0.0;
  s.width_setpoint_m = width_setpoint_m_;
  s.width_actual_m = metering_open_ ? width_setpoint_m_ * std::popcount(section_actual_mask_) /
                                           static_cast<double>(section_count_)
                                     : 0.0;
  s.ground_speed_m_s = speed_in_use_m_s_;
  s.mass_flow_kg_s = mass_flow_kg_s_;
  s.throw_width_m = prediction_valid_ ? prediction_.throw_width_m : kNaN;
  s.effective_width_m = prediction_valid_ ? prediction_.effective_width_m : kNaN;
  s.cv_percent = prediction_valid_ ? prediction_.cv_percent : kNaN;
  s.throw_width_se_m = prediction_valid_ ? prediction_.throw_width_se_m : kNaN;
  s.effective_width_se_m = prediction_valid_ ? prediction_.effective_width_se_m : kNaN;
  s.cv_se_percent = prediction_valid_ ? prediction_.cv_se_percent : kNaN;
  s.width_reachable = width_reachable_;
  s.work_state_setpoint = work_state_setpoint_;
  s.work_state_actual = metering_open_;
  s.section_count = section_count_;
  s.section_mask = static_cast<std::uint16_t>(section_mask_);
  s.section_actual_mask = static_cast<std::uint16_t>(section_actual_mask_);
  for (int d = 0; d < parameters_.disc_count; ++d) {
    const auto i = static_cast<std::size_t>(d);
    s.disc_rpm_actual[i] = discs_[i].rpm();
    s.disc_rpm_target[i] = sides_[i].rpm_target;
    s.disc_drop_point_turn_rad[i] = sides_[i].drop_point_turn_rad;
    s.disc_flow_fraction[i] = disc_metering_[i] ? sides_[i].flow_fraction : 0.0;
    s.disc_flow_delivered[i] = gates_[i].opening();
  }
  s.sides_pending = pending_;
  s.border_mode = border_mode_;
  s.border_gap_m = border_gap_m_;
  s.border_applied = border_applied_;
  s.wind_compensation = wind_compensation_;
  s.wind_compensated = wind_compensated_;
  s.wind_x_m_s = wind_x_m_s_;
  s.wind_y_m_s = wind_y_m_s_;
  s.material = material_;
  s.last_command_sequence = has_sequence_ ? last_sequence_ : -1;
  s.fault_codes = faults_.active_mask(s.time);
  for (std::size_t i = 0; i < kFaultCount; ++i) s.fault_counts[i] = faults_.count(static_cast<Fault>(i));
  return s;
}

}  // namespace spread::firmware
