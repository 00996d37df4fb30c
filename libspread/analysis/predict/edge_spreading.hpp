#pragma once
// Border and edge spreading: the last bout along a field edge, with the edge-side disc set apart.
//
// The tramline of the last bout lies half a bout width W from the field edge. Across it (x from the
// tramline, towards the edge positive) the field receives this pass plus the passes before it: pass k at
// −kW, driven the other way for odd k (to-and-fro: its pattern mirrored). The passes before are at the
// normal setting; on this pass the disc on the edge side runs at its own speed, drop point and flow (the
// share of the normal metered flow it receives: a border setting reduces the rate on that side so that
// the field inside is not over-applied). The rate is read in trays, as a fraction of the field's rate
// inside (one pass's landed mass per bout width).
//
// Two kinds of edge (the German fertiliser ordinance, DüV §5, and the manufacturers' border settings):
// - border spreading (a road, a path, water): at most max_beyond_fraction of this pass's mass beyond the
//   edge line and no over-application anywhere the last pass reaches; next to water the edge line lies
//   gap_m inside the field edge (1 m with a border spreading device, 3 m without). Among the settings
//   that meet both, the one with the least fertiliser missing in the last bout.
// - edge spreading (next to another field): the rate over the strip of one tray width that ends at the
//   edge line at least min_edge_rate of the field's, and no over-application anywhere; among those, the
//   least fertiliser misplaced — missing in the last bout or thrown over the edge, in the same unit.
//
// The judge looks at the whole ground the last pass reaches, not at the last bout alone: a setting that
// keeps the last bout even by throwing its mass into the bout before floods that bout. The judged span
// runs from the edge line back over every bout the last pass can reach (its normal reach scaled by the
// fastest speed searched over the field's), and each bout of it — [−W/2, edge line], then
// [−3W/2, −W/2], … — is over-applied when more than max_over_applied_fraction of its width lies above the
// over limit, or any of it more than rate_tolerance above the over limit. The over limit at a place:
// 1 + rate_tolerance, or the rate the field's interior gets at the same place at the normal
// setting where that is higher (a bout cannot be asked to be more even than the field; under-applied
// likewise, below 1 − rate_tolerance and the interior's rate). Trays that straddle a bout's end count in
// both bouts by their overlap.
//
// Where the discs throw across the centre line, the field-side disc can put more over the line than the
// border allows even with the edge-side disc off; then its drop point changes on this pass too (turned to
// throw less towards the edge), a setting ranked after every one that meets the thresholds with the
// field-side disc unchanged.
//
// Search: the edge-side disc's speed over the material's rows in kEdgeGridStep_rpm steps times its drop
// point in kEdgeGridStep_deg steps within ±max_drop_point_turn_rad, each against the field-side disc's
// drop point on the same angular grid, then a finer grid around the best edge-side setting; at each pair
// the flow in steps of kEdgeFlowStep (the flow scales that disc's landings: no flight per step). The discs
// fly apart, so each disc is predicted once per setting and the pairs combine their trays. Predictions
// without standard errors, each disc's landings kept apart (Prediction::left_landing_count).
#include <cstdint>
#include <limits>
#include <memory_resource>
#include <utility>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

enum class EdgeKind : std::uint8_t { kBorder, kEdge };
const char* to_string(EdgeKind kind);

struct EdgeRequest {
  EdgeKind kind = EdgeKind::kBorder;
  int side = kRightDisc;                 // the edge's side as the driver sees it (kLeftDisc, kRightDisc)
  double gap_m = 0.0;                    // the edge line this far inside the field edge, m (>= 0, < W/2)
  double max_beyond_fraction = 0.001;    // border: of this pass's mass, beyond the edge line
  double rate_tolerance = 0.10;          // inside: over-applied above 1 + this, under-applied below 1 − this
  // Of any bout's width, at most this much above the over limit (one 0.5 m tray is 4.5 % of an 11 m bout),
  // and no tray anywhere more than rate_tolerance above it.
  double max_over_applied_fraction = 0.05;
  double min_edge_rate = 0.80;           // edge: the rate at the edge line, of the field's
  // The edge-side disc's drop point searched: turns within ± this of the field's setting (±90°, as the
  // setting chart; up to π).
  double max_drop_point_turn_rad = 1.5707963267948966;
  // find_edge_setting's budget: at most this many predictions (at least kEdgeMinPredictions: the field's,
  // the normal pass and the answer's profile). A budget that covers the whole search's count (its grid
  // points and the finer grid's 120, reckoned before any is flown) runs it unchanged. Any other runs the
  // same order and judges each setting as soon as it is flown, the normal setting's edge-side disc against
  // every field-side drop point flown first; the points beyond the budget are not flown, and the answer is
  // the best of what was (EdgeResult::finished false).
  int max_predictions = std::numeric_limits<int>::max();
};
inline constexpr int kEdgeMinPredictions = 3;

