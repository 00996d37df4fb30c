#include "libspread/analysis/predict/wind_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/golden_section.hpp"

namespace spread::predict {

namespace {

// A CV a search can compare: NaN (no mass in the bout) ranks last.
double comparable(double cv) { return std::isnan(cv) ? std::numeric_limits<double>::infinity() : cv; }

// One disc's range: speed [low_rpm, high_rpm], drop-point turn [low_rad, high_rad].
struct DiscRange {
  double low_rpm = 0.0, high_rpm = 0.0, low_rad = 0.0, high_rad = 0.0;
};

// The search over one context: the request being varied, the shared layout and kernel, each disc's trays
// as they stand, and the buffers they live in (the workspace's search buffer).
class WindSearch {
 public:
  WindSearch(const Predictor& predictor, const PredictionRequest& request, Prediction& out, PredictorWorkspace& workspace)
      : predictor_(predictor), request_(request), out_(out), workspace_(workspace) {
    request_.rpm = 0.0;
    request_.drop_point_turn_rad = 0.0;
    request_.standard_errors = false;
  }

  // The present setting as a machine set once drives the field: its discs keep their settings on the
  // return pass (ReturnPassSettings::kSame), which meets the wind from the other side.
  PredictStatus predict_present(const DiscSetting (&present)[2]) {
    set(present);
    ++predictions_;
    request_.return_pass = ReturnPassSettings::kSame;
    const PredictStatus status = predictor_.predict(request_, out_, workspace_);
    // The search's own predictions read only the landings: no return pass flown for them.
    request_.return_pass = ReturnPassSettings::kOutgoingMirrored;
    return status;
  }

  // The layout (covering `extent_m` each side, within the predictor's limits and the buffer) and kernel of
  // the search, and each disc's trays at the present setting (the last prediction).
  void start(double extent_m, double kernel_m) {
    const double tray_width_m = out_.trays.tray_width_m;
    layout_ = metrics::tray_layout_covering(std::min(extent_m, predictor_.limits().max_half_extent_m), tray_width_m);
    kernel_m_ = kernel_m;
    bout_trays_ = metrics::bout_tray_count(layout_, request_.bout_width_m);
    const auto t = static_cast<std::size_t>(layout_.tray_count);
    const std::span<double> buffer = workspace_.search_buffer();
    for (int d = 0; d < 2; ++d) disc_trays_[d] = buffer.subspan(static_cast<std::size_t>(d) * t, t);
    candidate_ = buffer.subspan(2 * t, t);
    pattern_ = buffer.subspan(3 * t, t);
    scratch_ = buffer.subspan(4 * t);
    for (int d = 0; d < 2; ++d) land(d, disc_trays_[d]);
    cv_ = cv_of(disc_trays_[0], disc_trays_[1]);
  }

  // Disc `d` at `setting`, the other as it stands: the CV, and that disc's trays in candidate_. Beyond the
  // budget (predictions kept for the answer and its fall-back), not flown: infinity, which no setting keeps.
  double try_disc(int d, const DiscSetting& setting) {
    if (predictions_ + 1 + (kWindMinPredictions - 1) > budget_) {
      finished_ = false;
      return std::numeric_limits<double>::infinity();
    }
    DiscSetting discs[2] = {current_[0], current_[1]};
    discs[d] = setting;
    set(discs);
    ++predictions_;
    if (predictor_.predict(request_, out_, workspace_) != PredictStatus::kOk) return std::numeric_limits<double>::infinity();
    land(d, candidate_);
    return d == kLeftDisc ? cv_of(candidate_, disc_trays_[1]) : cv_of(disc_trays_[0], candidate_);
  }
  // Keeps disc `d` at `setting` when its CV is lower than the present best (candidate_ holds its trays).
  bool keep_if_lower(int d, const DiscSetting& setting, double cv) {
    if (!(cv < cv_)) return false;
    cv_ = cv;
    current_[d] = setting;
    std::copy(candidate_.begin(), candidate_.end(), disc_trays_[d].begin());
    return true;
  }
  // The golden-section refinement of one coordinate of disc `d` (speed or turn) around its value at the
  // start. Each point lower than the best so far is kept as it is flown (its trays are in candidate_ then),
  // which ends where the search's own best is; the other disc, which the points are judged with, stays.
  void refine(int d, bool speed, double low, double high, double tolerance) {
    const DiscSetting base = current_[d];
    const auto at = [&](double v) { return speed ? DiscSetting{v, base.drop_point_turn_rad} : DiscSetting{base.rpm, v}; };
    golden_section_minimum(
        [&](double v) {
          const double cv = try_disc(d, at(v));
          keep_if_lower(d, at(v), cv);
          return cv;
        },
        low, high, speed ? base.rpm : base.drop_point_turn_rad, cv_, tolerance);
  }

