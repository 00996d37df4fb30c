// The field run with the ECU in the loop (machine_in_loop.hpp): named stages over one run's state.
#include "libspread/analysis/field/machine_in_loop.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <optional>
#include <string>

#include "libspread/analysis/field/coverage_map.hpp"
#include "libspread/analysis/field/disc_stamps.hpp"
#include "libspread/analysis/field/field_summary.hpp"
#include "libspread/analysis/field/field_wind.hpp"
#include "libspread/control/ecu.hpp"
#include "libspread/control/section_planner.hpp"
#include "libspread/core/clock.hpp"
#include "libspread/core/error.hpp"

namespace spread::field {
namespace {

namespace fw = spread::firmware;

[[noreturn]] void refuse(const std::string& what) {
  throw Error(ErrorKind::kArgument, "field machine", "field machine: " + what);
}

bool positive(double v) { return v > 0.0 && std::isfinite(v); }

void check(const MachineSettings& s) {
  if (!positive(s.target_rate_kg_ha)) refuse("target_rate_kg_ha must be > 0");
  if (!positive(s.bout_width_m)) refuse("bout_width_m must be > 0");
  if (!positive(s.rpm)) refuse("the field's disc speed (rpm) must be > 0");
  if (!positive(s.cell_m)) refuse("cell_m must be > 0");
  if (!positive(s.speed_m_s)) refuse("speed_m_s must be > 0");
  if (!positive(s.loop_period_s) || s.loop_period_s > 1.0) refuse("loop_period_s must lie in (0, 1] s");
  if (s.section_count < 1 || s.section_count > fw::kMaxSections) {
    refuse("section_count must be 1.." + std::to_string(fw::kMaxSections) + ", got " + std::to_string(s.section_count));
  }
  for (const double v : {s.look_ahead_on_s, s.look_ahead_off_s, s.gate_full_travel_s, s.turn_s, s.border_gap_m}) {
    if (!(v >= 0.0) || !std::isfinite(v)) refuse("look-ahead, gate travel, turn time and border gap must be >= 0");
  }
  if (!positive(s.disc_time_constant_s)) refuse("disc_time_constant_s must be > 0");
  if (!positive(s.rpm_step_rpm)) refuse("rpm_step_rpm must be > 0");
  if (!std::isfinite(s.wind_east_m_s) || !std::isfinite(s.wind_north_m_s)) refuse("the wind must be finite");
}

// With section control a tramline is driven on to the innermost headland round's track, where the tractor
// turns, half a bout beyond the headland's line at each end: the sections switch off over the worked headland.
std::vector<Pass> driven_passes(std::vector<Pass> passes, const MachineSettings& s) {
  const bool headland = std::any_of(passes.begin(), passes.end(), [](const Pass& p) { return p.kind == PassKind::kHeadland; });
  if (!s.section_control || !headland) return passes;
  for (Pass& pass : passes) {
    if (pass.kind != PassKind::kTramline || pass.path.size() < 2) continue;
    const auto draw_on = [&](Point end, Point before) {
      const Point d = end - before;
      return length(d) > 0.0 ? end + (0.5 * s.bout_width_m / length(d)) * d : end;
    };
    const std::size_t n = pass.path.size();
    const Point first = draw_on(pass.path[0], pass.path[1]), last = draw_on(pass.path[n - 1], pass.path[n - 2]);
    pass.path.front() = first;
    pass.path.back() = last;
  }
  return passes;
}

fw::EcuParameters ecu_parameters(const MachineSettings& s, int disc_count) {
  fw::EcuParameters p;
  p.disc_time_constant_s = s.disc_time_constant_s;
  p.gate_full_travel_s = s.gate_full_travel_s;
  p.section_count = s.section_count;
  p.disc_count = disc_count;
  p.rpm_max = std::max(p.rpm_max, s.rpm);
  p.width_max_m = std::max(p.width_max_m, s.bout_width_m);
  // Manual mode: automatic mode's width curve is not used, sampled coarsely.
  p.solver.curve_rpm_step = 50.0;
  return p;
}

// A piece of the machine's movement in one loop period: along one straight piece of its pass.
struct Move {
  Point from, to, forward;
  double length_m = 0.0;
};

// Where the machine is along a pass's path, and its moves.
class PathWalker {
 public:
  explicit PathWalker(const std::vector<Point>& path) : path_(path) { skip_empty(); }
  bool done() const { return segment_ + 1 >= path_.size(); }
  Point position() const { return at(offset_m_); }
  Point forward() const {
    const Point d = path_[segment_ + 1] - path_[segment_];
    return (1.0 / length(d)) * d;
  }
  // Moves on by up to distance_m, appending its straight pieces.
  void advance(double distance_m, std::vector<Move>& moves) {
    while (distance_m > 0.0 && !done()) {
      const double segment_m = length(path_[segment_ + 1] - path_[segment_]);
      const double step_m = std::min(distance_m, segment_m - offset_m_);
      moves.push_back({at(offset_m_), at(offset_m_ + step_m), forward(), step_m});
      offset_m_ += step_m;
      distance_m -= step_m;
      if (offset_m_ >= segment_m) {
        ++segment_;
        offset_m_ = 0.0;
        skip_empty();
      }
    }
  }