inline constexpr double kEdgeGridStep_rpm = 25.0;
inline constexpr double kEdgeGridStep_deg = 10.0;
inline constexpr double kEdgeFlowStep = 0.01;
inline constexpr double kEdgeMinFlow = 0.0, kEdgeMaxFlow = 1.20;  // 0: the edge-side disc off

// This pass's setting: the edge-side disc's speed, drop point and flow, and the field-side disc's drop point.
struct EdgeSetting {
  DiscSetting disc;
  double flow_fraction = 1.0;  // of the normal metered flow to that disc
  // The field-side disc's drop point on this pass (its speed and flow stay the field's); NaN: the field's.
  double field_side_drop_point_turn_rad = std::numeric_limits<double>::quiet_NaN();
};

struct EdgeProfile {
  EdgeProfile() = default;
  // Its vectors from `memory`.
  explicit EdgeProfile(std::pmr::memory_resource* memory) : rate(memory), under_applied_m(memory), over_applied_m(memory) {}
  metrics::TrayLayout trays;      // x from the last tramline, towards the edge positive
  std::pmr::vector<double> rate;  // per tray, of the field's rate inside
  double edge_line_m = 0.0;       // x of the edge line: W/2 − gap_m
  double mass_beyond_fraction = 0.0;  // of this pass's mass, beyond the edge line
  double max_rate_inside = 0.0;   // over the last bout's trays, [−W/2, edge line]
  double max_rate_field = 0.0;    // over the whole judged span, [judged_from_m, edge line]
  double over_limit = 0.0;        // 1 + tolerance: above it, and above the interior's rate there, over-applied
  double under_limit = 0.0;       // 1 − tolerance: below it, and below the interior's rate there, under-applied
  double max_excess = 0.0;        // the most any tray of the judged span lies above its over limit (< 0: none)
  // The mean rate over the strip of one tray width ending at the edge line (the trays it overlaps,
  // weighted by the overlap).
  double rate_at_edge = 0.0;
  // ∫ max(0, interior − rate) dx over the last bout: the fertiliser missing against what the field's
  // interior gets at each place, in metres of field rate.
  double missing_inside_m = 0.0;
  double mean_rate_last_bout = 0.0;      // over [−W/2, edge line]
  double under_applied_last_bout_m = 0.0;  // length of the last bout below under_limit
  // The bout with the most length above over_limit (0: the last bout, k: the k-th before it) and that
  // length, m; over the judged span.
  int most_over_applied_bout = 0;
  double most_over_applied_m = 0.0;
  double most_flooded_m = 0.0;    // the most length of one bout above its over limit by more than the tolerance
  double judged_from_m = 0.0;     // the judged span's field-side end (a bout edge)
  // Strips of the judged span where the rate is below under_limit or above over_limit, [from, to] m.
  std::pmr::vector<std::pair<double, double>> under_applied_m, over_applied_m;
  bool meets = false;             // the kind's thresholds
};

struct EdgeResult {
  PredictStatus status = PredictStatus::kOk;  // of the normal setting's request
  EdgeSetting setting;            // found (meets or, when nothing meets, the least violation)
  EdgeProfile profile;            // at that setting
  EdgeProfile normal_profile;     // the same pass with the edge-side disc at the normal setting
  int predictions = 0;
  bool finished = true;           // false: the budget (EdgeRequest::max_predictions) did not cover the whole search
};

// `normal`: the setting of the field (rpm, drop point or each disc's own), bout width (> 0), wind, height,
// CV target. kOutOfRange without a bout width, on a one-disc machine, or for an edge request out of its
// domain (gap outside [0, W/2), thresholds not in (0, 1] (max_over_applied_fraction [0, 1]), side not 0 or
// 1); a refused normal request is
// its status.
// Predicts through the Predictor's own workspace; its working arrays come from `memory`.
EdgeResult find_edge_setting(Predictor& predictor, const PredictionRequest& normal, const EdgeRequest& edge,
                             std::pmr::memory_resource* memory = std::pmr::get_default_resource());

// The profile of the last pass with the edge-side disc at `setting` into `out` (its vectors keep their
// allocator), the working arrays from `memory`. Status as find_edge_setting's; kOutOfRange too for a flow
// outside [0, kEdgeMaxFlow] or an edge-side setting the predictor refuses. `out` is unchanged on a refusal.
PredictStatus edge_profile(Predictor& predictor, const PredictionRequest& normal, const EdgeRequest& edge,
                           const EdgeSetting& setting, EdgeProfile& out,
                           std::pmr::memory_resource* memory = std::pmr::get_default_resource());

}  // namespace spread::predict
