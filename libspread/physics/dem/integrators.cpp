// The step and its integrator families: symplectic Euler (seed Eq. 41), velocity Verlet, and the Gear
// predictor–corrector (gear_predictor_corrector.hpp); the kicks and drifts over the flat arrays, and the
// periodic wrap after the step.
#include <algorithm>
#include <cstddef>
#include <cstdint>

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
  kick_drift(dt_s_, dt_s_, false);  // Eq. 41: v from the forces at t, then x with the new v
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
  const bool drifted = drifted_in_pass_;
  drifted_in_pass_ = false;
  // v(t + Δt/2) = v(t) + Δt/2 a(t), x(t + Δt) = x(t) + Δt v(t + Δt/2), then a(t + Δt) and
  // v(t + Δt) = v(t + Δt/2) + Δt/2 a(t + Δt). The forces at t are those of the previous step's end.
  if (!forces_valid_) {
    maintain_lists();
    compute_forces();
  }
  auto t0 = Clock::now();
  // The previous step's pass may have given this step's opening kick and drift (steps()).
  if (!drifted) {
    kick_drift(0.5 * dt_s_, dt_s_, opening_kick_clears_sums());
    stats_.integrate_s += seconds_since(t0);
  }
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

bool DemEngine::opening_kick_clears_sums() const {
  // The forces at t are not read again: on one thread the kick leaves the sums at zero, where the force
  // evaluation would otherwise zero them in a pass of its own — without wall contacts, or with walls on the
  // wall list (fixed in space, kept with the pair list); other walls are looked at for every particle, which
  // zeroes the sums anyway. Where threads share the particles, the wall pass zeroes them, each thread its own
  // range (the wall list's particles are too few to share: one thread would write into the other's range).
  const bool walls_listed = walls_fixed_in_space_ && params_.has(effect::kParticleContact);
  return !threads_share_pairs() && (!params_.has(effect::kWallContact) || walls_listed);
}