  DiscSetting current_[2];
  double cv_ = 0.0;
  int predictions_ = 0;
  int budget_ = std::numeric_limits<int>::max();
  bool finished_ = true;

  void set(const DiscSetting (&discs)[2]) {
    request_.disc_rpm = {discs[0].rpm, discs[1].rpm};
    request_.disc_drop_point_turn_rad = {discs[0].drop_point_turn_rad, discs[1].drop_point_turn_rad};
  }
  PredictionRequest& request() { return request_; }

 private:
  // Disc d's landings of the last prediction into `trays` (the left disc's come first).
  void land(int d, std::span<double> trays) {
    std::fill(trays.begin(), trays.end(), 0.0);
    const std::size_t first = d == kLeftDisc ? 0 : out_.left_landing_count;
    const std::size_t end = d == kLeftDisc ? out_.left_landing_count : out_.landing_x_m.size();
    metrics::accumulate_transverse_kernel(out_.landing_x_m.subspan(first, end - first),
                                          out_.landing_mass_fraction.subspan(first, end - first), layout_, kernel_m_,
                                          trays);
  }
  // The field's CV with the compensation applied on every heading: on the way back the wind comes from the
  // other side and the discs swap settings, so (the machine being its own mirror image) the return pass
  // lands as the outgoing one does — the racetrack overlap, exactly for a lateral wind. A wind along the
  // track makes the return pass differ by its along-track part alone, which the ranking leaves out; the
  // answer is predicted with its return pass flown (compensate_wind).
  double cv_of(std::span<const double> left, std::span<const double> right) {
    for (std::size_t k = 0; k < pattern_.size(); ++k) pattern_[k] = left[k] + right[k];
    const double cv = metrics::cv_at_trays(pattern_, layout_, bout_trays_, metrics::Overlap::kRacetrack, scratch_);
    return comparable(cv);
  }

