#pragma once
// Dormand–Prince 5(4) for many flights at once: kFlightLanes flights side by side in SIMD lanes
// (structure of arrays: one FlightLanes per state component and stage). The stages, the right-hand side
// and the error norm run on all lanes together; each lane keeps its own step size, time, step count and
// acceptance, exactly as fly_dormand_prince (dormand_prince.hpp) does for one flight, with the same
// operations in the same order — so every landing is bit for bit the one fly_to_ground gives. A lane whose
// flight has landed (crossing located by the scalar code on that lane's step) or stopped takes the next
// flight at once, so lanes stay busy whatever the flight lengths.
//
// For the effect combinations without spin state or lift (gravity, drag, wind: what a drag-only table
// flies); the others fly one by one (fly_many, fly_to_ground.cpp).
#include <cstddef>
#include <span>

#include "libspread/physics/flight/dormand_prince.hpp"
#include "libspread/physics/flight/flight_lanes.hpp"

// FlightLanes by value: see flight_lanes.hpp on -Wpsabi.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace spread::flight::detail {

// The effects the lanes evaluate (flight_rhs_lanes): drag and wind, nothing else.
template <EffectSet E>
inline constexpr bool kLaneEffects = (E & ~(kDrag | kWind)) == 0;

// flight_rhs for kLaneEffects combinations, on lanes: the same operations as flight_rhs<E>.
template <EffectSet E>
[[gnu::always_inline]] inline void flight_rhs_lanes(const FlightLanes& drag_rate, const FlightLanes& reynolds_per_speed,
                                                   const double* wind_m_s, double gravity_m_s2, const FlightLanes* y,
                                                   FlightLanes* dy) {
  static_assert(kLaneEffects<E>);
  dy[0] = y[3];
  dy[1] = y[4];
  dy[2] = y[5];
  FlightLanes ax = splat<FlightLanes>(0.0);
  FlightLanes ay = splat<FlightLanes>(0.0);
  FlightLanes az = splat<FlightLanes>(-gravity_m_s2);
  if constexpr ((E & kDrag) != 0) {
    FlightLanes ux = y[3];
    FlightLanes uy = y[4];
    FlightLanes uz = y[5];
    if constexpr ((E & kWind) != 0) {
      ux -= wind_m_s[0];
      uy -= wind_m_s[1];
      uz -= wind_m_s[2];
    }
    const FlightLanes k = drag_rate_of(drag_rate, reynolds_per_speed, ux, uy, uz);
    ax -= k * ux;
    ay -= k * uy;
    az -= k * uz;
  }
  dy[3] = ax;
  dy[4] = ay;
  dy[5] = az;
}

// std::max(std::abs(a), std::abs(b)) lane by lane (as the scalar error norm: b where |a| < |b|, else |a|).
inline FlightLanes abs_max(FlightLanes a, FlightLanes b) {
  const FlightLaneBits sign = as_bits(splat<FlightLanes>(-0.0));
  const FlightLanes abs_a = from_bits(as_bits(a) & ~sign), abs_b = from_bits(as_bits(b) & ~sign);
  const FlightLaneBits m = abs_a < abs_b;
  return from_bits((as_bits(abs_b) & m) | (as_bits(abs_a) & ~m));
}

