// `spread drum SCENE [--set k=v]... [--json]`: the rotating drum of seed 001 — packed bed, settling
// (kinetic-energy history), rotation, bed measurements and the flow-regime label with its evidence.
// `spread drum SCENE --sweep-froude 0.01,0.1,... [--map map.png]`: the same scene at several Froude numbers,
// one row per run, and the regime map PNG. `spread simulate` routes scenes with a [drum] table here.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "libspread/core/strict_number.hpp"
#include "tools/spread/command_registry.hpp"
#include "tools/spread/drum_command.hpp"

#include "libspread/core/error.hpp"

#include "libspread/physics/drum/drum_simulation.hpp"
#include "libspread/physics/drum/regime_map_plot.hpp"

namespace spread::drum {
namespace {

using nlohmann::json;

json evidence_json(const spread::drum::RegimeEvidence& e) {
  return json{{"regime", spread::drum::regime_name(e.regime)},
              {"reason", e.reason},
              {"froude", e.froude},
              {"samples", e.samples},
              {"angle_of_repose_deg", e.angle_of_repose_deg},
              {"angle_of_repose_sd_deg", e.angle_of_repose_sd_deg},
              {"surface_sagitta", e.surface_sagitta},
              {"airborne_fraction", e.airborne_fraction},
              {"co_rotating_fraction", e.co_rotating_fraction},
              {"wall_coverage", e.wall_coverage},
              {"wall_speed_ratio", e.wall_speed_ratio},
              {"bed_centroid_angle_deg", e.centroid_angle_deg},
              {"lacey_index", e.lacey_index}};
}

json result_json(const spread::drum::DrumResult& r) {
  json j{{"particles", r.particles},
         {"dt_s", r.dt_s},
         {"contact_time_s", r.contact_time_s},
         {"froude", r.froude},
         {"settled", r.settled},
         {"settle_time_s", r.settle_time_s},
         {"rest_threshold_j", r.rest_threshold_j},
         {"particle_steps", r.particle_steps},
         {"wall_s", r.wall_s},
         {"evidence", evidence_json(r.evidence)},
         {"files", r.files}};
  return j;
}

}  // namespace

int run_drum_command(const std::string& scene_path, const std::vector<std::string>& overrides, bool json_out,
                     const std::string& sweep, const std::string& map_path) {
  const DrumScene scene = load_drum_scene(scene_path, overrides);
  std::vector<double> froudes;
  if (!sweep.empty()) {
    std::stringstream ss(sweep);
    for (std::string item; std::getline(ss, item, ',');) {
      const std::optional<double> froude = parse_finite_number(item);
      if (!froude) {
        throw spread::Error(spread::ErrorKind::kArgument, "--sweep-froude", "--sweep-froude: '" + item + "' is not a number");
      }
      froudes.push_back(*froude);
      if (!(froudes.back() > 0.0)) {
        throw spread::Error(spread::ErrorKind::kArgument, "--sweep-froude", "--sweep-froude: values must be > 0");
      }
    }
  }
  if (froudes.empty()) {
    const DrumResult r = run_drum(scene);
    if (json_out) {
      std::cout << result_json(r).dump(2) << "\n";
    } else {
      std::printf("%zu particles, dt %.3g s, settled %s after %.3f s, Fr %.3f\n", r.particles, r.dt_s, r.settled ? "yes" : "no",
                  r.settle_time_s, r.froude);
      std::printf("regime: %s (%s)\n", regime_name(r.evidence.regime).c_str(), r.evidence.reason.c_str());
      std::printf("angle of repose %.1f ± %.1f deg, airborne %.3f, co-rotating %.3f, wall coverage %.2f, Lacey %.3f\n",
                  r.evidence.angle_of_repose_deg, r.evidence.angle_of_repose_sd_deg, r.evidence.airborne_fraction,
                  r.evidence.co_rotating_fraction, r.evidence.wall_coverage, r.evidence.lacey_index);
      for (const auto& f : r.files) std::printf("wrote %s\n", f.c_str());
    }
    return 0;
  }
  std::vector<RegimeEvidence> runs;
  json rows = json::array();
  for (double fr : froudes) {
    DrumScene s = scene;
    s.angular_velocity_rad_s = omega_from_froude(fr, s.radius_m);
    s.output_directory.clear();
    const DrumResult r = run_drum(s);
    runs.push_back(r.evidence);
    rows.push_back(result_json(r));
    if (!json_out)
      std::printf("Fr %-7.3g %-13s angle %5.1f deg  airborne %.3f  co-rotating %.3f  coverage %.2f  (%s)\n", fr,
                  regime_name(r.evidence.regime).c_str(), r.evidence.angle_of_repose_deg, r.evidence.airborne_fraction,
                  r.evidence.co_rotating_fraction, r.evidence.wall_coverage, r.evidence.reason.c_str());
  }
  json out{{"sweep", rows}};
  if (!map_path.empty()) {
    write_regime_map_png(runs, map_path, "drum regime map: " + scene.source_name);
    out["map_png"] = map_path;
    if (!json_out) std::printf("wrote %s\n", map_path.c_str());
  }
  if (json_out) std::cout << out.dump(2) << "\n";
  return 0;
}

}  // namespace spread::drum

namespace spread::cli::cmd_drum {
namespace {

struct DrumState {
  std::string scene_path;
  std::vector<std::string> overrides;
  bool json_out = false;
  std::string sweep;
  std::string map_path;
};

spread::cli::CommandRegistration reg{"drum", [](CLI::App& app, int& exit_code) {
  static auto state = std::make_unique<DrumState>();
  auto* sub = app.add_subcommand("drum", "rotating drum (seed 001): packed bed, settling, rotation, flow regime");
  sub->add_option("scene", state->scene_path, "drum scene TOML file (with a [drum] table)")->required();
  sub->add_option("--set", state->overrides, "override a scene key: section.key=value (repeatable)");
  sub->add_flag("--json", state->json_out, "machine-readable output on stdout");
  sub->add_option("--sweep-froude", state->sweep, "comma-separated Froude numbers Fr = ω²R/g: one run each");
  sub->add_option("--map", state->map_path, "with --sweep-froude: write the regime map PNG here");
  sub->callback([&exit_code] {
    exit_code = spread::drum::run_drum_command(state->scene_path, state->overrides, state->json_out, state->sweep,
                                               state->map_path);
  });
}};

}  // namespace
}  // namespace spread::cli::cmd_drum
