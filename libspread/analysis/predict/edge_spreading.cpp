#include "libspread/analysis/predict/edge_spreading.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <utility>

namespace spread::predict {

const char* to_string(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::kBorder: return "border";
    case EdgeKind::kEdge: return "edge";
  }
  return "?";
}

namespace {

// Mass of a landing (kernel of half-width h) beyond the line at `line_m`; a granule that did not land
// (x not finite) is nowhere.
double beyond(double x, double weight, double line_m, double h) {
  if (!std::isfinite(x)) return 0.0;
  if (h == 0.0) return x >= line_m ? weight : 0.0;
  return weight * (1.0 - metrics::epanechnikov_cdf((line_m - x) / h));
}

// What does not change with this pass's settings: the layout, the passes before this one at the normal
// setting, and the judged span.
struct Frame {
  explicit Frame(std::pmr::memory_resource* memory) : fixed(memory), interior(memory) {}
  metrics::TrayLayout trays;
  double bout_width_m = 0.0, line_m = 0.0, kernel_m = 0.0;
  double target_per_tray = 0.0;   // the field's rate inside, as mass per tray
  std::pmr::vector<double> fixed;     // per tray
  double fixed_beyond = 0.0;      // mass beyond the line
  int first_judged = 0, end_inside = 0;  // trays of the judged span up to the one holding the line
  int judged_bouts = 1;           // the last bout and the bouts before it that the last pass can reach
  double judged_from_m = 0.0;     // −(judged_bouts − 1/2) W
  double over_limit = 0.0;        // 1 + tolerance: above it and the interior's rate a tray is over-applied
  double under_limit = 0.0;       // 1 − tolerance: below it and the interior's rate under-applied
  std::pmr::vector<double> interior;  // per tray, the rate the field's interior gets there (all passes)
};

// Disc `disc`'s landings of `p`, x turned so that the edge (on side `edge_side`) lies towards +x.
template <typename Visit>
void disc_landings(const Prediction& p, int disc, int edge_side, Visit visit) {
  const double orient = edge_side == kRightDisc ? 1.0 : -1.0;
  const std::size_t first = disc == kRightDisc ? p.left_landing_count : 0;
  const std::size_t end = disc == kRightDisc ? p.landing_x_m.size() : p.left_landing_count;
  for (std::size_t i = first; i < end; ++i) visit(orient * p.landing_x_m[i], p.landing_mass_fraction[i]);
}

// The bout of x: 0 for the last bout (x >= −W/2), k for [−(k + 1/2) W, −(k − 1/2) W).
int bout_of(double x_m, double bout_width_m) {
  return x_m >= -0.5 * bout_width_m ? 0 : static_cast<int>(std::ceil((-x_m - 0.5 * bout_width_m) / bout_width_m - 1e-12));
}

// The passes before the last one, to and fro: pass k lies k bouts in from it and every odd pass is driven the
// other way. In still air an odd pass is the normal pattern mirrored; in wind it meets the wind from the
// other side (docs/metrics.md "To-and-fro in wind"): where the return pass lands as the outgoing one does
// (ReturnPass::kRacetrack) it is the normal pattern itself, otherwise the return pass's own landings
// (`back`, in its machine frame) mirrored.
struct PassLandings {
  std::span<const double> x_m, mass_fraction;
  double mirror = 1.0;  // −1: the pass is driven the other way, its machine frame mirrored onto the field
};
PassLandings pass_landings(const Prediction& normal, std::span<const double> back_x_m,
                           std::span<const double> back_mass_fraction, int k) {
  if (k % 2 == 0) return {normal.landing_x_m, normal.landing_mass_fraction, 1.0};
  if (normal.return_pass == ReturnPass::kRacetrack) return {normal.landing_x_m, normal.landing_mass_fraction, 1.0};
  if (normal.return_pass == ReturnPass::kFlown) return {back_x_m, back_mass_fraction, -1.0};
  return {normal.landing_x_m, normal.landing_mass_fraction, -1.0};
}

// `reach_scale`: how much further than the normal setting a setting searched can throw (the fastest speed
// searched over the field's: launch speed is ωR). `back_*`: the return pass's landings where it was flown.
void make_frame(const Prediction& normal, std::span<const double> back_x_m, std::span<const double> back_mass_fraction,
                const EdgeRequest& edge, double bout_width_m, double tray_width_m, double reach_scale,
                std::pmr::memory_resource* memory, Frame& f) {
  f.bout_width_m = bout_width_m;
  f.line_m = 0.5 * bout_width_m - edge.gap_m;
  f.kernel_m = normal.kernel_half_width_m;
  const double orient = edge.side == kRightDisc ? 1.0 : -1.0;
  double reach_m = 0.0, landed = 0.0;
  for (std::size_t i = 0; i < normal.landing_x_m.size(); ++i) {
    if (!std::isfinite(normal.landing_x_m[i])) continue;
    reach_m = std::max(reach_m, std::abs(normal.landing_x_m[i]));
    landed += normal.landing_mass_fraction[i];
  }
  reach_m += f.kernel_m;
  const double search_reach_m = reach_scale * reach_m;
  // Every bout the last pass can reach, and the trays to hold them with the passes that reach them.
  f.judged_bouts = 1 + std::max(1, static_cast<int>(std::ceil((search_reach_m - 0.5 * bout_width_m) / bout_width_m)));
  f.judged_from_m = -(f.judged_bouts - 0.5) * bout_width_m;
  f.trays = metrics::tray_layout_covering(std::max(bout_width_m + search_reach_m, -f.judged_from_m + reach_m), tray_width_m);
  // An even count puts tray edges on the multiples of the tray width: on the bouts' ends and the edge line
  // wherever those lie on them (W/2 and the gap in whole trays), so no tray straddles them.
  if (f.trays.tray_count % 2 != 0) ++f.trays.tray_count;
  f.target_per_tray = landed * tray_width_m / bout_width_m;
  f.fixed.assign(static_cast<std::size_t>(f.trays.tray_count), 0.0);
  const double half_extent_m = -f.trays.left_edge_m();
  // The passes before: pass k at −kW, to and fro (pass_landings), while it still reaches the layout.
  const int passes = static_cast<int>(std::ceil((half_extent_m + reach_m) / bout_width_m)) + 1;
  std::pmr::vector<double> x(std::max(normal.landing_x_m.size(), back_x_m.size()), 0.0, memory);
  const auto place = [&](int k) {
    const PassLandings pass = pass_landings(normal, back_x_m, back_mass_fraction, k);
    const std::span<double> placed = std::span(x).first(pass.x_m.size());
    for (std::size_t i = 0; i < placed.size(); ++i) placed[i] = pass.mirror * orient * pass.x_m[i] - k * bout_width_m;
    return std::pair{std::span<const double>(placed), pass.mass_fraction};
  };
  for (int k = 1; k <= passes; ++k) {
    const auto [placed, mass] = place(k);
    for (std::size_t i = 0; i < placed.size(); ++i) f.fixed_beyond += beyond(placed[i], mass[i], f.line_m, f.kernel_m);
    metrics::accumulate_transverse_kernel(placed, mass, f.trays, f.kernel_m, f.fixed);
  }
  const double left_m = f.trays.left_edge_m(), w = f.trays.tray_width_m;
  f.first_judged = std::max(0, static_cast<int>(std::floor((f.judged_from_m - left_m) / w + 1e-9)));
  // Over-applied: above 1 + tolerance, or above what the field's interior gets at that place where that is
  // higher (a bout cannot be asked to be more even than the field); under-applied likewise. The interior:
  // the same passes continued past the edge (pass −k at +kW).
  std::pmr::vector<double> interior(f.fixed.size(), 0.0, memory);
  for (int k = -passes; k <= passes; ++k) {
    const auto [placed, mass] = place(k);
    metrics::accumulate_transverse_kernel(placed, mass, f.trays, f.kernel_m, interior);
  }
  for (double& v : interior) v /= f.target_per_tray;
  f.interior = std::move(interior);
  f.under_limit = 1.0 - edge.rate_tolerance;
  f.over_limit = 1.0 + edge.rate_tolerance;
  // Up to and with the tray that holds the line (only its part inside counts).
  f.end_inside = std::min(f.trays.tray_count, static_cast<int>(std::ceil((f.line_m - left_m) / w - 1e-9)));
}

// One disc of this pass at one setting: its trays and its mass beyond the line, at full flow.
struct EdgeDisc {
  explicit EdgeDisc(std::pmr::memory_resource* memory) : trays(memory) {}
  std::pmr::vector<double> trays;
  double beyond = 0.0, mass = 0.0;
};

// At most this many bouts judged (a throw of 100 m over 1 m bouts is already far beyond any spreader).
constexpr int kMaxJudgedBouts = 256;

// Per judged bout: the length above the over limit, and above it by more than the tolerance (flooded).
struct BoutTally {
  std::array<double, kMaxJudgedBouts> over_m{}, flooded_m{};
  int bouts = 0;
};

// The figures reset, and the pass's mass beyond the line with the edge-side disc at flow f.
void start_figures(const Frame& frame, const EdgeDisc& inner, const EdgeDisc& disc, double flow, EdgeProfile& out) {
  const double pass_mass = inner.mass + flow * disc.mass;
  out.mass_beyond_fraction =
      pass_mass > 0.0 ? (frame.fixed_beyond + inner.beyond + flow * disc.beyond) / pass_mass : 0.0;
  out.max_rate_inside = 0.0;
  out.max_rate_field = 0.0;
  out.max_excess = -std::numeric_limits<double>::infinity();
  out.missing_inside_m = 0.0;
  out.rate_at_edge = 0.0;
  out.mean_rate_last_bout = 0.0;
  out.under_applied_last_bout_m = 0.0;
  out.under_applied_m.clear();
  out.over_applied_m.clear();
}

// An over-applied stretch [a, b] at rate r, split at the bouts' ends into the tally.
void tally_over(double a, double b, double r, double over_limit, double tolerance, double bout_m, BoutTally& tally) {
  double from = a;
  while (from < b) {
    const int bout = bout_of(from + 1e-12, bout_m);
    const double bout_end = bout == 0 ? b : -(bout - 0.5) * bout_m;
    const double to = std::min(b, bout_end);
    if (bout < tally.bouts) {
      tally.over_m[static_cast<std::size_t>(bout)] += to - from;
      if (r > over_limit + tolerance) tally.flooded_m[static_cast<std::size_t>(bout)] += to - from;
    }
    from = to;
  }
}

// The bouts' tallies, the limits, and the verdict. The last bout is only [−W/2, line] wide; every bout is
// allowed the same length.
void finish_figures(const Frame& frame, const EdgeRequest& edge, const BoutTally& tally, EdgeProfile& out) {
  out.mean_rate_last_bout /= frame.line_m + 0.5 * frame.bout_width_m;
  out.most_flooded_m = *std::max_element(tally.flooded_m.begin(), tally.flooded_m.begin() + tally.bouts);
  out.most_over_applied_bout = 0;
  out.most_over_applied_m = tally.over_m[0];
  for (int j = 1; j < tally.bouts; ++j) {
    if (tally.over_m[static_cast<std::size_t>(j)] > out.most_over_applied_m) {
      out.most_over_applied_m = tally.over_m[static_cast<std::size_t>(j)];
      out.most_over_applied_bout = j;
    }
  }
  out.judged_from_m = frame.judged_from_m;
  out.over_limit = frame.over_limit;
  out.under_limit = frame.under_limit;
  const bool not_over = out.most_over_applied_m <= edge.max_over_applied_fraction * frame.bout_width_m + 1e-9 &&
                        out.max_excess <= edge.rate_tolerance;
  out.meets = edge.kind == EdgeKind::kBorder ? out.mass_beyond_fraction <= edge.max_beyond_fraction && not_over
                                             : out.rate_at_edge >= edge.min_edge_rate && not_over;
}

// Appends [from, to] to a list of stretches, joined to the last one when they meet.
void add_stretch(std::pmr::vector<std::pair<double, double>>& list, double from, double to) {
  if (!list.empty() && std::abs(list.back().second - from) < 1e-9) {
    list.back().second = to;
  } else {
    list.emplace_back(from, to);
  }
}

// The profile's figures with the field-side disc `inner` and the edge-side disc at flow f (strips only when
// `strips`): the judged span tray by tray, each tray's inside part [a, b] split at the bouts' ends.
void evaluate(const Frame& frame, const EdgeDisc& inner, const EdgeDisc& disc, double flow, const EdgeRequest& edge,
              EdgeProfile& out, bool strips) {
  const double w = frame.trays.tray_width_m, left_m = frame.trays.left_edge_m(), bout_m = frame.bout_width_m;
  start_figures(frame, inner, disc, flow, out);
  BoutTally tally;
  tally.bouts = std::min(frame.judged_bouts, kMaxJudgedBouts);
  const double last_from_m = -0.5 * bout_m, edge_strip_from_m = frame.line_m - w;
  for (int k = frame.first_judged; k < frame.end_inside; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const double r = (frame.fixed[i] + inner.trays[i] + flow * disc.trays[i]) / frame.target_per_tray;
    const double a = std::max(left_m + k * w, frame.judged_from_m), b = std::min(left_m + (k + 1) * w, frame.line_m);
    if (!(b > a)) continue;
    const double interior = frame.interior[i];
    // Where this pass gives what the interior gets, the two sums differ only by rounding: not over.
    constexpr double kRounding = 1e-9;
    const double over_limit = std::max(frame.over_limit, interior + kRounding);
    const double under_limit = std::min(frame.under_limit, interior - kRounding);
    const bool over = r > over_limit, under = r < under_limit;
    out.max_rate_field = std::max(out.max_rate_field, r);
    out.max_excess = std::max(out.max_excess, r - over_limit);
    if (b > last_from_m) {  // in the last bout
      const double inside_m = b - std::max(a, last_from_m);
      out.max_rate_inside = std::max(out.max_rate_inside, r);
      out.missing_inside_m += std::max(0.0, interior - r) * inside_m;
      out.mean_rate_last_bout += r * inside_m;
      if (under) out.under_applied_last_bout_m += inside_m;
    }
    if (b > edge_strip_from_m) out.rate_at_edge += r * (b - std::max(a, edge_strip_from_m)) / w;
    if (over) tally_over(a, b, r, over_limit, edge.rate_tolerance, bout_m, tally);
    if (strips && under) add_stretch(out.under_applied_m, a, b);
    if (strips && over) add_stretch(out.over_applied_m, a, b);
  }
  finish_figures(frame, edge, tally, out);
}

// Lower is better: the settings that meet the thresholds first (by the kind's aim), then the rest by how
// far they miss them.
double score(const EdgeProfile& p, const EdgeRequest& edge, double bout_width_m) {
  // Border spreading: the least fertiliser missing inside (nothing may go over). Edge spreading, whose
  // thresholds allow mass over the edge: the least fertiliser misplaced, missing inside or thrown over,
  // in the same unit (a share b of the pass's mass over the edge is about b·W metres of field rate).
  if (p.meets) {
    return edge.kind == EdgeKind::kBorder ? p.missing_inside_m : p.missing_inside_m + p.mass_beyond_fraction * bout_width_m;
  }
  const double over = std::max(0.0, p.most_over_applied_m / bout_width_m - edge.max_over_applied_fraction) /
                          std::max(edge.max_over_applied_fraction, 0.01) +
                      std::max(0.0, p.max_excess - edge.rate_tolerance) / edge.rate_tolerance;
  const double miss = edge.kind == EdgeKind::kBorder
                          ? std::max(0.0, p.mass_beyond_fraction / edge.max_beyond_fraction - 1.0)
                          : std::max(0.0, 1.0 - p.rate_at_edge / edge.min_edge_rate);
  // Among those that miss, each threshold's miss in units of the threshold: a border missed by a factor 30
  // is not closer than one missed by 2.5 with a bout over-applied a little more than allowed. But a setting
  // that floods a bout — more than twice the allowed length above the over limit by more than the
  // tolerance (10 % of a bout above 120 % with the defaults) — is the closest only when every other is too.
  const bool floods = p.most_flooded_m > 2.0 * edge.max_over_applied_fraction * bout_width_m + 1e-9;
  return (floods ? 1e12 : 1e6) * (1.0 + over + miss);
}

bool valid(const PredictionRequest& normal, const EdgeRequest& edge, const Predictor& predictor) {
  const double half = 0.5 * normal.bout_width_m;
  return normal.bout_width_m > 0.0 && predictor.machine().disc_count == 2 &&
         (edge.side == kLeftDisc || edge.side == kRightDisc) && edge.gap_m >= 0.0 && edge.gap_m < half &&
         edge.max_beyond_fraction > 0.0 && edge.max_beyond_fraction <= 1.0 && edge.rate_tolerance > 0.0 &&
         edge.rate_tolerance <= 1.0 && edge.min_edge_rate > 0.0 && edge.min_edge_rate <= 1.0 &&
         edge.max_over_applied_fraction >= 0.0 && edge.max_over_applied_fraction <= 1.0 &&
         edge.max_drop_point_turn_rad >= 0.0 && edge.max_drop_point_turn_rad <= kPi;
}

// A setting that changes the field-side disc too ranks after every one that meets the thresholds with that
// disc at the field's setting (the driver then sets apart one disc only), and before every one that does not.
constexpr double kFieldSideChangedPenalty = 1e3;

class EdgeSearch {
 public:
  EdgeSearch(Predictor& predictor, const PredictionRequest& normal, const EdgeRequest& edge,
             std::pmr::memory_resource* memory)
      : predictor_(predictor), normal_(normal), edge_(edge), frame_(memory), x_(memory), w_(memory),
        back_x_(memory), back_mass_(memory) {}

