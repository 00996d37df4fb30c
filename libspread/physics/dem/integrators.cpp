// The step and its integrator families: symplectic Euler (seed Eq. 41), velocity Verlet, and the Gear
// predictor–corrector (gear_predictor_corrector.hpp); the kicks and drifts over the flat arrays, and the
// periodic wrap after the step.
#include <algorithm>

#include "libspread/physics/dem/energy_monitor.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"

namespace spread::dem {

using detail::Clock;
using detail::seconds_since;

void DemEngine::step() {
  if (monitor_ != nullptr) monitor_->begin_step(*this);
  switch (params_.integrator) {
    case Integrator::kSymplecticEuler: step_symplectic_euler(); break;
    case Integrator::kVelocityVerlet: step_velocity_verlet(); break;
    case Integrator::kGear4:
    case Integrator::kGear5:
    case Integrator::kGear6: step_gear(); break;
  }
  if (params_.periodic_z.enabled) wrap_periodic_z();
  stats_.particle_steps += active_count();
  ++stats_.steps;
  time_s_ += dt_s_;
  if (monitor_ != nullptr) monitor_->end_step(*this);  // before the collector removes launched particles
  collect();
}

void DemEngine::step_symplectic_euler() {
  maintain_lists();
  compute_forces();
  const auto t0 = Clock::now();
  kick_drift(dt_s_, dt_s_);  // Eq. 41: v from the forces at t, then x with the new v
  stats_.integrate_s += seconds_since(t0);
}

void DemEngine::step_gear() {
  // Gear: predict to t + Δt, one force evaluation there, correct (gear_predictor_corrector.hpp).
  if (gear_.needs_start(p_)) {  // particles were added: start values from the forces now
    maintain_lists();
    compute_forces();
    gear_.start(p_, params_.gravity_m_s2, dt_s_);
  }
  auto t0 = Clock::now();
  gear_.predict(p_, dt_s_);
  stats_.integrate_s += seconds_since(t0);
  forces_at_next_time();
  t0 = Clock::now();
  gear_.correct(p_, params_.gravity_m_s2, dt_s_);
  stats_.integrate_s += seconds_since(t0);
}

void DemEngine::step_velocity_verlet() {
  kick_in_pass_dt_s_ = 0.0;  // (left set if a force evaluation threw) no kick with the start-up forces
  // v(t + Δt/2) = v(t) + Δt/2 a(t), x(t + Δt) = x(t) + Δt v(t + Δt/2), then a(t + Δt) and
  // v(t + Δt) = v(t + Δt/2) + Δt/2 a(t + Δt). The forces at t are those of the previous step's end.
  if (!forces_valid_) {
    maintain_lists();
    compute_forces();
  }
  auto t0 = Clock::now();
  kick_drift(0.5 * dt_s_, dt_s_);
  stats_.integrate_s += seconds_since(t0);
  // The closing half kick goes with the particle–particle pass, each particle's as its sums complete
  // (pair_pass.cpp); without that pass, here.
  kick_in_pass_dt_s_ = 0.5 * dt_s_;
  kicked_in_pass_ = false;
  forces_at_next_time();
  kick_in_pass_dt_s_ = 0.0;
  if (!kicked_in_pass_) {
    t0 = Clock::now();
    kick(0.5 * dt_s_);
    stats_.integrate_s += seconds_since(t0);
  }
  forces_valid_ = true;
}

void DemEngine::forces_at_next_time() {
  // The positions are those of t + Δt already, so the walls must stand where they are at t + Δt too.
  time_s_ += dt_s_;
  maintain_lists();
  compute_forces();
  time_s_ -= dt_s_;
}

void DemEngine::kick(double dt) {
  // v += Δt (F/m + g), ω += Δt T/I with the stored 1/m, 1/I (no division per particle per step).
  const std::size_t n = p_.size();
  const Vec3 g = params_.gravity_m_s2;
  for (std::size_t i = 0; i < n; ++i) {
    if (!p_.active[i]) continue;
    const double inv_m = p_.inv_mass_kg[i];
    p_.vx[i] += dt * (p_.fx[i] * inv_m + g.x());
    p_.vy[i] += dt * (p_.fy[i] * inv_m + g.y());
    p_.vz[i] += dt * (p_.fz[i] * inv_m + g.z());
  }
  kick_spin(dt);
}

void DemEngine::kick_spin(double dt) {
  if (!p_.with_spin) return;
  const std::size_t n = p_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!p_.active[i]) continue;
    const double inv_i = p_.inv_inertia_kg_m2[i];
    p_.wx[i] += dt * p_.tx[i] * inv_i;
    p_.wy[i] += dt * p_.ty[i] * inv_i;
    p_.wz[i] += dt * p_.tz[i] * inv_i;
  }
}

