// lookup_compare SCENE --table FILE [--material NAME] [--rpm R] [--set key=value]... [--duration S]
// Prediction from a launch table (spread::predict::Predictor, the core of the C API) against the direct
// simulation of the same scene (dem::simulate, what `spread simulate` runs): throw width of the machine
// (both discs, 0.5 m trays, 99 % of the mass) and R̄, ξ of one disc (seed Eqs. 51–52). Prints JSON.
// Used to measure the agreement and interpolation figures of docs/building-tables.md.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/physics/dem/simulate.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace {

// Throw width of the machine from one disc's landings about its centre, computed as the predictor
// does: left disc at x − s/2, right disc its mirror image, trays fitted to the landings.
double machine_throw_width_m(const std::vector<double>& x, const std::vector<double>& mass,
                             const spread::tables::Machine& machine, double tray_width_m) {
  const bool two = machine.disc_count == 2;
  const double half = two ? 0.5 * machine.disc_spacing_m : 0.0;
  std::vector<double> xs, ws;
  double total = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) total += mass[k] * (two ? 2.0 : 1.0);
  for (std::size_t k = 0; k < x.size(); ++k) {
    xs.push_back(x[k] - half);
    ws.push_back(mass[k] / total);
    if (two) {
      xs.push_back(half - x[k]);
      ws.push_back(mass[k] / total);
    }
  }
  double half_extent = tray_width_m;
  for (double v : xs) half_extent = std::max(half_extent, std::abs(v));
  const spread::metrics::TrayLayout trays = spread::metrics::tray_layout_covering(half_extent, tray_width_m);
  std::vector<double> tray_mass(static_cast<std::size_t>(trays.tray_count), 0.0);
  spread::metrics::accumulate_transverse(xs, ws, spread::metrics::MachineLayout{1, 0.0}, trays, tray_mass);
  return spread::metrics::throw_width(tray_mass, trays, 0.99);
}

double relative(double table, double direct) { return direct != 0.0 ? (table - direct) / direct : 0.0; }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lookup_compare: table prediction vs direct DEM simulation of the same scene"};
  std::string scene_path, table_path, material;
  std::vector<std::string> overrides;
  double rpm = 0.0, duration = 0.0;
  app.add_option("scene", scene_path, "scene file (TOML)")->required();
  app.add_option("--table", table_path, "launch-table file")->required();
  app.add_option("--material", material, "material (default: [simulate] material)");
  app.add_option("--rpm", rpm, "disc speed (default: machine.rpm)");
  app.add_option("--set", overrides, "override a scene value (as lookup_builder / spread simulate)");
  app.add_option("--duration", duration, "simulated DEM time of the direct run (default numerics.duration_s)");
  CLI11_PARSE(app, argc, argv);
  try {
    spread::scene::Scene scene = spread::scene::load_scene_file(scene_path, overrides);
    if (rpm > 0.0) scene.machine.rpm = rpm;
    spread::dem::SimulationConfig cfg = spread::dem::config_from_scene(scene, material);
    if (duration > 0.0) cfg.duration_s = duration;
    const spread::dem::SimulationResult direct = spread::dem::simulate(cfg);

    spread::predict::Predictor predictor(spread::tables::read_table_file(table_path));
    std::vector<double> x, mass;
    for (std::size_t k = 0; k < direct.landings.size(); ++k) {
      if (!direct.landings[k].landed) continue;
      x.push_back(direct.landings[k].state.position_m.x());
      mass.push_back(direct.launches[k].mass_kg);
    }
    const double direct_throw = machine_throw_width_m(x, mass, predictor.machine(), 0.5);

    spread::predict::PredictionRequest request;
    request.material = cfg.materials[0].name;
    request.rpm = scene.machine.rpm;
    request.effects = cfg.flight_effects;
    spread::predict::Prediction p;
    const auto status = predictor.predict(request, p);
    if (status != spread::predict::PredictStatus::kOk) {
      std::cerr << "lookup_compare: prediction refused: " << spread::predict::to_string(status) << "\n";
      return 2;
    }
    nlohmann::json out = {
        {"material", request.material},
        {"rpm", request.rpm},
        {"direct",
         {{"simulated_s", cfg.duration_s},
          {"launched", direct.launches.size()},
          {"mean_radius_m", direct.mean_radius_m},
          {"radial_width_m", direct.radial_width_m},
          {"throw_width_m", direct_throw},
          {"wall_time_s", direct.wall_time_s}}},
        {"table",
         {{"flights", p.flights},
          {"mean_radius_m", p.mean_radius_m},
          {"radial_width_m", p.radial_width_m},
          {"throw_width_m", p.throw_width_m}}},
        {"relative_difference",
         {{"mean_radius", relative(p.mean_radius_m, direct.mean_radius_m)},
          {"radial_width", relative(p.radial_width_m, direct.radial_width_m)},
          {"throw_width", relative(p.throw_width_m, direct_throw)}}}};
    std::cout << out.dump(2) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "lookup_compare: error: " << e.what() << "\n";
    return 2;
  }
}