  // The normal prediction and the frame; false with status_ set when refused.
  bool start() {
    if (!valid(normal_, edge_, predictor_)) {
      status_ = PredictStatus::kOutOfRange;
      return false;
    }
    PredictionRequest r = normal_;
    r.standard_errors = false;
    status_ = predictor_.predict(r, prediction_);
    ++predictions_;
    if (status_ != PredictStatus::kOk) return false;
    if (prediction_.return_pass == ReturnPass::kFlown && !fly_return_pass(r)) return false;
    normal_disc_ = disc_setting(normal_, edge_.side);
    normal_field_side_ = disc_setting(normal_, field_side_index());
    const double max_rpm = predictor_.max_rpm(*predictor_.find_material(normal_.material));
    const double slowest_rpm = std::min(normal_disc_.rpm, normal_field_side_.rpm);
    make_frame(prediction_, back_x_, back_mass_, edge_, normal_.bout_width_m, prediction_.trays.tray_width_m,
               slowest_rpm > 0.0 ? std::max(1.0, max_rpm / slowest_rpm) : 1.0, frame_.fixed.get_allocator().resource(),
               frame_);
    kernel_m_ = prediction_.kernel_half_width_m;
    return true;
  }
  // The return pass of the passes before the last (driven the other way, it meets the wind from the other
  // side, the discs at the field's setting): its landings kept, then the normal prediction again, whose
  // views the search reads.
  bool fly_return_pass(const PredictionRequest& normal) {
    PredictionRequest back = normal;
    back.wind_x_m_s = -normal.wind_x_m_s;
    back.wind_y_m_s = -normal.wind_y_m_s;
    back.return_pass = ReturnPassSettings::kOutgoingMirrored;  // its landings alone are read
    status_ = predictor_.predict(back, prediction_);
    ++predictions_;
    if (status_ != PredictStatus::kOk) return false;
    back_x_.assign(prediction_.landing_x_m.begin(), prediction_.landing_x_m.end());
    back_mass_.assign(prediction_.landing_mass_fraction.begin(), prediction_.landing_mass_fraction.end());
    status_ = predictor_.predict(normal, prediction_);
    ++predictions_;
    return status_ == PredictStatus::kOk;
  }
  int field_side_index() const { return edge_.side == kRightDisc ? kLeftDisc : kRightDisc; }
  // This pass with the field-side disc at `field_side` and the edge-side one at `edge_side` (full flow): one
  // prediction; each disc's trays into `inner` and `disc`.
  bool pass_at(const DiscSetting& field_side, const DiscSetting& edge_side, EdgeDisc& inner, EdgeDisc& disc) {
    if (!predict_pass(field_side, edge_side)) return false;
    take(field_side_index(), inner);
    take(edge_.side, disc);
    return true;
  }
  // Disc `which` of this pass at `setting` (full flow), the other disc at its field setting: the discs fly
  // apart, so one disc's landings do not depend on the other's setting.
  bool disc_at(int which, const DiscSetting& setting, EdgeDisc& out) {
    const bool edge_side = which == edge_.side;
    if (!predict_pass(edge_side ? normal_field_side_ : setting, edge_side ? setting : normal_disc_)) return false;
    take(which, out);
    return true;
  }
  // The best flow of the edge-side disc at this pair of settings; its score.
  double best_flow(const EdgeDisc& inner, const EdgeDisc& disc, double& flow) {
    double best = std::numeric_limits<double>::infinity();
    const int steps = static_cast<int>(std::lround((kEdgeMaxFlow - kEdgeMinFlow) / kEdgeFlowStep));
    for (int i = 0; i <= steps; ++i) {
      const double f = kEdgeMinFlow + i * kEdgeFlowStep;
      evaluate(frame_, inner, disc, f, edge_, scratch_, false);
      const double s = score(scratch_, edge_, frame_.bout_width_m);
      if (s < best) {
        best = s;
        flow = f;
      }
    }
    return best;
  }
  void profile(const EdgeDisc& inner, const EdgeDisc& disc, double flow, EdgeProfile& p) {
    evaluate(frame_, inner, disc, flow, edge_, p, true);
    p.trays = frame_.trays;
    p.edge_line_m = frame_.line_m;
    p.rate.resize(frame_.fixed.size());
    for (std::size_t k = 0; k < p.rate.size(); ++k) {
      p.rate[k] = (frame_.fixed[k] + inner.trays[k] + flow * disc.trays[k]) / frame_.target_per_tray;
    }
  }