 private:
  Point at(double offset_m) const { return path_[segment_] + offset_m * forward(); }
  void skip_empty() {
    while (!done() && !(length(path_[segment_ + 1] - path_[segment_]) > 0.0)) ++segment_;
  }
  const std::vector<Point>& path_;
  std::size_t segment_ = 0;
  double offset_m_ = 0.0;
};

// What one disc delivered since its last stamp, at one state and heading.
struct PendingStamp {
  const StampPattern* stamp = nullptr;
  double mass_kg = 0.0;
  double length_m = 0.0;
  Point first, last, forward;
};

class FieldMachine {
 public:
  FieldMachine(const Boundary& boundary, std::vector<Pass> passes, fw::SpreadPredictor& ecu_predictor,
               predict::Predictor& predictor, const predict::PredictionRequest& field, const MachineSettings& s)
      : s_(s),
        field_(field),
        disc_count_(predictor.machine().disc_count >= 2 ? 2 : 1),
        stamps_(predictor, field, s.cell_m, s.rpm_step_rpm),
        planner_(ecu_predictor, fw::EcuParameters{}.section_max_beyond_percent, fw::SectionPlanner::Threading::kInline),
        ecu_(clock_, ecu_parameters(s, disc_count_), &ecu_predictor, &planner_) {
    out_.passes = driven_passes(std::move(passes), s);
    fit_to_field(boundary);
  }

  MachineRun run() {
    spin_up();
    for (std::size_t i = 0; i < out_.passes.size(); ++i) {
      if (i > 0) turn(out_.passes[i]);
      drive(static_cast<int>(i));
      run_out(out_.passes[i]);
    }
    for (PendingStamp& p : pending_) flush(p);
    out_.loop_steps = steps_;
    out_.stamps_built = stamps_.size();
    out_.planner_searches = planner_.searches();
    out_.applied.steps = stamped_;
    if (s_.progress) s_.progress(total_steps_, total_steps_);
    return std::move(out_);
  }