// Flies launches[i] (granules[i], or granules[0] for all) into out[i]; inputs validated by the caller.
template <EffectSet E>
void fly_dormand_prince_lanes(std::span<const Granule> granules, std::span<const State> launches,
                              double ground_z_m, const Air& air, const Settings& settings, std::span<Landing> out) {
  static_assert(kLaneEffects<E>);
  constexpr int kLanes = kFlightLanes;
  constexpr std::size_t n = 6;
  using T = FlightLanes;
  T y[n], y_new[n], stage[n], k1[n], k2[n], k3[n], k4[n], k5[n], k6[n], k7[n];
  for (std::size_t i = 0; i < n; ++i) y[i] = y_new[i] = stage[i] = k1[i] = splat<T>(0.0);
  T drag_rate = splat<T>(0.0), reynolds_per_speed = splat<T>(0.0), h_lanes = splat<T>(0.0);
  const double wind[3] = {air.wind_m_s[0], air.wind_m_s[1], air.wind_m_s[2]};
  const double gravity = settings.gravity_m_s2;
  const double rtol = settings.rel_tol;
  const double atol = settings.abs_tol;
  // Per lane: the flight it carries (-1: none), and fly_dormand_prince's loop variables.
  std::size_t flight[kLanes];
  bool busy[kLanes] = {};
  double t[kLanes] = {}, h[kLanes] = {};
  int steps[kLanes] = {}, rejected[kLanes] = {};
  bool last_rejected[kLanes] = {};
  std::size_t next = 0;
  const std::size_t count = launches.size();

  const auto lane_state = [&](int l, const StateVector<E>& v) {
    State s;
    for (int i = 0; i < 3; ++i) {
      s.position_m[i] = v[static_cast<std::size_t>(i)];
      s.velocity_m_s[i] = v[static_cast<std::size_t>(i + 3)];
    }
    s.spin_rad_s = launches[flight[l]].spin_rad_s;  // constant without spin decay (to_state)
    return s;
  };
  const auto gather = [&](const T* v, int l) {
    StateVector<E> s;
    for (std::size_t i = 0; i < n; ++i) s[i] = v[i][l];
    return s;
  };
  // The loop condition of fly_dormand_prince; false when lane l's flight stops there (not landed).
  const auto continues = [&](int l) {
    if (!(steps[l] < settings.max_steps && t[l] < settings.max_time_s)) return false;
    h[l] = std::min(h[l], settings.max_time_s - t[l]);
    return !(h[l] < kDpMinStep_s);
  };
  const auto stop_not_landed = [&](int l) {
    Landing& landing = out[flight[l]];
    landing = Landing{};
    landing.state = lane_state(l, gather(y, l));
    landing.flight_time_s = t[l];
    landing.steps = steps[l];
    landing.rejected_steps = rejected[l];
  };
  // Loads flights into lane l until one needs integrating (busy) or none is left (idle).
  const auto refill = [&](int l) {
    busy[l] = false;
    while (next < count) {
      const std::size_t i = next++;
      const State& launch = launches[i];
      if (launch.position_m.z() == ground_z_m && launch.velocity_m_s.z() <= 0.0) {  // as fly_unchecked
        out[i] = Landing{};
        out[i].state = launch;
        out[i].landed = true;
        continue;
      }
      const FlightParameters p =
          make_flight_parameters(granules.size() == 1 ? granules[0] : granules[i], launch, air, settings);
      const StateVector<E> y0 = to_state_vector<E>(launch);
      StateVector<E> dy0;
      flight_rhs<E>(p, y0, dy0);
      for (std::size_t c = 0; c < n; ++c) {
        y[c][l] = y0[c];
        k1[c][l] = dy0[c];
      }
      drag_rate[l] = p.drag_rate_per_s;
      reynolds_per_speed[l] = p.reynolds_per_speed_s_m;
      flight[l] = i;
      t[l] = 0.0;
      h[l] = settings.dt_s;
      steps[l] = rejected[l] = 0;
      last_rejected[l] = false;
      if (continues(l)) {
        busy[l] = true;
        return;
      }
      stop_not_landed(l);
    }
  };
  for (int l = 0; l < kLanes; ++l) refill(l);

  const auto rhs = [&](const T* in, T* dy) __attribute__((always_inline)) {
    flight_rhs_lanes<E>(drag_rate, reynolds_per_speed, wind, gravity, in, dy);
  };
  for (;;) {
    bool any = false;
    for (int l = 0; l < kLanes; ++l) {
      any = any || busy[l];
      h_lanes[l] = busy[l] ? h[l] : 0.0;  // an idle lane steps by 0: finite values, ignored
    }
    if (!any) break;
    const T hv = h_lanes;
    for (std::size_t i = 0; i < n; ++i) stage[i] = y[i] + hv * kA21 * k1[i];
    rhs(stage, k2);
    for (std::size_t i = 0; i < n; ++i) stage[i] = y[i] + hv * (kA31 * k1[i] + kA32 * k2[i]);
    rhs(stage, k3);
    for (std::size_t i = 0; i < n; ++i) stage[i] = y[i] + hv * (kA41 * k1[i] + kA42 * k2[i] + kA43 * k3[i]);
    rhs(stage, k4);
    for (std::size_t i = 0; i < n; ++i) {
      stage[i] = y[i] + hv * (kA51 * k1[i] + kA52 * k2[i] + kA53 * k3[i] + kA54 * k4[i]);
    }
    rhs(stage, k5);
    for (std::size_t i = 0; i < n; ++i) {
      stage[i] = y[i] + hv * (kA61 * k1[i] + kA62 * k2[i] + kA63 * k3[i] + kA64 * k4[i] + kA65 * k5[i]);
    }
    rhs(stage, k6);
    for (std::size_t i = 0; i < n; ++i) {
      y_new[i] = y[i] + hv * (kB1 * k1[i] + kB3 * k3[i] + kB4 * k4[i] + kB5 * k5[i] + kB6 * k6[i]);
    }
    rhs(y_new, k7);
    T sum = splat<T>(0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const T e = hv * (kE1 * k1[i] + kE3 * k3[i] + kE4 * k4[i] + kE5 * k5[i] + kE6 * k6[i] + kE7 * k7[i]);
      const T scale = atol + rtol * abs_max(y[i], y_new[i]);
      const T r = e / scale;
      sum += r * r;
    }
    const T err_lanes = lane_sqrt(sum / static_cast<double>(n));

    for (int l = 0; l < kLanes; ++l) {
      if (!busy[l]) continue;
      const double err = err_lanes[l];
      if (!(err <= 1.0)) {
        ++rejected[l];
        h[l] *= rejected_step_factor(err);
        last_rejected[l] = true;
        if (!continues(l)) {
          stop_not_landed(l);
          refill(l);
        }
        continue;
      }
      ++steps[l];
      if ((y[2][l] > ground_z_m || t[l] == 0.0) && y_new[2][l] <= ground_z_m) {  // as fly_dormand_prince
        DpStages<E> k;
        k.k1 = gather(k1, l);
        k.k2 = gather(k2, l);
        k.k3 = gather(k3, l);
        k.k4 = gather(k4, l);
        k.k5 = gather(k5, l);
        k.k6 = gather(k6, l);
        k.k7 = gather(k7, l);
        StateVector<E> y_land;
        const double theta = locate_crossing<E>(k, gather(y, l), gather(y_new, l), h[l], ground_z_m, y_land);
        Landing& landing = out[flight[l]];
        landing = Landing{};
        landing.state = lane_state(l, y_land);
        landing.flight_time_s = t[l] + theta * h[l];
        landing.steps = steps[l];
        landing.rejected_steps = rejected[l];
        landing.landed = true;
        refill(l);
        continue;
      }
      t[l] += h[l];
      for (std::size_t i = 0; i < n; ++i) {
        y[i][l] = y_new[i][l];
        k1[i][l] = k7[i][l];  // FSAL
      }
      h[l] *= accepted_step_factor(err, last_rejected[l], steps[l]);
      last_rejected[l] = false;
      if (!continues(l)) {
        stop_not_landed(l);
        refill(l);
      }
    }
  }
}

}  // namespace spread::flight::detail

#pragma GCC diagnostic pop