  PredictStatus status_ = PredictStatus::kOk;
  int predictions_ = 0;
  DiscSetting normal_disc_, normal_field_side_;

 private:
  bool predict_pass(const DiscSetting& field_side, const DiscSetting& edge_side) {
    PredictionRequest r = normal_;
    r.standard_errors = false;
    r.kernel_half_width_m = kernel_m_;
    const auto edge = static_cast<std::size_t>(edge_.side);
    const auto other = 1 - edge;
    // Each disc its own setting; the both-discs values, which no disc would use, cleared.
    r.disc_rpm[other] = field_side.rpm;
    r.disc_drop_point_turn_rad[other] = field_side.drop_point_turn_rad;
    r.disc_rpm[edge] = edge_side.rpm;
    r.disc_drop_point_turn_rad[edge] = edge_side.drop_point_turn_rad;
    r.rpm = 0.0;
    r.drop_point_turn_rad = 0.0;
    ++predictions_;
    return predictor_.predict(r, prediction_) == PredictStatus::kOk;
  }
  // Disc `which`'s landings of the last prediction into `out`'s trays, its mass and its mass beyond the line.
  void take(int which, EdgeDisc& out) {
    out.trays.assign(frame_.fixed.size(), 0.0);
    out.beyond = out.mass = 0.0;
    x_.clear();
    w_.clear();
    disc_landings(prediction_, which, edge_.side, [&](double x, double w) {
      x_.push_back(x);
      w_.push_back(w);
      out.mass += w;
      out.beyond += beyond(x, w, frame_.line_m, frame_.kernel_m);
    });
    metrics::accumulate_transverse_kernel(x_, w_, frame_.trays, frame_.kernel_m, out.trays);
  }