 private:
  // The grid, the field's cells, the worked-ground record, the sections' bands and their ground's offset.
  void fit_to_field(const Boundary& boundary) {
    const StampPattern& left = stamps_.at({predict::kLeftDisc, s_.rpm, 0.0, 0.0, 0.0});
    double reach_m = pattern_reach_m(left), mass = 0.0, moment = 0.0;
    for (int d = 0; d < disc_count_; ++d) {
      const StampPattern& p = stamps_.at({d, s_.rpm, 0.0, 0.0, 0.0});
      reach_m = std::max(reach_m, pattern_reach_m(p));
      for (std::size_t k = 0; k < p.size(); ++k) {
        mass += p.fraction[k];
        moment += p.fraction[k] * p.y_m[k];
      }
    }
    // A wind or a narrowed disc throws elsewhere: a quarter more room, and what still falls off the grid is
    // counted beyond the boundary (rate_grid.hpp).
    out_.applied.grid = grid_for(boundary, out_.passes, 1.25 * reach_m, s_.cell_m);
    inside_ = inside_mask(out_.applied.grid, boundary.ring);
    coverage_.emplace(out_.applied.grid, s_.bout_width_m);
    ground_offset_m_ = mass > 0.0 ? moment / mass : 0.0;
    const double w = s_.bout_width_m / s_.section_count;
    for (int i = 0; i < s_.section_count; ++i) section_x_m_[static_cast<std::size_t>(i)] = -0.5 * s_.bout_width_m + (i + 0.5) * w;
    for (const Pass& pass : out_.passes) total_steps_ += static_cast<std::size_t>(path_length_m(pass.path) / (s_.speed_m_s * s_.loop_period_s)) + 1;
  }

  bool inside(Point at) const {
    const RateGrid& g = out_.applied.grid;
    const double gx = std::floor((at.x_m - g.x0_m) / g.cell_m), gy = std::floor((at.y_m - g.y0_m) / g.cell_m);
    if (!(gx >= 0.0 && gy >= 0.0 && gx < g.nx && gy < g.ny)) return false;
    return inside_[static_cast<std::size_t>(gy) * static_cast<std::size_t>(g.nx) + static_cast<std::size_t>(gx)] != 0;
  }

  // The task controller's sections: on where the ground ahead of each section's strip is in the field and
  // not worked (look-ahead: the turn-on time for a section off, the turn-off time for one on).
  std::uint32_t sections_for(Point at, Point forward, int pass, double along_m) const {
    const std::uint32_t all = (std::uint32_t{1} << s_.section_count) - 1u;
    if (!s_.section_control) return all;
    const Point right{forward.y_m, -forward.x_m};
    std::uint32_t mask = 0;
    for (int i = 0; i < s_.section_count; ++i) {
      const bool was_on = ((commanded_ >> i) & 1u) != 0;
      const double ahead_m = ground_offset_m_ + s_.speed_m_s * (was_on ? s_.look_ahead_off_s : s_.look_ahead_on_s);
      const Point ground = at + ahead_m * forward + section_x_m_[static_cast<std::size_t>(i)] * right;
      if (inside(ground) && !coverage_->worked(ground, pass, along_m)) mask |= std::uint32_t{1} << i;
    }
    return mask;
  }

  // One loop period: the command, the ECU's step, the clock.
  fw::EcuStatus tick(bool work_state, std::uint32_t sections, bool border, Point forward, double speed_m_s) {
    fw::EcuCommand c;
    c.sequence = ++sequence_;
    c.mode = static_cast<std::int32_t>(fw::Mode::kManual);
    c.rate_setpoint_kg_ha = s_.target_rate_kg_ha;
    c.width_setpoint_m = s_.bout_width_m;
    c.ground_speed_m_s = speed_m_s;
    c.rpm_setpoint = s_.rpm;
    c.work_state = work_state;
    c.material = field_.material;
    c.section_count = s_.section_count;
    for (int i = 0; i < s_.section_count; ++i) c.section_on[static_cast<std::size_t>(i)] = ((sections >> i) & 1u) != 0;
    c.border_mode = static_cast<std::int32_t>(border ? fw::BorderMode::kRightBorder : fw::BorderMode::kOff);
    c.border_gap_m = s_.border_gap_m;
    wind_ = wind_in_machine_frame(forward, s_.wind_east_m_s, s_.wind_north_m_s);
    c.wind_compensation = s_.wind_compensation && (s_.wind_east_m_s != 0.0 || s_.wind_north_m_s != 0.0) && disc_count_ == 2;
    c.wind_x_m_s = wind_.x_m;
    c.wind_y_m_s = wind_.y_m;
    if (const fw::Rejection bad = ecu_.apply_command(c)) {
      refuse(std::string("the ECU rejects the command: ") + std::string(fw::fault_name(*bad)));
    }
    if (work_state && sections != commanded_) out_.section_switches += static_cast<std::size_t>(std::popcount(sections ^ commanded_));
    if (work_state) commanded_ = sections;
    ecu_.step(s_.loop_period_s);
    clock_.advance(from_seconds(s_.loop_period_s));
    ++steps_;
    if (s_.progress && steps_ % kProgressSteps == 0) s_.progress(std::min(steps_, total_steps_), total_steps_);
    const fw::EcuStatus status = ecu_.status();
    out_.border_applied = out_.border_applied || status.border_applied;
    return status;
  }

