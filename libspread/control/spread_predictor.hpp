#pragma once
// What the ECU needs from a spread prediction, independent of where it comes from (the C API over a
// table file in the product, an analytic stand-in in unit tests).
#include <array>
#include <cstddef>
#include <limits>
#include <span>
#include <string_view>

namespace spread::firmware {

struct SpreadPrediction {
  double throw_width_m = 0.0;      // lateral extent holding 99 % of the mass [m]
  double effective_width_m = 0.0;  // the headline working width (docs/metrics.md "Effective working width") [m]
  // The first band's upper end: every bout from the narrowest up to it meets the CV target. What automatic
  // mode aims at (rpm_for_width_solver.hpp): it grows steadily with the disc speed, where the headline
  // jumps to a wider band once that band is established [m].
  double first_band_width_m = 0.0;
  double cv_percent = 0.0;         // coefficient of variation at the requested bout width [%]
  // Monte Carlo standard errors of the three above over the table's launch samples (docs/metrics.md
  // "Uncertainty"); NaN = not known (a predictor without them, or undefined at this point).
  double throw_width_se_m = std::numeric_limits<double>::quiet_NaN();      // [m]
  double effective_width_se_m = std::numeric_limits<double>::quiet_NaN();  // [m]
  double cv_se_percent = std::numeric_limits<double>::quiet_NaN();         // [percentage points]
};

// kUnsupported: the predictor cannot answer this kind of question (one disc, or no search behind it).
enum class PredictionOutcome { kOk, kUnknownMaterial, kOutOfRange, kFailed, kUnsupported };

inline constexpr int kLeftDisc = 0, kRightDisc = 1;  // as the driver sees them

// One side's spread narrowed to an edge line, as the border search of docs/field-calibration.md "Border
// and edge spreading" finds it: the disc on that side at its own speed, drop point and share of the flow,
// and the other disc's drop point on this pass (NaN: unchanged).
struct SideNarrowing {
  double rpm = 0.0;                  // the side's disc [r/min]
  double drop_point_turn_rad = 0.0;  // the side's disc, turned from the table's drop point [rad]
  double flow_fraction = 1.0;        // the side's disc's flow, of the field's [-] (0: off)
  double other_drop_point_turn_rad = std::numeric_limits<double>::quiet_NaN();  // [rad]; NaN: the field's
  double mass_beyond_percent = 0.0;  // of this pass's mass, beyond the edge line [%]
  bool meets = false;                // the border's thresholds hold at this setting
};

// What to narrow: one side of the pattern of `material` at `rpm` (both discs alike) on bouts of
// `bout_width_m`, to an edge line `edge_line_m` from the centre line (0 < edge line <= bout / 2).
struct NarrowingRequest {
  std::string_view material;
  double rpm = 0.0;             // the field's disc speed [r/min]
  double bout_width_m = 0.0;    // [m]
  int side = kRightDisc;        // kLeftDisc, kRightDisc
  double edge_line_m = 0.0;     // [m]
  // false: a border (a road, water, a strip spread already): at most max_beyond_percent of the pass's
  // mass beyond the line. true: next to another field: the rate at the line at least 80 % of the field's.
  bool field_edge = false;
  double max_beyond_percent = 0.1;  // [%]
  double wind_x_m_s = 0.0;          // wind across the travel, to the right [m/s]
  double wind_y_m_s = 0.0;          // wind along the travel, forward [m/s]
};

// A strip of one side: distances from the machine's centre line outward on that side [m].
struct SideStrip {
  double from_m = 0.0;
  double to_m = 0.0;
};

struct RpmRange {
  double min_rpm = 0.0;  // [r/min]
  double max_rpm = 0.0;  // [r/min]
};

class SpreadPredictor {
 public:
  virtual ~SpreadPredictor() = default;
  // The materials the predictor knows (the ECU precomputes a width curve for each at start).
  virtual std::size_t material_count() const = 0;
  virtual std::string_view material_name(std::size_t index) const = 0;
  virtual bool has_material(std::string_view material) const = 0;
  // CV target the effective width is taken at [%].
  virtual double cv_target_percent() const = 0;
  // Disc speeds the predictor is valid for, for this material [r/min].
  virtual RpmRange rpm_range(std::string_view material) const = 0;
  // Predicts the pattern of `material` at disc speed `rpm` [r/min]; CV evaluated at bout width
  // `bout_width_m` [m] and the effective width at the predictor's CV target. Must not allocate.
  virtual PredictionOutcome predict(std::string_view material, double rpm, double bout_width_m,
                                    SpreadPrediction& out) = 0;
  // The setting that narrows `request`'s side to its edge line, with the least fertiliser missing (or
  // misplaced, at a field edge) inside, or the closest when none meets the thresholds.
  // `strip_rate_percent[i]` receives the mean rate this pass plus the passes before it give strip
  // `strips[i]`, percent of the field's rate. Seconds of work: never in the loop.
  virtual PredictionOutcome narrow_side(const NarrowingRequest& request, std::span<const SideStrip> strips,
                                        std::span<double> strip_rate_percent, SideNarrowing& out) {
    (void)request, (void)strips, (void)strip_rate_percent, (void)out;
    return PredictionOutcome::kUnsupported;
  }
  // Wind compensation: each disc's speed and drop point (flow 1; `meets`: the CV at the bout width within
  // the target) that bring the to-and-fro pattern at `rpm` back towards the CV target in the wind.
  // Tens of milliseconds: never in the loop.
  virtual PredictionOutcome compensate_wind(std::string_view material, double rpm, double bout_width_m,
                                            double wind_x_m_s, double wind_y_m_s, std::array<SideNarrowing, 2>& out) {
    (void)material, (void)rpm, (void)bout_width_m, (void)wind_x_m_s, (void)wind_y_m_s, (void)out;
    return PredictionOutcome::kUnsupported;
  }
};

}  // namespace spread::firmware