  Predictor& predictor_;
  PredictionRequest normal_;
  EdgeRequest edge_;
  Prediction prediction_;
  Frame frame_;
  double kernel_m_ = 0.0;
  std::pmr::vector<double> x_, w_;
  std::pmr::vector<double> back_x_, back_mass_;  // the return pass's landings where it is flown
  EdgeProfile scratch_;  // best_flow's evaluations (figures only: its vectors stay empty)
};

// The field-side disc's drop point on the last pass: NaN means the field's.
double field_side_turn(const EdgeSetting& setting, const DiscSetting& field) {
  return std::isnan(setting.field_side_drop_point_turn_rad) ? field.drop_point_turn_rad
                                                            : setting.field_side_drop_point_turn_rad;
}

}  // namespace

PredictStatus edge_profile(Predictor& predictor, const PredictionRequest& normal, const EdgeRequest& edge,
                           const EdgeSetting& setting, EdgeProfile& out, std::pmr::memory_resource* memory) {
  EdgeSearch search(predictor, normal, edge, memory);
  if (!search.start()) return search.status_;
  EdgeDisc inner(memory), disc(memory);
  const DiscSetting field_side{search.normal_field_side_.rpm, field_side_turn(setting, search.normal_field_side_)};
  if (!(setting.flow_fraction >= 0.0 && setting.flow_fraction <= kEdgeMaxFlow) ||
      !search.pass_at(field_side, setting.disc, inner, disc)) {
    return PredictStatus::kOutOfRange;
  }
  search.profile(inner, disc, setting.flow_fraction, out);
  return PredictStatus::kOk;
}

