// `spread simulate SCENE [--set k=v]... [--json]`: the full process — disc DEM with the partitioned
// hand-off to flight — printing the launch statistics, the collector's angular mass fractions, R̄ and
// ξ of the landings, the particle-steps, the effects that ran and the wall time per module.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "libspread/core/sieve_analysis.hpp"
#include "tools/spread/command_registry.hpp"
#include "tools/spread/drum_command.hpp"

#include "libspread/physics/drum/drum_scene.hpp"

#include "libspread/analysis/accuracy/monolithic_reference.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/physics/dem/simulate.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/plot/plot.hpp"

namespace spread::cli::cmd_simulate {
namespace {

using nlohmann::json;

struct SimulateState {
  std::string scene_path;
  std::vector<std::string> overrides;
  std::string material;
  bool json_out = false;
  bool monolithic = false;
  int energy_every_steps = 0;
};

int run(const SimulateState& s) {
  namespace dem = spread::dem;
  const spread::scene::Scene scene = spread::scene::load_scene_file(s.scene_path, s.overrides);
  dem::SimulationConfig cfg = dem::config_from_scene(scene, s.material);
  cfg.energy_monitor_every_steps = s.energy_every_steps;
  const std::filesystem::path dir = scene.outputs.directory;
  const bool any_output = scene.outputs.launch_csv || scene.outputs.pattern_png || scene.outputs.vtk_every_steps > 0;
  if (any_output) std::filesystem::create_directories(dir);
  if (scene.outputs.vtk_every_steps > 0) {
    cfg.vtk_prefix = (dir / "particles").string();
    cfg.vtk_walls_prefix = (dir / "walls").string();
    cfg.vtk_every_steps = scene.outputs.vtk_every_steps;
  }
  dem::SimulationResult r;
  spread::accuracy::MonolithicResult monolithic;  // --monolithic only
  try {
    if (s.monolithic) {
      monolithic = spread::accuracy::simulate_monolithic(cfg);
      r = std::move(monolithic.run);
    } else {
      r = dem::simulate(cfg);
    }
  } catch (const std::invalid_argument& e) {
    // The engine's start-up checks judge the scene's values: name the scene.
    throw spread::scene::SceneError(scene.source_name + ": " + e.what());
  }
  json outputs = json::object();
  if (scene.outputs.launch_csv) {
    const auto path = (dir / "launches.csv").string();
    dem::write_launch_csv(r.launches, path);
    outputs["launch_csv"] = path;
  }
  if (scene.outputs.pattern_png && !r.landings.empty()) {
    std::vector<double> x, y, m;
    for (std::size_t k = 0; k < r.landings.size(); ++k)
      if (r.landings[k].landed) {
        x.push_back(r.landings[k].state.position_m.x());
        y.push_back(r.landings[k].state.position_m.y());
        m.push_back(r.launches[k].mass_kg);
      }
    if (!m.empty()) {
      spread::metrics::MachineLayout one{1, 0.0};
      const auto pattern = spread::metrics::ground_pattern(x, y, m, one, 0.25);
      const auto path = (dir / "ground_pattern.png").string();
      spread::plot::write_ground_pattern_png(pattern, path, "simulate: " + scene.machine.name + " (one disc)", one);
      outputs["pattern_png"] = path;
    }
  }
  json module_time = json::object();
  for (const auto& [k, v] : r.module_time_s) module_time[k] = v;
  json out = {{"scene", scene.source_name},
              {"material", cfg.materials[0].name},
              {"rpm", cfg.rpm},
              {"released", r.released},
              {"launched", r.launches.size()},
              {"on_disc_at_end", r.on_disc_at_end},
              {"lost", r.lost},
              {"launch",
               {{"speed_mean", r.launch.speed_mean},
                {"speed_sd", r.launch.speed_sd},
                {"angle_from_tangent_deg_mean", r.launch.angle_from_tangent_deg_mean},
                {"elevation_deg_mean", r.launch.elevation_deg_mean}}},
              {"sector_mass_fraction", r.sector_mass_fraction},
              {"mean_radius_m", r.mean_radius_m},
              {"radial_width_m", r.radial_width_m},
              {"particle_steps", r.particle_steps},
              {"flight_steps", r.flight_steps},
              {"dt_contact_s", r.dt_contact_s},
              {"contact_time_s", r.contact_time_s},
              {"wall_time_s", r.wall_time_s},
              {"effects", r.effects},
              {"module_time_s", module_time},
              {"outputs", outputs}};
  // A material given by its sieve analysis: the sheet's size guide number and uniformity index
  // (docs/products.md).
  const spread::scene::Material* material = scene.find_material(cfg.materials[0].name);
  if (material != nullptr && !material->sieve.empty()) {
    out["size_guide_number"] = spread::size_guide_number(material->sieve);
    out["uniformity_index"] = spread::uniformity_index(material->sieve);
  }
  if (s.monolithic) {
    out["monolithic_flight_particle_steps"] = monolithic.flight_particle_steps;
    out["monolithic_landed"] = monolithic.landings.size();
  }
  if (r.energy_monitored) {
    const dem::EnergyReport& e = r.energy;
    out["energy"] = {{"max_penetration_ratio", e.max_penetration_ratio},
                     {"balance_residual", e.balance_residual()},
                     {"energy_created_j", e.energy_created_j},
                     {"energy_input_j", e.energy_input_j},
                     {"disc_work_j", e.disc_work_j},
                     {"gravity_work_j", e.gravity_work_j},
                     {"added_kinetic_j", e.added_kinetic_j},
                     {"launched_kinetic_j", e.launched_kinetic_j},
                     {"dissipated_j", e.dissipated_j},
                     {"kinetic_j", e.kinetic_j},
                     {"elastic_j", e.elastic_j},
                     {"steps", e.steps}};
  }
  if (s.json_out) {
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << "launched " << r.launches.size() << " of " << r.released << " released; speed "
              << r.launch.speed_mean << " ± " << r.launch.speed_sd << " m/s; R̄ " << r.mean_radius_m << " m, ξ "
              << r.radial_width_m << " m; " << r.particle_steps << " particle-steps in " << r.wall_time_s << " s\n";
  }
  return spread::cli::kExitOk;
}

spread::cli::CommandRegistration reg{"simulate", [](CLI::App& app, int& exit_code) {
  static auto state = std::make_unique<SimulateState>();
  auto* sub = app.add_subcommand("simulate", "full process: disc DEM + flight (partitioned scheme, seed Sect. 3.1)");
  sub->add_option("scene", state->scene_path, "scene TOML file")->required();
  sub->add_option("--set", state->overrides, "override a scene key: key=value (repeatable)");
  sub->add_option("--material", state->material, "material to simulate (default: [simulate] material)");
  sub->add_flag("--json", state->json_out, "machine-readable output on stdout");
  sub->add_flag("--monolithic", state->monolithic,
                "also keep launched particles in the DEM loop at the contact step until they land (cost reference)");
  sub->add_option("--energy-monitor", state->energy_every_steps,
                  "energy budget and max penetration every step, sampled every N steps (0 = off); adds \"energy\" to the summary")
      ->check(CLI::NonNegativeNumber);
  sub->callback([&exit_code] {
    // A scene with a [drum] table is the rotating drum, not a disc.
    if (spread::drum::is_drum_scene_file(state->scene_path)) {
      exit_code = spread::drum::run_drum_command(state->scene_path, state->overrides, state->json_out, "", "");
      return;
    }
    exit_code = run(*state);
  });
}};

}  // namespace
}  // namespace spread::cli::cmd_simulate
