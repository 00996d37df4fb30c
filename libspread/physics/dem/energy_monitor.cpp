#include "libspread/physics/dem/energy_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "libspread/physics/dem/contact_kernel.hpp"
#include "libspread/physics/dem/engine.hpp"

namespace spread::dem {

EnergyMonitor::EnergyMonitor(int sample_every_steps) : sample_every_steps_(sample_every_steps) {
  if (sample_every_steps_ < 1)
    throw std::invalid_argument("energy monitor: sample_every_steps = " + std::to_string(sample_every_steps) +
                                " must be >= 1");
}

void EnergyMonitor::attach(const DemEngine& engine) {
  const WallSet& walls = engine.walls();
  std::size_t moving = 0;
  for (const auto& g : walls.groups) moving += g.angular_velocity_rad_s != 0.0 ? 1 : 0;
  if (moving > 0 && walls.groups.size() > 1)
    throw std::invalid_argument("energy monitor: the disc work needs the spinning wall group to be the only group; "
                                "this wall set has " + std::to_string(walls.groups.size()) + " groups, " +
                                std::to_string(moving) + " moving");
  law_ = engine.params().contact_law;
  pair_table_ = PairTable(engine.materials(), {}, law_, engine.params().linear);
  attached_ = true;
}

// Energy stored in one contact's springs, from the history the force pass left (contact_kernel.hpp,
// LawHistory: the elastic tangential force and the overlap δ of that evaluation).
double EnergyMonitor::spring_energy_j(const PairParams& pair, double r_eff_m, const double* history) const {
  const LawHistory<double> h = load_history(history);
  const double delta = h.overlap_m;
  if (!(delta > 0.0)) return 0.0;
  const double ft2 = h.elastic.x * h.elastic.x + h.elastic.y * h.elastic.y + h.elastic.z * h.elastic.z;
  // ∫ F dδ of Eq. 16: 4/3 E* √R* δ^{3/2} → 8/15 E* √R* δ^{5/2}; Thornton's spring k_t = 8 G* √(R* δ).
  const double sqrt_r_delta = std::sqrt(r_eff_m * delta);
  double normal = 0.0, k_t = 0.0;
  if (law_.normal == NormalModel::kHertz) normal = (8.0 / 15.0) * pair.e_star_pa * sqrt_r_delta * delta * delta;
  else if (law_.normal == NormalModel::kLinear) normal = 0.5 * pair.kn_linear_n_m * delta * delta;
  if (law_.tangential == TangentialModel::kThornton) k_t = 8.0 * pair.g_star_pa * sqrt_r_delta;
  else if (law_.tangential == TangentialModel::kLinear) k_t = pair.kt_linear_n_m;
  return normal + (k_t > 0.0 ? 0.5 * ft2 / k_t : 0.0);
}

EnergyMonitor::Totals EnergyMonitor::measure(const DemEngine& engine) const {
  const ParticleArrays& p = engine.particles();
  const Vec3 g = engine.params().gravity_m_s2;
  const WallSet& walls = engine.walls();
  Totals t;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!p.active[i]) continue;
    ++t.particles;
    const double m = p.mass_kg[i];
    t.kinetic_j += 0.5 * m * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    if (p.with_spin) t.kinetic_j += 0.5 * p.inertia_kg_m2[i] * (p.wx[i] * p.wx[i] + p.wy[i] * p.wy[i] + p.wz[i] * p.wz[i]);
    t.potential_j -= m * (g.x() * p.x[i] + g.y() * p.y[i] + g.z() * p.z[i]);
    // Wall contacts: each slot with a key holds the last evaluation's overlap and spring.
    const double r = p.radius_m[i];
    for (int s = 0; s < kWallSlots; ++s) {
      const std::size_t slot = i * kWallSlots + static_cast<std::size_t>(s);
      const std::uint32_t key = p.wall_key[slot];
      if (key == 0) continue;
      const double* h = &p.wall_history[slot * kHistoryDoubles];
      const std::size_t group = (key >> 24) - 1;  // wall_feature_key: (group + 1) << 24
      const int wall_material = group < walls.groups.size() ? walls.groups[group].material : 0;
      t.elastic_j += spring_energy_j(pair_table_(p.material[i], wall_material), r, h);
      t.max_penetration_ratio = std::max(t.max_penetration_ratio, load_history(h).overlap_m / r);
    }
  }
  const PairList& pairs = engine.pair_list();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const double* h = &pairs.history[k * kHistoryDoubles];
    const double overlap_m = load_history(h).overlap_m;
    if (!(overlap_m > 0.0)) continue;  // not touching: the pass reset the history
    const std::size_t i = pairs.first[k], j = pairs.second[k];
    if (i >= n || j >= n || !p.active[i] || !p.active[j]) continue;
    const double ri = p.radius_m[i], rj = p.radius_m[j];
    t.elastic_j += spring_energy_j(pair_table_(p.material[i], p.material[j]), ri * rj / (ri + rj), h);
    t.max_penetration_ratio = std::max(t.max_penetration_ratio, overlap_m / std::min(ri, rj));
  }
  return t;
}