namespace {

// The drop points a disc's search may use: within ± the request's turn of its own and within the turns the
// table validates (a disc set outside them keeps its drop point).
struct TurnWindow {
  double base_rad = 0.0, low_rad = 0.0, high_rad = 0.0;
  TurnWindow(double base, double max_turn_rad, const TurnRange& valid)
      : base_rad(base), low_rad(std::max(valid.low_rad, base - max_turn_rad)),
        high_rad(std::min(valid.high_rad, base + max_turn_rad)) {
    if (low_rad > high_rad) low_rad = high_rad = base_rad;
  }
  // Grid points outside are skipped (not clamped onto its end: no setting is flown twice).
  bool outside(double turn_rad) const { return !TurnRange{low_rad, high_rad}.contains(turn_rad); }
};

// find_edge_setting's stages over one context: the normal setting's pass (start), whether the budget holds
// the whole search (count_whole), the field-side disc's drop points (field_side_discs), the edge-side
// disc's speed × drop point grid judged against each (coarse_grid), a finer grid around the best
// (fine_grid), and the answer's profile (answer). Each setting flown is judged as soon as it can be.
class EdgeGridSearch {
 public:
  EdgeGridSearch(Predictor& predictor, const PredictionRequest& normal, const EdgeRequest& edge,
                 std::pmr::memory_resource* memory, EdgeResult& result)
      : predictor_(predictor), normal_(normal), edge_(edge), memory_(memory), result_(result),
        search_(predictor, normal, edge, memory), inner_normal_(memory), disc_(memory), normal_disc_(memory),
        inner_turns_(memory), inners_(memory),
        step_rad_(kEdgeGridStep_deg * kPi / 180.0),
        turns_(static_cast<int>(std::floor(edge.max_drop_point_turn_rad / step_rad_ + 1e-9))) {}

