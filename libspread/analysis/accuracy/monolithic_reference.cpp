// The monolithic reference flight (seed Sect. 3.1) beside a disc run.
#include "libspread/analysis/accuracy/monolithic_reference.hpp"

#include <chrono>
#include <cmath>

#include "libspread/physics/flight/flight.hpp"

namespace spread::accuracy {

void MonolithicFlight::after_step(const dem::DemEngine& engine) {
  const std::vector<dem::LaunchRecord>& launches = engine.launches();
  for (; joined_ < launches.size(); ++joined_) {
    const dem::LaunchRecord& l = launches[joined_];
    x_.push_back(l.position_m.x()); y_.push_back(l.position_m.y()); z_.push_back(l.position_m.z());
    vx_.push_back(l.velocity_m_s.x()); vy_.push_back(l.velocity_m_s.y()); vz_.push_back(l.velocity_m_s.z());
    d_.push_back(l.diameter_m); m_.push_back(l.mass_kg);
  }
  if (x_.empty()) return;
  const auto t0 = std::chrono::steady_clock::now();
  const double dt = engine.dt_s();
  const Vec3 g = engine.params().gravity_m_s2;
  std::size_t k = 0;
  while (k < x_.size()) {
    // Drag, Eq. 27 with C_D of Eq. 32, in still air: a = g − ½ ρ C_D (π d²/4) |v| v / m.
    const double speed = std::sqrt(vx_[k] * vx_[k] + vy_[k] * vy_[k] + vz_[k] * vz_[k]);
    double ax = g.x(), ay = g.y(), az = g.z();
    if (speed > 0.0) {
      const double re = air_.density_kg_m3 * d_[k] * speed / air_.viscosity_pa_s;
      const double cd = flight::drag_coefficient(re);
      const double c = 0.5 * air_.density_kg_m3 * cd * 0.25 * kPi * d_[k] * d_[k] * speed / m_[k];
      ax -= c * vx_[k]; ay -= c * vy_[k]; az -= c * vz_[k];
    }
    // Symplectic Euler (seed Eq. 41): v first, then x with the new v.
    vx_[k] += dt * ax; vy_[k] += dt * ay; vz_[k] += dt * az;
    x_[k] += dt * vx_[k]; y_[k] += dt * vy_[k]; z_[k] += dt * vz_[k];
    ++flight_particle_steps_;
    if (z_[k] <= ground_z_m_) {
      landings_.emplace_back(x_[k], y_[k], z_[k]);
      for (auto* v : {&x_, &y_, &z_, &vx_, &vy_, &vz_, &d_, &m_}) {
        (*v)[k] = v->back();
        v->pop_back();
      }
      continue;
    }
    ++k;
  }
  flight_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void MonolithicFlight::after_duration(dem::DemEngine& engine) {
  // Only the launched granules fly on, as in the partitioned run (whose flight starts at launch).
  engine.drop_on_disc_particles();
  while (landings_.size() < engine.launches().size() && engine.time_s() < give_up_at_s_) {
    engine.step();
    after_step(engine);
  }
}

PartitionSaving predicted_saving(const dem::SimulationResult& part) {
  const double n = static_cast<double>(part.launches.size());
  PartitionSaving s;
  for (std::size_t k = 0; k < part.launches.size(); ++k) {
    s.t_c_s += part.launches[k].residence_s;
    s.t_f_s += part.landings[k].flight_time_s;
  }
  s.t_c_s /= n;
  s.t_f_s /= n;
  const double flight_steps_per_granule = static_cast<double>(part.flight_steps) / n;
  s.n_fc = (s.t_f_s / flight_steps_per_granule) / part.dt_contact_s;
  s.c_r = (1.0 - 1.0 / s.n_fc) / (1.0 + s.t_c_s / s.t_f_s);
  return s;
}

MonolithicResult simulate_monolithic(const dem::SimulationConfig& config) {
  MonolithicFlight flight(-config.disc_height_m, config.air, config.duration_s + 30.0);
  MonolithicResult out;
  out.run = dem::simulate(config, &flight);
  out.run.module_time_s["monolithic_flight"] = flight.flight_s();
  out.landings = flight.landings();
  out.flight_particle_steps = flight.flight_particle_steps();
  return out;
}

}  // namespace spread::accuracy
