#pragma once
// Viscous spin decay of a sphere in still air, seed Eqs. 34–36:
//   I dω/dt = −α μ D³ ω,   α = 2.01 (1 + 0.201 √Re_spin),   Re_spin = ρ |ω| D² / (4 μ),
// with I = m D²/10 (solid sphere), so dω/dt = −(10 α μ D / m) ω.
#include <cmath>

namespace spread::flight::detail {

inline double spin_decay_alpha_of(double spin_reynolds) {
  return 2.01 * (1.0 + 0.201 * std::sqrt(spin_reynolds));
}

}  // namespace spread::flight::detail
