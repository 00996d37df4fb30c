#pragma once
// The pair pass's context: the pass's own view of the engine (PairPassArrays: flat arrays, nothing else),
// its forms (PairForm), a particle's range of pairs and the particle as its pairs read it (FirstBody). The
// engine fills the arrays by name (pair_pass.cpp, DemEngine::pair_pass_arrays); the stages
// (pair_pass_stages.hpp, pair_pass_avx512.hpp, pair_kicks.hpp) read nothing else.
#include <cstddef>
#include <cstdint>

#include "libspread/physics/dem/contact_kernel.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"
#include "libspread/physics/dem/material.hpp"
#include "libspread/physics/dem/lanes.hpp"

namespace spread::dem::pairs {

using detail::kMinParallelItems;
using lanes::Lanes2;
using lanes::pack;
using lanes::splat;
using lanes::V3;

// The pass's forms, one template argument: per-pair results stored for a gather (threads, an energy
// monitor) or added straight into the sums; along a periodic z axis (minimum image) or not; with the next
// step's opening kick and drift (drift: direct form only, PairPassArrays::drift_dt_s) or without, so that
// the passes without it carry none of its code.
struct PairForm {
  bool store_pairs;
  bool periodic;
  bool drift;
};

// What the pass reads and writes, as flat arrays taken once outside the loop (the vectors' bounds and
// sizes do not change within the pass). Copied into each thread (firstprivate): shared, its pointers were
// read through the parallel region's argument block, and since a byte store (held) may alias anything,
// GCC reloaded them for every listed pair.
template <class Law>
struct PairPassArrays {
  const double *x, *y, *z, *vx, *vy, *vz, *wx, *wy, *wz, *radius, *mass, *inertia;
  const std::uint16_t* material;
  const std::uint8_t* active;
  const std::uint32_t *pair_start, *partner;
  double* history;
  std::uint8_t* held;
  double *pair_force, *pair_torque_i, *pair_torque_j;  // per pair (stored form)
  PairSum* sums;                                       // per particle
  double *fx, *fy, *fz, *tx, *ty, *tz;                 // the particles' force sums (the wall pass started them)
  const PairParams* params;                            // material pair table, row-major
  const typename Law::Coeffs* coeffs;                  // Law::coeffs per material pair
  std::size_t material_count;
  double period_m, dt_s;
  // Velocity Verlet's closing half kick, applied to each particle as its sums complete (the data are
  // still in cache; DemEngine::kick would read them all again): Δt/2 (s), 0 when the step has no kick here.
  double kick_dt_s;
  double gravity_m_s2[3];
  const double *inv_mass, *inv_inertia;
  double *kick_v[3], *kick_w[3];  // the velocities and spins the kick writes (the same arrays as vx… wz)
  // The pairs the direct pass looks at: entries [near_start[i], near_start[i + 1]) of near_pairs, each a
  // pair index (the near list, neighbor_list.hpp); null: all of i's listed pairs (the stored form).
  const std::uint32_t *near_start, *near_pairs;
  // The near list's bodies per entry and the bodies' touch rows (x, y, z, r; r NaN when inactive): the batched
  // pass's touch test, eight entries a register (null: one entry at a time). The drift form brings both
  // kinds of rows to the new positions and velocities as it moves each particle (the next pass then reads
  // them as they are); a particle's rows are read last by its own batch's stages 1 and 2.
  const std::uint32_t *near_first, *near_second;
  double* touch_rows;
  double* law_rows;  // the bodies' law rows (vx, vy, vz, wx, wy, wz, r, I), with touch_rows
  std::uint8_t* near_held;  // NearList::held, kept with `held` by the pass that reads the touch rows
  // The next step's opening half kick and drift, applied right after the closing kick when nothing comes
  // between the two steps (DemEngine::steps), by the passes of form drift: Δt of the drift (s). Both kicks
  // take the same forces and the same Δt/2, so the opening one adds the closing one's increment again.
  // drift_clears_sums: the sums are left at zero for the next step's force evaluation, as kick_drift's
  // clear_sums leaves them (otherwise its wall pass zeroes them, and they are not written here); x0…: the
  // positions at the near list's build, for the largest move since (null: not measured).
  double drift_dt_s;
  bool drift_clears_sums;
  double* position[3];
  const double *x0, *y0, *z0;
};

// Particle i's pairs to look at: entries [begin, end) of `at` (null: the pair indices themselves).
struct PairRange {
  const std::uint32_t* at;
  std::uint32_t begin, end;
  std::uint32_t operator[](std::uint32_t e) const { return at != nullptr ? at[e] : e; }
};
template <class Law>
SPREAD_CONTACT_INLINE PairRange pairs_of(const PairPassArrays<Law>& a, std::size_t i) {
  if (a.near_start != nullptr) return {a.near_pairs, a.near_start[i], a.near_start[i + 1]};
  return {nullptr, a.pair_start[i], a.pair_start[i + 1]};
}

// Particle i as its pairs read it (it is `first` in all of them), and its share of its pairs, summed from
// zero in pair order.
template <class Law>
struct FirstBody {
  std::size_t i;
  double x, y, z;  // position (m)
  double r, m;     // radius (m), mass (kg)
  V3<double> v, w;  // velocity (m/s), spin (rad/s)
  bool active;
  const PairParams* params_row;
  const typename Law::Coeffs* coeffs_row;
  double sum_f[3], sum_t[3];  // force (N), torque (N m)
};

template <class V>
SPREAD_CONTACT_INLINE FirstBody<typename V::Law> first_body(const PairPassArrays<typename V::Law>& a, std::size_t i) {
  const std::size_t row = static_cast<std::size_t>(a.material[i]) * a.material_count;
  FirstBody<typename V::Law> b{.i = i, .x = a.x[i], .y = a.y[i], .z = a.z[i], .r = a.radius[i], .m = a.mass[i],
                               .v = V3<double>{a.vx[i], a.vy[i], a.vz[i]}, .w = V3<double>{0.0, 0.0, 0.0},
                               .active = a.active[i] != 0, .params_row = a.params + row, .coeffs_row = a.coeffs + row,
                               .sum_f = {0.0, 0.0, 0.0}, .sum_t = {0.0, 0.0, 0.0}};
  if constexpr (V::kRotation) b.w = V3<double>{a.wx[i], a.wy[i], a.wz[i]};
  return b;
}

}  // namespace spread::dem::pairs
