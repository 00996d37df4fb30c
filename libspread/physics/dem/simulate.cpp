#include "libspread/physics/dem/simulate.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "libspread/physics/dem/disc_run.hpp"
#include "libspread/physics/dem/vtk_writer.hpp"
#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::dem {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

LaunchSummary summarise_launches(const std::vector<LaunchRecord>& launches, const Vec3& axis) {
  LaunchSummary s;
  if (launches.empty()) return s;
  const double n = static_cast<double>(launches.size());
  double sum = 0.0, sum2 = 0.0, tang = 0.0, elev = 0.0;
  for (const auto& l : launches) {
    const double speed = l.velocity_m_s.norm();
    sum += speed;
    sum2 += speed * speed;
    const Vec3 er = Vec3(l.position_m.x() - axis.x(), l.position_m.y() - axis.y(), 0.0).normalized();
    // Tangent in the direction of the horizontal velocity's tangential part (either spin sense).
    Vec3 et(-er.y(), er.x(), 0.0);
    double vt = l.velocity_m_s.dot(et);
    if (vt < 0.0) { et = -et; vt = -vt; }
    const double vr = l.velocity_m_s.dot(er);
    tang += std::atan2(vr, vt) * 180.0 / kPi;
    elev += std::atan2(l.velocity_m_s.z(), std::hypot(vr, vt)) * 180.0 / kPi;
  }
  s.speed_mean = sum / n;
  s.speed_sd = n > 1 ? std::sqrt(std::max(0.0, (sum2 - n * s.speed_mean * s.speed_mean) / (n - 1.0))) : 0.0;
  s.angle_from_tangent_deg_mean = tang / n;
  s.elevation_deg_mean = elev / n;
  return s;
}

std::array<double, 12> sector_mass_fraction(const std::vector<LaunchRecord>& launches, const Vec3& axis) {
  std::array<double, 12> f{};
  double total = 0.0;
  for (const auto& l : launches) {
    double a = std::atan2(l.position_m.y() - axis.y(), l.position_m.x() - axis.x());
    if (a < 0.0) a += 2.0 * kPi;
    const int k = std::min(11, static_cast<int>(a / (kPi / 6.0)));
    f[static_cast<std::size_t>(k)] += l.mass_kg;
    total += l.mass_kg;
  }
  if (total > 0.0)
    for (auto& v : f) v /= total;
  return f;
}

void write_launch_csv(const std::vector<LaunchRecord>& launches, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write launch CSV '" + path + "'");
  std::fprintf(f, "id,time_s,residence_s,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,wz_rad_s,diameter_m,mass_kg,material\n");
  for (const auto& l : launches)
    std::fprintf(f, "%u,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n", l.id, l.time_s,
                 l.residence_s, l.position_m.x(), l.position_m.y(), l.position_m.z(), l.velocity_m_s.x(),
                 l.velocity_m_s.y(), l.velocity_m_s.z(), l.spin_rad_s.x(), l.spin_rad_s.y(), l.spin_rad_s.z(),
                 l.diameter_m, l.mass_kg, l.material);
  std::fclose(f);
}

