#pragma once
// What the ECU needs from a spread prediction, independent of where it comes from (the C API over a
// table file in the product, an analytic stand-in in unit tests).
#include <cstddef>
#include <limits>
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

enum class PredictionOutcome { kOk, kUnknownMaterial, kOutOfRange, kFailed };

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
};

}  // namespace spread::firmware
