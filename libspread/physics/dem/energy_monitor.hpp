#pragma once
// Energy and penetration diagnostics of a DEM run. Attached to a DemEngine
// (DemEngine::set_energy_monitor), it is called twice per step — before the step and after its forces
// and integration, before the collector removes launched particles — and keeps an exact per-step
// energy budget of the granules on the disc:
//
//   kinetic  T = Σ ½ m v² + ½ I ω²                         (translation + rotation)
//   elastic  U = Σ_contacts U_n + U_t                      (Hertz: U_n = 8/15 E* √R* δ^{5/2}, the
//                                                            integral of Eq. 16; linear: ½ k_n δ²;
//                                                            tangential spring U_t = |F_t,el|² / (2 k_t))
//   disc work     W_d += Δt · ω τ_z,  τ_z = Σ_i ẑ·[(x_i − c) × F_wall,i + M_wall,i]
//                 (torque·ω of the spinning wall group on the granules; F_wall,i and M_wall,i are the
//                  particle's force and moment minus its particle–particle share)
//   gravity work  W_g += Σ m g·(x_end − x_begin)           (over the same particles in one step)
//   dissipated    D  += W_d + W_g − Δ(T + U)               (per step, exact bookkeeping)
//
// Every contact law in the engine is dissipative (damping, Coulomb slip), so D may only grow. The
// "energy created" is the largest drop of the cumulative D at any step (checked every step); the balance
// residual is that drop over the energy put in (initial T + U, T of granules added, W_d, W_g > 0 parts).
// It measures energy that the time discretisation (or an unstable contact) creates — symplectic Euler
// at N_c steps per contact trades energy between T and U within each contact by O(π/N_c).
// Granules entering and leaving between steps (inlet, collector) are booked as "added" and
// "launched"; launched granules' energy comes from the engine's launch records.
//
// The maximum penetration ratio is max δ/R over every wall contact (R the granule's radius) and every
// particle pair (R the smaller radius), from the overlaps the force pass stored (contact history).
//
// Off (no monitor attached) it costs the engine two null-pointer tests per step. On, it costs two passes
// over the particles, pairs and wall-contact slots per step. Samples of the time series are kept every
// `sample_every_steps` steps; the budget and the maxima are exact over every step regardless.
//
// Scope: the disc work needs the wall force split per wall group, which the engine sums per particle;
// the monitor therefore refuses a wall set with a moving group next to any other group. Exact for the
// symplectic Euler integrator (the forces of a step act over that step); with velocity Verlet and Gear the
// power is taken with the end-of-step forces (one step of lag, O(Δt/t_c) of each contact's work).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/material.hpp"

namespace spread::dem {

class DemEngine;

struct EnergySample {
  double time_s = 0.0;
  std::size_t particles = 0;
  double kinetic_j = 0.0;               // translation + rotation
  double elastic_j = 0.0;               // contact springs, normal + tangential
  double potential_j = 0.0;             // −Σ m g·x (zero at the origin)
  double disc_work_j = 0.0;             // cumulative
  double gravity_work_j = 0.0;          // cumulative
  double dissipated_j = 0.0;            // cumulative
  double max_penetration_ratio = 0.0;   // max δ/R since the previous sample
};

struct EnergyReport {
  std::uint64_t steps = 0;
  double initial_kinetic_j = 0.0, initial_elastic_j = 0.0;
  double kinetic_j = 0.0, elastic_j = 0.0;  // now
  double disc_work_j = 0.0;                 // ∫ ω τ_z dt
  double gravity_work_j = 0.0;              // Σ m g·Δx
  double added_kinetic_j = 0.0;             // T of granules added between steps (inlet)
  double launched_kinetic_j = 0.0;          // T of granules the collector removed (launch records)
  double dissipated_j = 0.0;                // cumulative D
  double energy_input_j = 0.0;              // initial T + U, added T, and the positive parts of W_d and W_g per step
  double energy_created_j = 0.0;            // largest drop of the cumulative D (0 if it never fell)
  double max_penetration_ratio = 0.0;       // max δ/R over every contact of every step
  double balance_residual() const { return energy_input_j > 0.0 ? energy_created_j / energy_input_j : 0.0; }
};

class EnergyMonitor {
 public:
  // sample_every_steps >= 1: keep one EnergySample every that many steps.
  explicit EnergyMonitor(int sample_every_steps = 100);

  // Called by the engine (DemEngine::step); not for other callers.
  void begin_step(const DemEngine& engine);
  void end_step(const DemEngine& engine);

  const EnergyReport& report() const { return report_; }
  const std::vector<EnergySample>& samples() const { return samples_; }

 private:
  struct Totals {
    double kinetic_j = 0.0, elastic_j = 0.0, potential_j = 0.0;
    double max_penetration_ratio = 0.0;
    std::size_t particles = 0;
  };
  void attach(const DemEngine& engine);
  Totals measure(const DemEngine& engine) const;
  double disc_power_w(const DemEngine& engine);
  double spring_energy_j(const PairParams& pair, double r_eff_m, const double* history) const;

  int sample_every_steps_ = 100;
  bool attached_ = false;
  bool have_end_ = false;
  PairTable pair_table_;  // E*, G*, linear springs: what the springs' energy needs (no overrides touch them)
  ContactLaw law_ = kHertzThorntonLaw;
  Totals begin_{}, end_{};
  std::size_t launches_seen_ = 0;
  double dissipated_peak_j_ = 0.0;
  double sample_max_ratio_ = 0.0;
  // Per-particle scratch: the particle–particle share of the horizontal force and of the vertical
  // moment, to split off the wall part.
  std::vector<double> pair_fx_, pair_fy_, pair_mz_;
  EnergyReport report_;
  std::vector<EnergySample> samples_;
};

}  // namespace spread::dem