  // Each disc's gate delivery over the machine's moves of this period, and the sections' worked strips.
  void deliver(const fw::EcuStatus& status, const std::vector<Move>& moves, int pass, double along_m) {
    const double kg_per_m = s_.target_rate_kg_ha / 1e4 * s_.bout_width_m / disc_count_;
    for (int d = 0; d < disc_count_; ++d) {
      const auto i = static_cast<std::size_t>(d);
      const double delivered = status.disc_flow_delivered[i];
      if (!(delivered > 0.0)) continue;
      const StampPattern& stamp = stamps_.at({d, status.disc_rpm_actual[i], status.disc_drop_point_turn_rad[i], wind_.x_m, wind_.y_m});
      for (const Move& m : moves) add(pending_[i], stamp, kg_per_m * delivered * m.length_m, m);
    }
    if (status.section_actual_mask == 0 || moves.empty()) return;
    const Point at = moves.back().to, forward = moves.back().forward, right{forward.y_m, -forward.x_m};
    const double w = s_.bout_width_m / s_.section_count;
    for (int k = 0; k < s_.section_count; ++k) {
      if (((status.section_actual_mask >> k) & 1u) == 0) continue;
      const Point centre = at + ground_offset_m_ * forward + section_x_m_[static_cast<std::size_t>(k)] * right;
      coverage_->mark(centre + (-0.5 * w) * right, centre + (0.5 * w) * right, pass, along_m);
    }
  }

  void add(PendingStamp& p, const StampPattern& stamp, double mass_kg, const Move& m) {
    const bool same = p.stamp == &stamp && p.forward.x_m == m.forward.x_m && p.forward.y_m == m.forward.y_m;
    if (p.stamp != nullptr && (!same || p.length_m + m.length_m > s_.cell_m)) flush(p);
    if (p.stamp == nullptr) p = PendingStamp{&stamp, 0.0, 0.0, m.from, m.to, m.forward};
    p.mass_kg += mass_kg;
    p.length_m += m.length_m;
    p.last = m.to;
  }

  // The stamp of what a disc delivered, at the middle of the ground it moved over meanwhile.
  void flush(PendingStamp& p) {
    if (p.stamp == nullptr) return;
    const Point mid = 0.5 * (p.first + p.last);
    stamp(out_.applied.grid, *p.stamp, {mid.x_m, mid.y_m, p.forward.x_m, p.forward.y_m, p.mass_kg});
    out_.applied.metered_kg += p.mass_kg;
    out_.applied.not_landed_kg += p.mass_kg * std::max(0.0, 1.0 - p.stamp->landed_fraction);
    ++stamped_;
    p = PendingStamp{};
  }

  // The discs brought to the field's speed before the first pass, feed shut.
  void spin_up() {
    const Point forward = out_.passes.empty() || out_.passes[0].path.size() < 2 ? Point{0.0, 1.0} : PathWalker(out_.passes[0].path).forward();
    const bool border = s_.border && !out_.passes.empty() && out_.passes[0].outermost;
    for (double t = 0.0; t < 6.0 * s_.disc_time_constant_s + 1.0; t += s_.loop_period_s) tick(false, all_sections(), border, forward, 0.0);
  }