  bool start() {
    if (!search_.start()) {
      result_.status = search_.status_;
      return false;
    }
    const std::optional<std::size_t> material = predictor_.find_material(normal_.material);
    min_rpm_ = predictor_.min_rpm(*material);
    max_rpm_ = predictor_.max_rpm(*material);
    speeds_ = std::max(1, static_cast<int>(std::ceil((max_rpm_ - min_rpm_) / kEdgeGridStep_rpm - 1e-9)));
    search_.pass_at(search_.normal_field_side_, search_.normal_disc_, inner_normal_, disc_);
    search_.profile(inner_normal_, disc_, 1.0, result_.normal_profile);
    // The budget: a grid point is flown only while one prediction is left after it for the answer's
    // profile; the points left out are skipped, so the search ends with the best of those flown (finished
    // false). The normal setting's edge-side disc is then judged against each field-side drop point.
    budget_ = std::max(edge_.max_predictions, kEdgeMinPredictions);
    limited_ = edge_.max_predictions < std::numeric_limits<int>::max();
    if (limited_) normal_disc_ = disc_;
    const TurnRange valid = predictor_.drop_point_turn_range();
    edge_window_.emplace(search_.normal_disc_.drop_point_turn_rad, edge_.max_drop_point_turn_rad, valid);
    field_window_.emplace(search_.normal_field_side_.drop_point_turn_rad, edge_.max_drop_point_turn_rad, valid);
    return true;
  }