namespace {

// The DEM until the run's duration, with the VTK snapshots it asks for; returns the time spent writing them.
double run_disc(const SimulationConfig& cfg, DiscRun& run, RunExtension* extension) {
  DemEngine& engine = run.engine();
  const bool write_vtk = !cfg.vtk_prefix.empty() && cfg.vtk_every_steps > 0;
  const bool write_walls_vtk_files = write_vtk && !cfg.vtk_walls_prefix.empty();
  double vtk_s = 0.0;
  std::uint64_t step = 0;
  while (run.before(cfg.duration_s)) {
    run.step();
    if (extension != nullptr) extension->after_step(engine);
    ++step;
    if (write_vtk && step % static_cast<std::uint64_t>(cfg.vtk_every_steps) == 0) {
      const auto t0 = Clock::now();
      char name[64];
      std::snprintf(name, sizeof name, "_%09llu.vtk", static_cast<unsigned long long>(step));
      write_particles_vtk(engine.particles(), cfg.vtk_prefix + name);
      if (write_walls_vtk_files) write_walls_vtk(engine.walls(), engine.time_s(), cfg.vtk_walls_prefix + name);
      vtk_s += since(t0);
    }
  }
  return vtk_s;
}

// What the DEM run leaves: its launches and their summary, counts, the energy report and module times.
void record_disc_run(const SimulationConfig& cfg, const DiscRun& run, const EnergyMonitor* monitor, SimulationResult& res) {
  const DemEngine& engine = run.engine();
  const EngineStats& st = engine.stats();
  res.engine_stats = st;
  if (monitor != nullptr) {
    res.energy_monitored = true;
    res.energy = monitor->report();
    res.energy_samples = monitor->samples();
  }
  res.launches = engine.launches();
  res.released = run.inlet().released();
  res.lost = st.lost;
  res.particle_steps = st.particle_steps;
  res.module_time_s["inlet"] = run.inlet_s();
  if (cfg.engine.has(effect::kParticleContact)) res.module_time_s["dem_pair_search"] = st.pair_search_s;
  res.module_time_s["dem_forces"] = st.forces_s;
  res.module_time_s["dem_integrate"] = st.integrate_s;
  res.module_time_s["dem_collector"] = st.collector_s;
  const Vec3 axis = Vec3::Zero();
  res.launch = summarise_launches(res.launches, axis);
  res.sector_mass_fraction = sector_mass_fraction(res.launches, axis);
  res.effects = effect::names_in(cfg.engine.effects);
}

// The launches flown to the ground (the partitioned scheme's flight module) and their radial statistics.
void fly_launches(const SimulationConfig& cfg, SimulationResult& res) {
  auto t0 = Clock::now();
  std::vector<flight::Granule> granules(res.launches.size());
  std::vector<flight::State> states(res.launches.size());
  for (std::size_t k = 0; k < res.launches.size(); ++k) {
    const auto& l = res.launches[k];
    granules[k].diameter_m = l.diameter_m;
    granules[k].density_kg_m3 = cfg.materials[static_cast<std::size_t>(l.material)].density_kg_m3;
    states[k].position_m = l.position_m;
    states[k].velocity_m_s = l.velocity_m_s;
    states[k].spin_rad_s = l.spin_rad_s;
  }
  res.landings.resize(res.launches.size());
  flight::fly_batch(granules, states, -cfg.disc_height_m, cfg.air, cfg.flight_effects, cfg.flight_settings, res.landings,
                    cfg.flight_threads);
  for (const auto& l : res.landings) res.flight_steps += static_cast<std::uint64_t>(l.steps);
  res.module_time_s["flight"] = since(t0);
  for (std::string& name : effect::names_in(cfg.flight_effects & effect::kFlightEffects)) res.effects.push_back(std::move(name));
  t0 = Clock::now();
  std::vector<double> x, y, m;
  for (std::size_t k = 0; k < res.landings.size(); ++k) {
    if (!res.landings[k].landed) continue;
    x.push_back(res.landings[k].state.position_m.x());
    y.push_back(res.landings[k].state.position_m.y());
    m.push_back(res.launches[k].mass_kg);
  }
  if (!m.empty()) {
    const auto rs = metrics::radial_statistics(x, y, m, 0.0, 0.0);
    res.mean_radius_m = rs.mean_radius_m;
    res.radial_width_m = rs.radial_width_m;
  }
  res.module_time_s["metrics"] = since(t0);
}

}  // namespace

SimulationResult simulate(const SimulationConfig& cfg, RunExtension* extension) {
  const auto t_start = Clock::now();
  if (cfg.materials.empty()) throw std::invalid_argument("simulate: no materials");
  if (!(cfg.duration_s > 0.0)) throw std::invalid_argument("simulate: duration_s must be > 0");
  if (!(cfg.disc_height_m >= 0.0)) throw std::invalid_argument("simulate: disc_height_m must be >= 0");
  if (cfg.energy_monitor_every_steps < 0)
    throw std::invalid_argument("simulate: energy_monitor_every_steps must be >= 0 (0 = off)");
  SimulationResult res;
  const auto t0 = Clock::now();
  DiscRun run(cfg);
  DemEngine& engine = run.engine();
  res.module_time_s["disc_generator"] = since(t0);  // the disc's walls and the engine set up
  std::unique_ptr<EnergyMonitor> monitor;
  if (cfg.energy_monitor_every_steps > 0) {
    monitor = std::make_unique<EnergyMonitor>(cfg.energy_monitor_every_steps);
    engine.set_energy_monitor(monitor.get());
  }
  res.dt_contact_s = engine.dt_s();
  res.contact_time_s = engine.contact_time_s();
  const double vtk_s = run_disc(cfg, run, extension);
  res.on_disc_at_end = engine.active_count();
  if (extension != nullptr) extension->after_duration(engine);
  record_disc_run(cfg, run, monitor.get(), res);
  if (vtk_s > 0.0) res.module_time_s["vtk"] = vtk_s;
  if (cfg.fly && !res.launches.empty()) fly_launches(cfg, res);
  res.wall_time_s = since(t_start);
  return res;
}

}  // namespace spread::dem
