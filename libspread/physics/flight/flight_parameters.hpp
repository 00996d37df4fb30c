#pragma once
// Everything the right-hand side needs, derived once per flight so the hot loop only multiplies.
// All rates are per unit mass: the RHS returns accelerations (m/s²) and spin rates (rad/s²).
#include "libspread/physics/flight/flight.hpp"
#include "libspread/physics/flight/flight_term_table.hpp"

namespace spread::flight::detail {

struct FlightParameters {
  // Drag, Eq. 27 divided by m, with C_D |v| = (C_D Re) μ/(ρ_f D):
  //   a = −(A μ / (2 m D)) (C_D Re) v_rel,  A μ/(2 m D) = 3 μ / (4 ρ_p D²)   [1/s]
  // (C_D Re = 24 gives the Stokes rate 18 μ/(ρ_p D²), the inverse of τ_p in seed Sect. 2.4.)
  double drag_rate_per_s = 0.0;
  double reynolds_per_speed_s_m = 0.0;   // Re / |v_rel| = ρ_f D / μ   (Eq. 31)
  // Magnus, Eq. 28 divided by m: a = (½ ρ_f A / m) g (ω × v_rel) with ½ρ_f A/m = 3 ρ_f / (4 ρ_p D) [1/m]
  double magnus_rate_per_m = 0.0;
  double diameter_m = 0.0;
  LiftModel lift = LiftModel::kSmoothSaturating;
  // Spin decay, Eqs. 34–36: dω/dt = −α (10 μ D / m) ω,  Re_spin = (ρ_f D²/(4μ)) |ω|
  double spin_decay_rate_per_s = 0.0;       // 10 μ D / m
  double spin_reynolds_per_rad_s = 0.0;     // ρ_f D² / (4 μ)  [s/rad]
  double wind_m_s[3] = {0.0, 0.0, 0.0};
  double gravity_m_s2 = kStandardGravity_m_s2;
  // Spin used by Magnus when spin decay is off (then ω is constant and not integrated).
  double constant_spin_rad_s[3] = {0.0, 0.0, 0.0};
  double constant_spin_norm_rad_s = 0.0;  // |constant_spin_rad_s|
  // The terms of their own (flight_terms.hpp): each derives its parameters.
  TermParameters terms;
};

// Assumes validated inputs.
FlightParameters make_flight_parameters(const Granule& granule, const State& launch, const Air& air,
                                        const Settings& settings);

inline double granule_mass_kg(const Granule& granule) {
  return granule.density_kg_m3 * kPi * granule.diameter_m * granule.diameter_m * granule.diameter_m /
         6.0;
}

}  // namespace spread::flight::detail