  // A budget that may end the search early (short of every point of both grids and the finer grid's 120,
  // counted before any is flown): the search keeps its order, and each setting flown is judged as soon as
  // it can be, so that the answer is the best of what the budget bought and never worse than the normal
  // setting at its best flow. A budget the whole search fits runs it exactly as without one.
  void count_whole() {
    if (!limited_) return;
    int points = 0;
    for (int j = -turns_; j <= turns_; ++j) points += j != 0 && !field_window_->outside(field_window_->base_rad + j * step_rad_);
    for (int i = 0; i <= speeds_; ++i) {
      for (int j = -turns_; j <= turns_; ++j) points += j == 0 || !edge_window_->outside(edge_window_->base_rad + j * step_rad_);
    }
    whole_ = search_.predictions_ + points + 120 + 1 <= budget_;
    // Not the search spread_find_edge_setting runs (its ties may fall elsewhere), even should every point fit.
    if (!whole_) result_.finished = false;
  }

  // The field-side disc's drop points on its grid (index `turns`: the field's own), each flown once.
  void field_side_discs() {
    const double base = field_window_->base_rad;
    for (int j = -turns_; j <= turns_; ++j) {
      const double t = j == 0 ? base : base + j * step_rad_;
      if (j != 0 && field_window_->outside(t)) continue;
      if (j != 0 && !affordable()) continue;
      EdgeDisc d(memory_);
      if (j != 0 && !search_.disc_at(search_.field_side_index(), DiscSetting{search_.normal_field_side_.rpm, t}, d)) continue;
      inner_turns_.push_back(t);
      inners_.push_back(j == 0 ? inner_normal_ : std::move(d));
    }
  }

