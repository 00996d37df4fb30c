#pragma once
// The flight ODE, seed Eqs. 26–36, as a template over the effect bits: an effect that is off is not
// compiled into that instantiation at all (docs/design.md §7). Gravity and the air block (drag, Magnus,
// spin decay, wind) are written here; every other flight effect is a term of its own (flight_terms.hpp),
// added through the term table. The state is a flat array
//   y = [x, y, z, vx, vy, vz, (ωx, ωy, ωz)]
// and the spin block exists only when kSpinDecay is on — otherwise ω is constant (Eq. 34 switched off)
// and Magnus reads it from the parameters.
#include <array>
#include <cmath>

#include "libspread/physics/flight/drag_coefficient.hpp"
#include "libspread/physics/flight/flight_parameters.hpp"
#include "libspread/physics/flight/flight_term_table.hpp"
#include "libspread/physics/flight/lift_coefficient.hpp"
#include "libspread/physics/flight/spin_decay.hpp"

namespace spread::flight::detail {

// A term marked kInAirBlock is evaluated by the code below, which knows exactly these.
static_assert(kAirBlockEffects == (kDrag | kMagnus | kSpinDecay | kWind),
              "flight_rhs's air block evaluates drag, Magnus, spin decay and wind: a term marked kInAirBlock "
              "needs its evaluation there (or is a term of its own, flight_terms.hpp)");

template <EffectSet E>
inline constexpr bool kIntegratesSpin = (E & kSpinDecay) != 0;

template <EffectSet E>
inline constexpr int kStateSize = kIntegratesSpin<E> ? 9 : 6;

template <EffectSet E>
using StateVector = std::array<double, kStateSize<E>>;

// Drag acceleration (Eq. 27 with Eq. 32) of the relative air velocity u: −k u, k = drag_rate (C_D Re)(Re),
// Re = reynolds_per_speed |u|, for the flights that can run in lanes (no lift, no spin decay). Shared by
// flight_rhs and the lanes (dormand_prince_lanes.hpp) so that such a flight gives the same bits either
// way. T = double or FlightLanes.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // FlightLanes by value: see flight_lanes.hpp
template <class T>
[[gnu::always_inline]] inline T drag_rate_of(T drag_rate_per_s, T reynolds_per_speed_s_m, T ux, T uy, T uz) {
  const T speed = lane_sqrt(ux * ux + uy * uy + uz * uz);
  const T reynolds = reynolds_per_speed_s_m * speed;  // Eq. 31
  return drag_rate_per_s * drag_coefficient_times_reynolds_arithmetic(reynolds);  // Eqs. 27, 32
}
#pragma GCC diagnostic pop

template <EffectSet E>
inline void flight_rhs(const FlightParameters& p, const StateVector<E>& y, StateVector<E>& dy) {
  constexpr bool kHasDrag = (E & kDrag) != 0;
  constexpr bool kHasMagnus = (E & kMagnus) != 0;
  constexpr bool kHasWind = (E & kWind) != 0;
  constexpr bool kNeedsAir = kHasDrag || kHasMagnus;

  // |ω| once, shared by Magnus and spin decay.
  [[maybe_unused]] double spin_norm = 0.0;
  if constexpr (kIntegratesSpin<E>) {
    spin_norm = std::sqrt(y[6] * y[6] + y[7] * y[7] + y[8] * y[8]);
  } else if constexpr (kHasMagnus) {
    spin_norm = p.constant_spin_norm_rad_s;
  }

  dy[0] = y[3];
  dy[1] = y[4];
  dy[2] = y[5];
  double ax = 0.0;
  double ay = 0.0;
  double az = -p.gravity_m_s2;

  if constexpr (kNeedsAir) {
    // Relative air velocity replaces v_p in every air term (docs/design.md §2, wind).
    double ux = y[3];
    double uy = y[4];
    double uz = y[5];
    if constexpr (kHasWind) {
      ux -= p.wind_m_s[0];
      uy -= p.wind_m_s[1];
      uz -= p.wind_m_s[2];
    }
    const double speed = std::sqrt(ux * ux + uy * uy + uz * uz);
    const double reynolds = p.reynolds_per_speed_s_m * speed;  // Eq. 31
    if constexpr (kHasDrag) {
      // Without lift and spin decay the flight may run in lanes: the lanes' drag (drag_rate_of, the same
      // speed and Re as above). Otherwise glibc's power, as before the lanes.
      double k;
      if constexpr (!kHasMagnus && !kIntegratesSpin<E>) {
        k = drag_rate_of(p.drag_rate_per_s, p.reynolds_per_speed_s_m, ux, uy, uz);
      } else {
        k = p.drag_rate_per_s * drag_coefficient_times_reynolds(reynolds);  // Eqs. 27, 32
      }
      ax -= k * ux;
      ay -= k * uy;
      az -= k * uz;
    }
    if constexpr (kHasMagnus) {
      double wx;
      double wy;
      double wz;
      if constexpr (kIntegratesSpin<E>) {
        wx = y[6];
        wy = y[7];
        wz = y[8];
      } else {
        wx = p.constant_spin_rad_s[0];
        wy = p.constant_spin_rad_s[1];
        wz = p.constant_spin_rad_s[2];
      }
      const double c = p.magnus_rate_per_m * magnus_gain_m(p.lift, p.diameter_m, spin_norm, speed, reynolds);
      ax += c * (wy * uz - wz * uy);  // Eq. 28: direction ω × v_rel
      ay += c * (wz * ux - wx * uz);
      az += c * (wx * uy - wy * ux);
    }
  }
  add_term_accelerations<E>(p.terms, y.data(), ax, ay, az);
  dy[3] = ax;
  dy[4] = ay;
  dy[5] = az;

  if constexpr (kIntegratesSpin<E>) {
    const double rate =
        p.spin_decay_rate_per_s * spin_decay_alpha_of(p.spin_reynolds_per_rad_s * spin_norm);  // Eqs. 34–36
    dy[6] = -rate * y[6];
    dy[7] = -rate * y[7];
    dy[8] = -rate * y[8];
  }
}

}  // namespace spread::flight::detail
