#pragma once
// Time step from the contact duration (seed Sect. 3.1 with the DESIGN.md §2 correction of Eq. 43).
#include "libspread/dem/material.hpp"

namespace spread::dem {

// Hertz contact duration (Johnson): t_c = 2.87 (M*² / (R* E*² v))^{1/5}, v the impact speed (m/s).
double hertz_contact_time_s(double m_eff_kg, double r_eff_m, double e_star_pa, double impact_speed_m_s);

// Linear spring: t_c = π / sqrt(k/M*) (undamped half period).
double linear_contact_time_s(double m_eff_kg, double stiffness_n_m);

// Largest step for which the explicit integrators stay stable on the stiffest contact spring met at
// `impact_speed_m_s`: Δt < 2/ω_max with ω² = k/M* for the normal spring (Hertz: k = 2E* sqrt(R* δ_max),
// δ_max = (15 M* v² / (16 E* sqrt(R*)))^{2/5}) and, with rotation, the tangential spring acting on the
// reduced mass M*/(1 + M* R*²/I) (a solid sphere on a wall: M*/3.5).
double stable_step_bound_s(ContactModel model, const PairParams& pair, double m_eff_kg, double r_eff_m,
                           double impact_speed_m_s, bool rotation);

}  // namespace spread::dem
