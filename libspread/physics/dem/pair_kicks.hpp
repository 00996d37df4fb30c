#pragma once
// The integrator's stage inside the pair pass: velocity Verlet's closing half kick of each particle as its
// sums complete, and (the pass's drift form) the next step's opening half kick and drift, one particle at a
// time or eight a register (the batched pass). Each operation is the one DemEngine::kick, kick_spin and
// kick_drift_range (integrators.cpp) compute, in the same order, so the bits are those of separate passes.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "libspread/physics/dem/lane_rows.hpp"
#include "libspread/physics/dem/pair_pass_context.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace spread::dem::pairs {

// One kick's increments for particle i with force f (N) and torque t (N m): Δv = Δt (F/m + g),
// Δω = Δt T/I, exactly as DemEngine::kick and kick_spin compute them (Δt = kick_dt_s).
template <bool kRotation, class Law>
SPREAD_CONTACT_INLINE void kick_increments(const PairPassArrays<Law>& a, std::size_t i, const double (&f)[3], const double (&t)[3],
                                           double (&dv)[3], double (&dw)[3]) {
  const double dt = a.kick_dt_s, inv_m = a.inv_mass[i];
SPREAD_UNROLL(3)
  for (int c = 0; c < 3; ++c) dv[c] = dt * (f[c] * inv_m + a.gravity_m_s2[c]);
  if constexpr (kRotation) {
    const double inv_i = a.inv_inertia[i];
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) dw[c] = dt * t[c] * inv_i;
  }
}

// v += Δt (F/m + g), ω += Δt T/I for particle i, with its sums as stored.
template <bool kRotation, class Law>
SPREAD_CONTACT_INLINE void kick_particle(const PairPassArrays<Law>& a, std::size_t i) {
  if (!a.active[i]) return;
  const double f[3] = {a.fx[i], a.fy[i], a.fz[i]};
  double t[3] = {0.0, 0.0, 0.0}, dv[3], dw[3];
  if constexpr (kRotation) {
    t[0] = a.tx[i];
    t[1] = a.ty[i];
    t[2] = a.tz[i];
  }
  kick_increments<kRotation>(a, i, f, t, dv, dw);
SPREAD_UNROLL(3)
  for (int c = 0; c < 3; ++c) {
    a.kick_v[c][i] += dv[c];
    if constexpr (kRotation) a.kick_w[c][i] += dw[c];
  }
}

// Velocity Verlet's closing half kick of particle i with its finished sums F = F_walls + (partners' share +
// own share), the next step's opening half kick with the same F (v(t + 3Δt/2) = v(t + Δt) + Δt/2 a(t + Δt):
// the same increment added twice), and the next step's drift x += Δt v — each operation as kick_particle
// and the engine's kick_drift_range do it, so the bits are those of the two passes. The drift and the move
// apply to every particle, the kicks to the active ones (as there).
// The pairs' share of the sums comes as total_f = partners' share + own share (N), total_t likewise (N m).
template <bool kRotation, class Law>
SPREAD_CONTACT_INLINE void kick_twice_and_drift(const PairPassArrays<Law>& a, std::size_t i, const double (&total_f)[3],
                                                const double (&total_t)[3], double& moved2) {
  const double f[3] = {a.fx[i] + total_f[0], a.fy[i] + total_f[1], a.fz[i] + total_f[2]};
  double t[3] = {0.0, 0.0, 0.0};
  if constexpr (kRotation) {
    const double* const torque[3] = {a.tx, a.ty, a.tz};
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) t[c] = torque[c][i] + total_t[c];
  }
  double v[3] = {a.kick_v[0][i], a.kick_v[1][i], a.kick_v[2][i]}, w[3] = {0.0, 0.0, 0.0};
  if constexpr (kRotation) {
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) w[c] = a.kick_w[c][i];
  }
  if (a.active[i]) {
    double dv[3], dw[3];
    kick_increments<kRotation>(a, i, f, t, dv, dw);
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      v[c] = (v[c] + dv[c]) + dv[c];
      a.kick_v[c][i] = v[c];
      if constexpr (kRotation) {
        w[c] = (w[c] + dw[c]) + dw[c];
        a.kick_w[c][i] = w[c];
      }
    }
  }
  if (a.drift_clears_sums) {
    a.fx[i] = a.fy[i] = a.fz[i] = 0.0;
    if constexpr (kRotation) a.tx[i] = a.ty[i] = a.tz[i] = 0.0;
  }
  double x[3];
SPREAD_UNROLL(3)
  for (int c = 0; c < 3; ++c) {
    x[c] = a.position[c][i] + a.drift_dt_s * v[c];
    a.position[c][i] = x[c];
  }
  if (a.touch_rows != nullptr) {
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      a.touch_rows[4 * i + static_cast<std::size_t>(c)] = x[c];
      a.law_rows[8 * i + static_cast<std::size_t>(c)] = v[c];
      if constexpr (kRotation) a.law_rows[8 * i + 3 + static_cast<std::size_t>(c)] = w[c];
    }
  }
  if (a.x0 != nullptr) {
    const double dx = x[0] - a.x0[i], dy = x[1] - a.y0[i], dz = x[2] - a.z0[i];
    moved2 = std::max(moved2, dx * dx + dy * dy + dz * dz);
  }
}