void DemEngine::kick_drift(double dt_kick, double dt_drift) {
  if (p_.with_spin) kick_drift_pass<true>(dt_kick, dt_drift);
  else kick_drift_pass<false>(dt_kick, dt_drift);
}

template <bool kSpin>
void DemEngine::kick_drift_pass(double dt_kick, double dt_drift) {
  // kick(dt_kick), then x += dt_drift v, and the largest squared move since the near list's last build
  // (which maintain_lists would otherwise measure in a pass of its own): one pass over the particles.
  // Each quantity is computed as kick, kick_spin and max_displacement2 compute it.
  const std::size_t n = p_.size();
  const Vec3 g = params_.gravity_m_s2;
  double* const x = p_.x.data(); double* const y = p_.y.data(); double* const z = p_.z.data();
  double* const vx = p_.vx.data(); double* const vy = p_.vy.data(); double* const vz = p_.vz.data();
  double* const wx = p_.wx.data(); double* const wy = p_.wy.data(); double* const wz = p_.wz.data();
  const double* const fx = p_.fx.data(); const double* const fy = p_.fy.data(); const double* const fz = p_.fz.data();
  const double* const tx = p_.tx.data(); const double* const ty = p_.ty.data(); const double* const tz = p_.tz.data();
  const double* const inv_mass = p_.inv_mass_kg.data();
  const double* const inv_inertia = p_.inv_inertia_kg_m2.data();
  const std::uint8_t* const active = p_.active.data();
  const bool periodic = params_.periodic_z.enabled;
  const double period = params_.periodic_z.length_m();
  // x0 is sized at the first build; before it the move is measured by maintain_lists as before.
  const bool measure_near = near_.x0.size() == n;
  const double* const xn = near_.x0.data(); const double* const yn = near_.y0.data(); const double* const zn = near_.z0.data();
  double moved2_near = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (active[i]) {
      const double inv_m = inv_mass[i];
      vx[i] += dt_kick * (fx[i] * inv_m + g.x());
      vy[i] += dt_kick * (fy[i] * inv_m + g.y());
      vz[i] += dt_kick * (fz[i] * inv_m + g.z());
      if constexpr (kSpin) {
        const double inv_i = inv_inertia[i];
        wx[i] += dt_kick * tx[i] * inv_i;
        wy[i] += dt_kick * ty[i] * inv_i;
        wz[i] += dt_kick * tz[i] * inv_i;
      }
    }
    x[i] += dt_drift * vx[i];
    y[i] += dt_drift * vy[i];
    z[i] += dt_drift * vz[i];
    if (measure_near) {
      const double dx = x[i] - xn[i], dy = y[i] - yn[i];
      double dz = z[i] - zn[i];
      if (periodic) dz = minimum_image_z(dz, period);  // a wrap is not a move
      moved2_near = std::max(moved2_near, dx * dx + dy * dy + dz * dz);
    }
  }
  moved2_since_near_ = measure_near ? moved2_near : -1.0;
}

void DemEngine::wrap_periodic_z() {
  moved2_since_near_ = -1.0;  // measured before the wrap: maintain_lists measures again
  const PeriodicZ& pz = params_.periodic_z;
  const double period = pz.length_m();
  double* const z = p_.z.data();
  const std::size_t n = p_.size();
  // One period at most per step (a step moves far less than the period).
  for (std::size_t i = 0; i < n; ++i) {
    if (z[i] >= pz.max_m) z[i] -= period;
    else if (z[i] < pz.min_m) z[i] += period;
  }
}

}  // namespace spread::dem
