#pragma once
// Time step from the contact duration (seed Sect. 3.1 with the docs/design.md §2 correction of Eq. 43).
#include <vector>

#include "libspread/physics/dem/material.hpp"

namespace spread::dem {

struct EngineParams;  // engine.hpp

// Hertz contact duration (Johnson): t_c = 2.87 (M*² / (R* E*² v))^{1/5}, v the impact speed (m/s).
double hertz_contact_time_s(double m_eff_kg, double r_eff_m, double e_star_pa, double impact_speed_m_s);

// Linear spring: t_c = π / sqrt(k/M*) (undamped half period).
double linear_contact_time_s(double m_eff_kg, double stiffness_n_m);

// Largest step for which the explicit integrators stay stable on the stiffest contact spring met at
// `impact_speed_m_s`: Δt < 2/ω_max with ω² = k/M* for the normal spring (Hertz: k = 2E* sqrt(R* δ_max),
// δ_max = (15 M* v² / (16 E* sqrt(R*)))^{2/5}) and, with rotation, the tangential spring acting on the
// reduced mass M*/(1 + M* R*²/I) (a solid sphere on a wall: M*/3.5).
double stable_step_bound_s(const ContactLaw& law, const PairParams& pair, double m_eff_kg, double r_eff_m,
                           double impact_speed_m_s, bool rotation);


// The engine's step. t_c and the stable bound are the smallest over every (non-rigid) material against
// every material at the smallest particle radius (t_c ∝ R), both as particle against a wall
// (R* = r, M* = m) and against an equal particle (R* = r/2, M* = m/2), at the impact speed v
// (params.impact_speed_m_s, or the fastest wall surface + 5 m/s). Δt = min(t_c/N_c, bound) when
// params.dt_s is 0; a given Δt is kept if it is within the bound. Throws std::invalid_argument for a
// Δt above the bound, negative, or NaN.
struct StepChoice {
  double contact_time_s = 0.0;  // t_c
  double stable_bound_s = 0.0;  // largest stable Δt
  double dt_s = 0.0;            // the step the engine takes
};
StepChoice choose_time_step(const std::vector<Material>& materials, const PairTable& pair_table,
                            const EngineParams& params, double fastest_wall_speed_m_s);

}  // namespace spread::dem