  const Predictor& predictor_;
  PredictionRequest request_;
  Prediction& out_;
  PredictorWorkspace& workspace_;
  metrics::TrayLayout layout_;
  double kernel_m_ = 0.0;
  int bout_trays_ = 1;
  std::span<double> disc_trays_[2], candidate_, pattern_, scratch_;
};

}  // namespace

namespace {

// Each disc's range: its speed within the material's rows and ± max_speed_offset_rpm, its drop point within
// ± max_drop_point_turn_rad and the table's validated turns (a disc outside them keeps its own).
void disc_ranges(const Predictor& predictor, std::string_view material, const DiscSetting (&present)[2],
                 const WindCompensationLimits& limits, DiscRange (&range)[2]) {
  const std::optional<std::size_t> index = predictor.find_material(material);
  const double min_rpm = predictor.min_rpm(*index), max_rpm = predictor.max_rpm(*index);
  const TurnRange valid = predictor.drop_point_turn_range();
  for (int d = 0; d < 2; ++d) {
    const DiscSetting& p = present[d];
    range[d].low_rpm = std::max(min_rpm, p.rpm - limits.max_speed_offset_rpm);
    range[d].high_rpm = std::min(max_rpm, p.rpm + limits.max_speed_offset_rpm);
    range[d].low_rad = std::max(valid.low_rad, p.drop_point_turn_rad - limits.max_drop_point_turn_rad);
    range[d].high_rad = std::min(valid.high_rad, p.drop_point_turn_rad + limits.max_drop_point_turn_rad);
    if (range[d].low_rad > range[d].high_rad) range[d].low_rad = range[d].high_rad = p.drop_point_turn_rad;
  }
}

// The half-width (m) of the search's trays: wide enough for the fastest speed searched (launch speed is
// ωR), the present landings scaled, with the kernel and half a bout.
double search_half_width_m(const Prediction& present_prediction, const DiscSetting (&present)[2],
                           const DiscRange (&range)[2], double bout_width_m) {
  double reach_m = 0.0;
  for (double x : present_prediction.landing_x_m) {
    if (std::isfinite(x)) reach_m = std::max(reach_m, std::abs(x));
  }
  const double slowest_rpm = std::min(present[0].rpm, present[1].rpm);
  const double scale = slowest_rpm > 0.0 ? std::max(1.0, std::max(range[0].high_rpm, range[1].high_rpm) / slowest_rpm) : 1.0;
  return scale * reach_m + present_prediction.kernel_half_width_m + 0.5 * bout_width_m;
}

// Each disc in turn over its grid of speeds × drop points, keeping the lowest CV.
void grid_stage(WindSearch& search, const DiscRange (&range)[2], const int (&order)[2]) {
  for (const int d : order) {
    const DiscRange& r = range[d];
    const int turns = std::max(1, static_cast<int>(std::ceil((r.high_rad - r.low_rad) / kWindTurnStep_rad - 1e-9)));
    for (int i = 0; i < kWindSpeedSteps; ++i) {
      for (int j = 0; j <= turns; ++j) {
        const DiscSetting s{r.low_rpm + (r.high_rpm - r.low_rpm) * i / (kWindSpeedSteps - 1),
                            std::min(r.high_rad, r.low_rad + j * (r.high_rad - r.low_rad) / turns)};
        search.keep_if_lower(d, s, search.try_disc(d, s));
      }
    }
  }
}

// Rounds of golden sections, each disc's speed then its drop point, within one grid step of its best.
void refine_stage(WindSearch& search, const DiscRange (&range)[2], const int (&order)[2],
                  const WindCompensationLimits& limits) {
  for (int round = 0; round < kWindRefineRounds; ++round) {
    for (const int d : order) {
      const DiscRange& r = range[d];
      const double speed_step = (r.high_rpm - r.low_rpm) / (kWindSpeedSteps - 1);
      const double turn_step = std::min(kWindTurnStep_rad, r.high_rad - r.low_rad);
      const DiscSetting c = search.current_[d];
      search.refine(d, true, std::max(r.low_rpm, c.rpm - speed_step), std::min(r.high_rpm, c.rpm + speed_step),
                    limits.speed_tolerance_rpm);
      const DiscSetting c2 = search.current_[d];
      search.refine(d, false, std::max(r.low_rad, c2.drop_point_turn_rad - turn_step),
                    std::min(r.high_rad, c2.drop_point_turn_rad + turn_step), limits.drop_point_tolerance_rad);
    }
  }
}

}  // namespace

WindCompensation compensate_wind(const Predictor& predictor, const PredictionRequest& request, Prediction& out,
                                 PredictorWorkspace& workspace, const WindCompensationLimits& limits) {
  WindCompensation result;
  if (!(request.bout_width_m > 0.0) || predictor.machine().disc_count < 2) {
    result.status = PredictStatus::kOutOfRange;
    return result;
  }
  const DiscSetting present[2] = {disc_setting(request, kLeftDisc), disc_setting(request, kRightDisc)};
  // The caller's `out` stays unchanged on a refusal: a refused predict() leaves its output alone.
  WindSearch search(predictor, request, out, workspace);
  result.status = search.predict_present(present);
  if (result.status != PredictStatus::kOk) return result;
  const double present_cv = comparable(out.cv_to_and_fro);
  DiscRange range[2];
  disc_ranges(predictor, request.material, present, limits, range);
  search.current_[0] = present[0];
  search.current_[1] = present[1];
  search.budget_ = std::max(limits.max_predictions, kWindMinPredictions);
  search.start(search_half_width_m(out, present, range, request.bout_width_m), out.kernel_half_width_m);
  // The disc the wind comes from first (a wind towards +x comes from the left): the search is the mirror
  // image of itself for the mirror-image wind.
  const int first = request.wind_x_m_s >= 0.0 ? kLeftDisc : kRightDisc;
  const int order[2] = {first, 1 - first};
  grid_stage(search, range, order);
  refine_stage(search, range, order, limits);

  // The answer, with its standard errors. The search compared settings on one layout and kernel; the answer
  // is predicted on its own (its trays fitted, the automatic kernel): should that put it above the present
  // setting, the present setting is the answer — never worse than doing nothing.
  // The answer on the field: the discs swap settings with the heading (ReturnPassSettings::kSwapped); the
  // present setting kept on both headings (kSame).
  search.request().standard_errors = request.standard_errors;
  search.request().return_pass = ReturnPassSettings::kSwapped;
  search.set(search.current_);
  predictor.predict(search.request(), out, workspace);
  result.predictions = search.predictions_ + 1;
  if (comparable(out.cv_to_and_fro) > present_cv) {
    search.request().return_pass = ReturnPassSettings::kSame;
    search.set(present);
    predictor.predict(search.request(), out, workspace);
    ++result.predictions;
  }
  result.present_cv = present_cv;
  result.discs[kLeftDisc] = out.discs[kLeftDisc];
  result.discs[kRightDisc] = out.discs[kRightDisc];
  result.cv = comparable(out.cv_to_and_fro);
  result.finished = search.finished_;
  return result;
}

}  // namespace spread::predict
