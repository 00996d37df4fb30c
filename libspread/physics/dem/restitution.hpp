#pragma once
// Damping from the coefficient of restitution (seed Sect. 2.2).
namespace spread::dem {

// Hertz with δ^{1/4} damping (Eqs. 17–18): damping ratio γ for restitution e, Thornton, Cummins &
// Cleary (2013) fit as corrected in docs/design.md §2: γ = sqrt(1/(1 − (1+e)² exp(α)) − 1),
// α = e(h1 + e(h2 + … + e·h10)). The seed's Eq. 25 prints (1−e)², which is wrong. e >= 1 → 0.
double hertz_damping_ratio(double restitution);

// Linear spring–dashpot with the normal force clipped at 0: damping ratio ζ (F_d = 2ζ sqrt(m* k) δ̇)
// giving restitution e. Solved once by bisection on the non-dimensional impact (no closed form once
// the force is clipped). e >= 1 → 0.
double linear_damping_ratio(double restitution);

// Restitution of one non-dimensional head-on impact with damping ratio `ratio` (for tests and the
// bisection): Hertz (exponent 3/2, damping δ^{1/4}) or linear.
double simulated_restitution_hertz(double ratio);
double simulated_restitution_linear(double ratio);

}  // namespace spread::dem