// kick_twice_and_drift for particles [i, i + 8), a particle a lane: lane by lane the same operations in the
// same order (the same bits), eight particles an instruction (one at a time they took about a quarter of the
// pass's samples; in registers about 18 time-stamp ticks a particle, docs/drum.md). total_f[c], total_t[c]:
// the pairs' share of the eight particles' sums, component c. moved2: the largest squared move since the near
// list's build, lane by lane.
template <bool kRotation, class Law>
SPREAD_CONTACT_INLINE void kick_twice_and_drift8(const PairPassArrays<Law>& a, std::size_t i, const double* const (&total_f)[3],
                                                 const double* const (&total_t)[3], lanes::Lanes8& moved2) {
  using lanes::Lanes8;
  using lanes::Mask8;
  using Bytes8 = std::uint8_t __attribute__((vector_size(8)));
  Bytes8 active_bytes;
  __builtin_memcpy(&active_bytes, a.active + i, sizeof active_bytes);
  const Mask8 active = __builtin_convertvector(active_bytes, Mask8) != 0;  // the kicks apply to the active only
  const Lanes8 dt = splat<Lanes8>(a.kick_dt_s), inv_m = load_lanes8(a.inv_mass + i);
  double* const force[3] = {a.fx, a.fy, a.fz};
  double* const torque[3] = {a.tx, a.ty, a.tz};
  Lanes8 v[3], w[3] = {splat<Lanes8>(0.0), splat<Lanes8>(0.0), splat<Lanes8>(0.0)};
SPREAD_UNROLL(3)
  for (int c = 0; c < 3; ++c) {
    const Lanes8 f = load_lanes8(force[c] + i) + load_lanes8(total_f[c]);
    const Lanes8 dv = dt * (f * inv_m + splat<Lanes8>(a.gravity_m_s2[c]));
    const Lanes8 v0 = load_lanes8(a.kick_v[c] + i);
    v[c] = lanes::select(active, (v0 + dv) + dv, v0);
    store_lanes8(a.kick_v[c] + i, v[c]);
  }
  if constexpr (kRotation) {
    const Lanes8 inv_i = load_lanes8(a.inv_inertia + i);
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      const Lanes8 t = load_lanes8(torque[c] + i) + load_lanes8(total_t[c]);
      const Lanes8 dw = dt * t * inv_i;
      const Lanes8 w0 = load_lanes8(a.kick_w[c] + i);
      w[c] = lanes::select(active, (w0 + dw) + dw, w0);
      store_lanes8(a.kick_w[c] + i, w[c]);
    }
  }
  if (a.drift_clears_sums) {
SPREAD_UNROLL(3)
    for (int c = 0; c < 3; ++c) {
      store_lanes8(force[c] + i, splat<Lanes8>(0.0));
      if constexpr (kRotation) store_lanes8(torque[c] + i, splat<Lanes8>(0.0));
    }
  }
  Lanes8 x[3];
  const Lanes8 drift_dt = splat<Lanes8>(a.drift_dt_s);
SPREAD_UNROLL(3)
  for (int c = 0; c < 3; ++c) {
    x[c] = load_lanes8(a.position[c] + i) + drift_dt * v[c];
    store_lanes8(a.position[c] + i, x[c]);
  }
  if (a.touch_rows != nullptr) {
    double* const rows = a.touch_rows + 4 * i;
    store_touch_rows2<0>(rows, x[0], x[1], x[2]);
    store_touch_rows2<1>(rows, x[0], x[1], x[2]);
    store_touch_rows2<2>(rows, x[0], x[1], x[2]);
    store_touch_rows2<3>(rows, x[0], x[1], x[2]);
    // The law rows (vx, vy, vz, wx, wy, wz, r, I) as written before the pass (no spin: zeros).
    const Lanes8 col[8] = {v[0], v[1], v[2], w[0], w[1], w[2], load_lanes8(a.radius + i), load_lanes8(a.inertia + i)};
    Lanes8 row[8];
    transpose8x8(col, row);
SPREAD_UNROLL(8)
    for (int l = 0; l < 8; ++l) store_lanes8(a.law_rows + 8 * (i + static_cast<std::size_t>(l)), row[l]);
  }
  if (a.x0 != nullptr) {
    const Lanes8 dx = x[0] - load_lanes8(a.x0 + i), dy = x[1] - load_lanes8(a.y0 + i), dz = x[2] - load_lanes8(a.z0 + i);
    const Lanes8 d2 = dx * dx + dy * dy + dz * dz;
    moved2 = lanes::select(moved2 < d2, d2, moved2);  // std::max(moved2, d2), lane by lane
  }
}

}  // namespace spread::dem::pairs

#pragma GCC diagnostic pop
