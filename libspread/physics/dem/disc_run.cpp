// The disc run's set-up (walls, engine, collector, inlet) and its step.
#include "libspread/physics/dem/disc_run.hpp"

#include <chrono>
#include <stdexcept>
#include <utility>

#include "libspread/physics/dem/disc_generator.hpp"

namespace spread::dem {

namespace {
WallSet disc_walls(const SimulationConfig& cfg, double max_particle_radius_m) {
  WallSet walls;
  walls.groups.push_back(make_disc(cfg.disc, cfg.rpm, cfg.disc_material, max_particle_radius_m));
  return walls;
}

double inlet_density_kg_m3(const SimulationConfig& cfg) {
  if (cfg.inlet.material < 0 || static_cast<std::size_t>(cfg.inlet.material) >= cfg.materials.size())
    throw std::invalid_argument("disc run: the inlet's material index is not one of the materials");
  return cfg.materials[static_cast<std::size_t>(cfg.inlet.material)].density_kg_m3;
}
}  // namespace

Collector disc_collector(const SimulationConfig& cfg) {
  Collector c;
  c.enabled = true;
  c.radius_m = cfg.collector_radius_m > 0.0 ? cfg.collector_radius_m : cfg.disc.radius_m;
  c.lost_below_z_m = cfg.disc.z_apex_m - kFallenBelowApex_m;
  return c;
}

EngineParams disc_engine_params(const SimulationConfig& cfg) {
  const auto [min_m, max_m] = inlet_diameter_range_m(cfg.inlet);
  EngineParams ep = cfg.engine;
  ep.min_particle_radius_m = 0.5 * min_m;
  ep.max_particle_radius_m = 0.5 * max_m;
  return ep;
}

DiscRun::DiscRun(const SimulationConfig& cfg) : DiscRun(cfg, disc_engine_params(cfg)) {}

DiscRun::DiscRun(const SimulationConfig& cfg, const EngineParams& engine_params)
    : engine_(cfg.materials, cfg.overrides, disc_walls(cfg, engine_params.max_particle_radius_m), engine_params),
      inlet_(cfg.inlet, inlet_density_kg_m3(cfg)) {
  engine_.set_collector(disc_collector(cfg));
}

void DiscRun::step() {
  const auto t0 = std::chrono::steady_clock::now();
  inlet_.release_due(engine_, engine_.time_s());
  inlet_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  engine_.step();
}

}  // namespace spread::dem