void DemEngine::steps(std::size_t n) {
  // Between two of these steps only the wrap, the monitor and the collector would run; without them the
  // next step's opening kick and drift may go with this step's pass (Verlet only: the others' passes do
  // not kick).
  const bool fusable = params_.integrator == Integrator::kVelocityVerlet && monitor_ == nullptr && !collects() &&
                       !params_.periodic_z.enabled;
  struct Reset {
    bool& flag;
    ~Reset() { flag = false; }
  } reset{fuse_next_step_};
  for (std::size_t k = 0; k < n; ++k) {
    fuse_next_step_ = fusable && k + 1 < n;
    step();
  }
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

void DemEngine::kick_drift(double dt_kick, double dt_drift, bool clear_sums) {
  if (p_.with_spin) {
    if (clear_sums) kick_drift_pass<true, true>(dt_kick, dt_drift);
    else kick_drift_pass<true, false>(dt_kick, dt_drift);
  } else {
    if (clear_sums) kick_drift_pass<false, true>(dt_kick, dt_drift);
    else kick_drift_pass<false, false>(dt_kick, dt_drift);
  }
  sums_cleared_ = clear_sums;
}

namespace {

// The flat arrays kick_drift_pass reads and writes, by value in each thread (shared, GCC would reload
// them through the parallel region's argument block at every store).
struct KickDriftArrays {
  double *x, *y, *z, *vx, *vy, *vz, *wx, *wy, *wz;
  double *fx, *fy, *fz, *tx, *ty, *tz;
  const double *inv_mass, *inv_inertia;
  const std::uint8_t* active;
  const double *xn, *yn, *zn;  // positions at the near list's build (null: the move is not measured)
  double gravity_m_s2[3];
  double period_m;  // 0: no periodic axis
};

// Particles [begin, end): the kick, the drift, and the largest squared move since the near build (m²);
// kClearSums: the force and torque sums zeroed once read (their lines are in cache here; a pass of its own
// would stream them through the core again).
template <bool kSpin, bool kClearSums>
double kick_drift_range(const KickDriftArrays& k, double dt_kick, double dt_drift, std::size_t begin, std::size_t end) {
  double moved2_near = 0.0;
  for (std::size_t i = begin; i < end; ++i) {
    if (k.active[i]) {
      const double inv_m = k.inv_mass[i];
      k.vx[i] += dt_kick * (k.fx[i] * inv_m + k.gravity_m_s2[0]);
      k.vy[i] += dt_kick * (k.fy[i] * inv_m + k.gravity_m_s2[1]);
      k.vz[i] += dt_kick * (k.fz[i] * inv_m + k.gravity_m_s2[2]);
      if constexpr (kSpin) {
        const double inv_i = k.inv_inertia[i];
        k.wx[i] += dt_kick * k.tx[i] * inv_i;
        k.wy[i] += dt_kick * k.ty[i] * inv_i;
        k.wz[i] += dt_kick * k.tz[i] * inv_i;
      }
    }
    if constexpr (kClearSums) {
      k.fx[i] = k.fy[i] = k.fz[i] = 0.0;
      if constexpr (kSpin) k.tx[i] = k.ty[i] = k.tz[i] = 0.0;
    }
    k.x[i] += dt_drift * k.vx[i];
    k.y[i] += dt_drift * k.vy[i];
    k.z[i] += dt_drift * k.vz[i];
    if (k.xn != nullptr) {
      const double dx = k.x[i] - k.xn[i], dy = k.y[i] - k.yn[i];
      double dz = k.z[i] - k.zn[i];
      if (k.period_m > 0.0) dz = minimum_image_z(dz, k.period_m);  // a wrap is not a move
      moved2_near = std::max(moved2_near, dx * dx + dy * dy + dz * dz);
    }
  }
  return moved2_near;
}

}  // namespace

template <bool kSpin, bool kClearSums>
void DemEngine::kick_drift_pass(double dt_kick, double dt_drift) {
  // kick(dt_kick), then x += dt_drift v, and the largest squared move since the near list's last build
  // (which maintain_lists would otherwise measure in a pass of its own): one pass over the particles.
  // Each quantity is computed as kick, kick_spin and max_displacement2 compute it.
  const std::size_t n = p_.size();
  // x0 is sized at the first build; before it the move is measured by maintain_lists as before.
  const bool measure_near = near_.x0.size() == n;
  const auto near_or_null = [&](const std::vector<double>& v) { return measure_near ? v.data() : nullptr; };
  const KickDriftArrays k{.x = p_.x.data(), .y = p_.y.data(), .z = p_.z.data(),
                          .vx = p_.vx.data(), .vy = p_.vy.data(), .vz = p_.vz.data(),
                          .wx = p_.wx.data(), .wy = p_.wy.data(), .wz = p_.wz.data(),
                          .fx = p_.fx.data(), .fy = p_.fy.data(), .fz = p_.fz.data(),
                          .tx = p_.tx.data(), .ty = p_.ty.data(), .tz = p_.tz.data(),
                          .inv_mass = p_.inv_mass_kg.data(), .inv_inertia = p_.inv_inertia_kg_m2.data(),
                          .active = p_.active.data(),
                          .xn = near_or_null(near_.x0), .yn = near_or_null(near_.y0), .zn = near_or_null(near_.z0),
                          .gravity_m_s2 = {params_.gravity_m_s2.x(), params_.gravity_m_s2.y(), params_.gravity_m_s2.z()},
                          .period_m = params_.periodic_z.enabled ? params_.periodic_z.length_m() : 0.0};
  // Where the pair pass shares its pairs among threads, each thread takes the particles of one of as many
  // consecutive ranges, so that they stay in its cache for the pair pass. These ranges are equal in
  // particles, the pair pass's equal in listed pairs: the same on an even bed, apart where the density varies.
  double moved2_near = 0.0;
  if (threads_share_pairs()) {
#pragma omp parallel num_threads(params_.threads) firstprivate(k) reduction(max : moved2_near)
    {
      const std::size_t t = static_cast<std::size_t>(detail::thread_index());
      const std::size_t threads = static_cast<std::size_t>(detail::thread_count());
      moved2_near = std::max(moved2_near, kick_drift_range<kSpin, kClearSums>(k, dt_kick, dt_drift, n * t / threads, n * (t + 1) / threads));
    }
  } else {
    moved2_near = kick_drift_range<kSpin, kClearSums>(k, dt_kick, dt_drift, 0, n);
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