// ω τ_z of the spinning group on the granules (W). The wall share of each particle's force and moment is
// the total minus the pair share (the pair pass stores each pair's force on `first` and both moments).
double EnergyMonitor::disc_power_w(const DemEngine& engine) {
  const WallSet& walls = engine.walls();
  if (walls.groups.size() != 1 || walls.groups[0].angular_velocity_rad_s == 0.0) return 0.0;
  const WallGroup& disc = walls.groups[0];
  const ParticleArrays& p = engine.particles();
  const PairList& pairs = engine.pair_list();
  const std::size_t n = p.size();
  pair_fx_.assign(n, 0.0);
  pair_fy_.assign(n, 0.0);
  pair_mz_.assign(n, 0.0);
  const bool moments = p.with_spin;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const std::size_t i = pairs.first[k], j = pairs.second[k];
    if (i >= n || j >= n) continue;
    pair_fx_[i] += pairs.force[k * 3];
    pair_fy_[i] += pairs.force[k * 3 + 1];
    pair_fx_[j] -= pairs.force[k * 3];
    pair_fy_[j] -= pairs.force[k * 3 + 1];
    if (moments) {
      pair_mz_[i] += pairs.torque_first[k * 3 + 2];
      pair_mz_[j] += pairs.torque_second[k * 3 + 2];
    }
  }
  // Symplectic Euler evaluated the forces at x − Δt v (the drift used the new velocity); the other
  // integrators leave the end-of-step forces in the arrays.
  const double back_s = engine.params().integrator == Integrator::kSymplecticEuler ? engine.dt_s() : 0.0;
  double tau_z = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!p.active[i]) continue;
    const double rx = p.x[i] - back_s * p.vx[i] - disc.centre_m.x();
    const double ry = p.y[i] - back_s * p.vy[i] - disc.centre_m.y();
    const double fx = p.fx[i] - pair_fx_[i], fy = p.fy[i] - pair_fy_[i];
    tau_z += rx * fy - ry * fx;
    if (moments) tau_z += p.tz[i] - pair_mz_[i];
  }
  return disc.angular_velocity_rad_s * tau_z;
}

void EnergyMonitor::begin_step(const DemEngine& engine) {
  if (!attached_) attach(engine);
  begin_ = measure(engine);
  // Launch records since the previous step: their kinetic energy left through the collector.
  const auto& launches = engine.launches();
  double launched_j = 0.0;
  for (std::size_t k = launches_seen_; k < launches.size(); ++k) {
    const LaunchRecord& l = launches[k];
    const double r = 0.5 * l.diameter_m;
    launched_j += 0.5 * l.mass_kg * l.velocity_m_s.squaredNorm() +
                  (engine.particles().with_spin ? 0.5 * 0.4 * l.mass_kg * r * r * l.spin_rad_s.squaredNorm() : 0.0);
  }
  launches_seen_ = launches.size();
  report_.launched_kinetic_j += launched_j;
  if (!have_end_) {
    report_.initial_kinetic_j = begin_.kinetic_j;
    report_.initial_elastic_j = begin_.elastic_j;
    report_.energy_input_j += begin_.kinetic_j + begin_.elastic_j;
  } else {
    // Between steps only the inlet adds and the collector removes: T_now = T_before + added − launched.
    const double added = begin_.kinetic_j - end_.kinetic_j + launched_j;
    report_.added_kinetic_j += added;
    report_.energy_input_j += std::max(0.0, added);
  }
}

void EnergyMonitor::end_step(const DemEngine& engine) {
  if (!attached_) attach(engine);
  const double disc_work = disc_power_w(engine) * engine.dt_s();
  end_ = measure(engine);
  const double gravity_work = begin_.potential_j - end_.potential_j;
  const double dissipated = disc_work + gravity_work - ((end_.kinetic_j + end_.elastic_j) - (begin_.kinetic_j + begin_.elastic_j));
  have_end_ = true;
  EnergyReport& r = report_;
  ++r.steps;
  r.disc_work_j += disc_work;
  r.gravity_work_j += gravity_work;
  r.energy_input_j += std::max(0.0, disc_work) + std::max(0.0, gravity_work);
  r.dissipated_j += dissipated;
  dissipated_peak_j_ = std::max(dissipated_peak_j_, r.dissipated_j);
  r.energy_created_j = std::max(r.energy_created_j, dissipated_peak_j_ - r.dissipated_j);
  r.kinetic_j = end_.kinetic_j;
  r.elastic_j = end_.elastic_j;
  const double ratio = std::max(begin_.max_penetration_ratio, end_.max_penetration_ratio);
  r.max_penetration_ratio = std::max(r.max_penetration_ratio, ratio);
  sample_max_ratio_ = std::max(sample_max_ratio_, ratio);
  if (r.steps % static_cast<std::uint64_t>(sample_every_steps_) == 0) {
    EnergySample s;
    s.time_s = engine.time_s();
    s.particles = end_.particles;
    s.kinetic_j = end_.kinetic_j;
    s.elastic_j = end_.elastic_j;
    s.potential_j = end_.potential_j;
    s.disc_work_j = r.disc_work_j;
    s.gravity_work_j = r.gravity_work_j;
    s.dissipated_j = r.dissipated_j;
    s.max_penetration_ratio = sample_max_ratio_;
    samples_.push_back(s);
    sample_max_ratio_ = 0.0;
  }
}

}  // namespace spread::dem
