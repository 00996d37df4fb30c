#pragma once
// Spin (Magnus) lift coefficients, seed Eqs. 28–30, and the "gain" the RHS actually needs.
//
// Eq. 28: F = ½ ρ C_L A |v| (ω × v)/|ω|, with spin ratio Ω = D|ω|/(2|v|) (Eq. 30) and Re = ρ D |v|/μ.
// The RHS writes it as F = ½ ρ A · g · (ω × v) with the gain g = C_L |v| / |ω| (metres). g is computed
// so that it stays finite when ω → 0 or v → 0; since |ω × v| ≤ |ω||v|, |F| ≤ ½ρA C_L |v|², so the force
// tends to 0 in both limits.
#include <cmath>

#include "libspread/physics/flight/flight.hpp"

namespace spread::flight::detail {

inline constexpr double kLiftSaturation = 0.45;  // Oesterle & Bui Dinh high-Re plateau of C_L

// tanh(x)/x for x >= 0, accurate down to x = 0 (series below 1e-4: error < 2x⁴/15 < 1e-16 relative).
// tanh(x) = e/(e + 2) with e = expm1(2x): no cancellation at small x, half the cost of std::tanh
// (glibc, measured); above x = 20, tanh(x) = 1 to double precision (and expm1 would overflow at 355).
inline double tanh_over_x(double x) {
  if (x < 1e-4) return 1.0 - x * x / 3.0;
  if (x > 20.0) return 1.0 / x;
  const double e = std::expm1(2.0 * x);
  return e / ((e + 2.0) * x);
}

// Oesterle & Bui Dinh (1998): C_L = 0.45 + (2Ω − 0.45) exp(−0.075 Ω^p Re^0.7), seed Eq. 29.
// p = 0.4 in the original paper; the seed prints 0.04 (see docs/physics-flight.md).
inline double oesterle_bui_dinh(double spin_ratio, double reynolds, double spin_exponent) {
  return kLiftSaturation + (2.0 * spin_ratio - kLiftSaturation) *
                               std::exp(-0.075 * std::pow(spin_ratio, spin_exponent) *
                                        std::pow(reynolds, 0.7));
}

inline double lift_coefficient_of(LiftModel model, double spin_ratio, double reynolds) {
  switch (model) {
    case LiftModel::kSmoothSaturating:
      // Slope 2Ω at small Ω (Rubinow–Keller: C_L = 2Ω), saturating at 0.45.
      return kLiftSaturation * std::tanh(2.0 * spin_ratio / kLiftSaturation);
    case LiftModel::kOesterleBuiDinh:
      return oesterle_bui_dinh(spin_ratio, reynolds, 0.4);
    case LiftModel::kOesterleBuiDinhAsPrinted:
      return oesterle_bui_dinh(spin_ratio, reynolds, 0.04);
  }
  return 0.0;
}

// g = C_L |v| / |ω| in metres (see above). spin_norm = |ω| (rad/s), speed = |v_rel| (m/s).
inline double magnus_gain_m(LiftModel model, double diameter_m, double spin_norm, double speed,
                            double reynolds) {
  if (spin_norm <= 0.0 || speed <= 0.0) return 0.0;  // ω × v = 0 or |v| = 0: no lift
  if (model == LiftModel::kSmoothSaturating) {
    // C_L |v|/|ω| = 0.45 tanh(x) |v|/|ω| with x = D|ω|/(0.45|v|)  ⇒  g = D · tanh(x)/x:
    // exact, and bounded by D without dividing by a small |ω| or |v|.
    const double x = diameter_m * spin_norm / (kLiftSaturation * speed);
    return diameter_m * tanh_over_x(x);
  }
  const double spin_ratio = diameter_m * spin_norm / (2.0 * speed);  // Eq. 30
  return lift_coefficient_of(model, spin_ratio, reynolds) * speed / spin_norm;
}

}  // namespace spread::flight::detail
