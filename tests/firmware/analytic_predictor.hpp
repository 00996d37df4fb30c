#pragma once
// A stand-in for the C API in tests and benchmarks: a smooth, monotonic width-vs-rpm law with known
// inverse, so automatic mode can be checked against an exact answer.
//   throw width  T(rpm) = k * rpm² (ballistic range grows with launch speed², launch speed ∝ rpm)
//   effective    E(rpm) = 0.75 * T(rpm)
//   CV at bout W       = 10 % * (W / E)²  (15 % reached at W = E * sqrt(1.5); only for display)
#include <cmath>
#include <string_view>

#include "libspread/control/spread_predictor.hpp"

namespace spread::firmware::testing {

class AnalyticPredictor final : public SpreadPredictor {
 public:
  static constexpr double kThrowWidthPerRpmSquared = 36.0 / (1000.0 * 1000.0);  // 36 m at 1000 r/min
  static constexpr double kEffectiveFraction = 0.75;

  std::size_t material_count() const override { return 2; }
  std::string_view material_name(std::size_t index) const override { return index == 0 ? "urea" : "can27"; }
  bool has_material(std::string_view material) const override {
    return material == "urea" || material == "can27";
  }
  double cv_target_percent() const override { return 15.0; }
  RpmRange rpm_range(std::string_view) const override { return {300.0, 1100.0}; }
  PredictionOutcome predict(std::string_view material, double rpm, double bout_width_m,
                            SpreadPrediction& out) override {
    ++calls;
    if (!has_material(material)) return PredictionOutcome::kUnknownMaterial;
    if (rpm < 300.0 || rpm > 1100.0) return PredictionOutcome::kOutOfRange;
    if (fail_next) return PredictionOutcome::kFailed;
    // CAN 27 flies a little shorter than urea in this stand-in (denser, larger granules).
    const double material_factor = material == "urea" ? 1.0 : 0.9;
    out.throw_width_m = material_factor * kThrowWidthPerRpmSquared * rpm * rpm;
    out.effective_width_m = kEffectiveFraction * out.throw_width_m;
    out.first_band_width_m = out.effective_width_m;  // one band
    const double ratio = bout_width_m / out.effective_width_m;
    out.cv_percent = 10.0 * ratio * ratio;
    return PredictionOutcome::kOk;
  }
  // Exact inverse of E(rpm) for urea [r/min].
  static double urea_rpm_for_effective_width(double width_m) {
    return std::sqrt(width_m / (kEffectiveFraction * kThrowWidthPerRpmSquared));
  }

  int calls = 0;
  bool fail_next = false;
};

}  // namespace spread::firmware::testing