  // The edge-side disc's speed × drop point grid; every pair with a field-side drop point is judged from
  // the two discs' trays.
  void coarse_grid() {
    if (!whole_) {
      // Each field-side drop point flown, against the edge-side disc at the normal setting.
      for (std::size_t k = 0; k < inners_.size(); ++k) judge(k, search_.normal_disc_, normal_disc_);
    }
    const double base = edge_window_->base_rad;
    for (int i = 0; i <= speeds_; ++i) {
      for (int j = -turns_; j <= turns_; ++j) {
        if (j != 0 && edge_window_->outside(base + j * step_rad_)) continue;
        const DiscSetting setting{std::clamp(min_rpm_ + (max_rpm_ - min_rpm_) * i / speeds_, min_rpm_, max_rpm_),
                                  base + j * step_rad_};
        if (!affordable() || !search_.disc_at(edge_.side, setting, disc_)) continue;
        for (std::size_t k = 0; k < inners_.size(); ++k) judge(k, setting, disc_);
      }
    }
  }

  // A finer grid around the best edge-side setting, the field-side disc as found: a tenth of each step, over
  // one step each way.
  void fine_grid() {
    const EdgeSetting coarse = best_;
    const std::size_t coarse_inner = best_inner_;
    for (int i = -5; i <= 5; ++i) {
      for (int j = -5; j <= 5; ++j) {
        if (i == 0 && j == 0) continue;
        const double turn = coarse.disc.drop_point_turn_rad + j * 0.1 * step_rad_;
        if (j != 0 && edge_window_->outside(turn)) continue;
        const DiscSetting setting{std::clamp(coarse.disc.rpm + i * 0.1 * kEdgeGridStep_rpm, min_rpm_, max_rpm_), turn};
        if (!affordable() || !search_.disc_at(edge_.side, setting, disc_)) continue;
        judge(coarse_inner, setting, disc_);
      }
    }
  }

  void answer() {
    search_.disc_at(edge_.side, best_.disc, disc_);
    result_.setting = best_;
    search_.profile(inners_[best_inner_], disc_, best_.flow_fraction, result_.profile);
    result_.predictions = search_.predictions_;
  }

 private:
  bool affordable() {
    if (search_.predictions_ + 2 <= budget_) return true;
    result_.finished = false;
    return false;
  }
  // The pair (field-side drop point i, edge-side disc at `setting`) at its best flow, kept when it scores
  // lower than the best so far; a changed field-side drop point pays kFieldSideChangedPenalty.
  void judge(std::size_t i, const DiscSetting& setting, const EdgeDisc& d) {
    double flow = 1.0;
    double s = search_.best_flow(inners_[i], d, flow);
    const double field_base = field_window_->base_rad;
    if (inner_turns_[i] != field_base) s += kFieldSideChangedPenalty;
    if (s < best_score_) {
      best_score_ = s;
      best_ = EdgeSetting{setting, flow,
                          inner_turns_[i] == field_base ? std::numeric_limits<double>::quiet_NaN() : inner_turns_[i]};
      best_inner_ = i;
    }
  }

  Predictor& predictor_;
  const PredictionRequest& normal_;
  const EdgeRequest& edge_;
  std::pmr::memory_resource* memory_;
  EdgeResult& result_;
  EdgeSearch search_;
  EdgeDisc inner_normal_, disc_, normal_disc_;
  std::pmr::vector<double> inner_turns_;
  std::pmr::vector<EdgeDisc> inners_;
  double step_rad_ = 0.0;
  int turns_ = 0, speeds_ = 1;
  double min_rpm_ = 0.0, max_rpm_ = 0.0;
  int budget_ = 0;
  bool limited_ = false, whole_ = true;
  std::optional<TurnWindow> edge_window_, field_window_;
  double best_score_ = std::numeric_limits<double>::infinity();
  EdgeSetting best_;
  std::size_t best_inner_ = 0;
};

}  // namespace

EdgeResult find_edge_setting(Predictor& predictor, const PredictionRequest& normal, const EdgeRequest& edge,
                             std::pmr::memory_resource* memory) {
  EdgeResult result;
  EdgeGridSearch search(predictor, normal, edge, memory, result);
  if (!search.start()) return result;
  search.count_whole();
  search.field_side_discs();
  search.coarse_grid();
  search.fine_grid();
  search.answer();
  return result;
}

}  // namespace spread::predict