  // A headland turn: the feed shut, the next pass's border mode set meanwhile (the discs change speed on
  // the turn).
  void turn(const Pass& next) {
    const Point forward = next.path.size() < 2 ? Point{0.0, 1.0} : PathWalker(next.path).forward();
    const bool border = s_.border && next.outermost;
    for (double t = 0.0; t < s_.turn_s; t += s_.loop_period_s) tick(false, all_sections(), border, forward, s_.speed_m_s);
    commanded_ = all_sections();
  }

  void drive(int index) {
    const Pass& pass = out_.passes[static_cast<std::size_t>(index)];
    const bool border = s_.border && pass.outermost;
    PathWalker walker(pass.path);
    std::vector<Move> moves;
    double along_m = 0.0;
    commanded_ = all_sections();
    while (!walker.done()) {
      const std::uint32_t sections = sections_for(walker.position(), walker.forward(), index, along_m);
      const fw::EcuStatus status = tick(true, sections, border, walker.forward(), s_.speed_m_s);
      moves.clear();
      walker.advance(s_.speed_m_s * s_.loop_period_s, moves);
      for (const Move& m : moves) along_m += m.length_m;
      deliver(status, moves, index, along_m);
      out_.applied.spread_length_m += status.work_state_actual ? s_.speed_m_s * s_.loop_period_s : 0.0;
    }
  }

  // After the pass the feed is shut; gates still closing deliver on a straight run-out.
  void run_out(const Pass& pass) {
    if (pass.path.size() < 2) return;
    const std::size_t n = pass.path.size();
    const Point d = pass.path[n - 1] - pass.path[n - 2];
    if (!(length(d) > 0.0)) return;
    const Point forward = (1.0 / length(d)) * d;
    Point at = pass.path[n - 1];
    const bool border = s_.border && pass.outermost;
    for (int k = 0; k < 1000; ++k) {
      const fw::EcuStatus status = tick(false, all_sections(), border, forward, s_.speed_m_s);
      if (!(status.disc_flow_delivered[0] > 0.0) && !(status.disc_flow_delivered[1] > 0.0)) break;
      const double step_m = s_.speed_m_s * s_.loop_period_s;
      const Move m{at, at + step_m * forward, forward, step_m};
      at = m.to;
      deliver(status, {m}, -1, 0.0);
    }
  }

  std::uint32_t all_sections() const { return (std::uint32_t{1} << s_.section_count) - 1u; }

  MachineSettings s_;
  predict::PredictionRequest field_;
  int disc_count_;
  DiscStamps stamps_;
  ManualClock clock_;
  fw::SectionPlanner planner_;
  fw::Ecu ecu_;
  MachineRun out_;
  std::vector<std::uint8_t> inside_;
  std::optional<CoverageMap> coverage_;
  std::array<double, fw::kMaxSections> section_x_m_{};
  double ground_offset_m_ = 0.0;
  std::array<PendingStamp, 2> pending_{};
  Point wind_{0.0, 0.0};
  std::uint32_t commanded_ = 0;
  std::int64_t sequence_ = 0;
  std::size_t steps_ = 0, total_steps_ = 0, stamped_ = 0;
};

}  // namespace

MachineRun run_machine(const Boundary& boundary, std::vector<Pass> passes, firmware::SpreadPredictor& ecu_predictor,
                       predict::Predictor& predictor, const predict::PredictionRequest& field,
                       const MachineSettings& settings) {
  check(settings);
  if (!ecu_predictor.has_material(field.material)) refuse("the ECU's tables have no material '" + std::string(field.material) + "'");
  FieldMachine machine(boundary, std::move(passes), ecu_predictor, predictor, field, settings);
  return machine.run();
}

}  // namespace spread::field
