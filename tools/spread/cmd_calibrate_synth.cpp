// spread calibrate synth: a synthetic tray test from the pattern model at known parameters, with seeded noise.
#include "tools/spread/calibrate_report.hpp"

namespace spread::cli::calibrate {

void run_synth(const SynthOptions& o) {
  if (o.output.empty()) throw BadInput("--output: give the path of the CSV to write");
  spread::cli::require_output_folder("--output", o.output);
  spread::cli::refuse_existing_file("--output", o.output, o.force, "--force");
  if (o.samples < 16 || o.samples > 100000) throw BadInput("--samples must be in [16, 100000]");
  if (!(o.tray_width_m > 0.0) || !(o.half_width_m >= 2.5 * o.tray_width_m)) {
    throw BadInput("--tray-width must be > 0 and --half-width at least 2.5 tray widths");
  }
  const spread::cli::TableSession session(o.tables);
  const spread::tables::TableContents& contents = session.contents();
  const cal::PatternSetup setup = cal::pattern_setup_from_table(contents, o.material, o.rpm);
  cal::PatternParameters truth = cal::parameters_of(setup.material);
  if (!std::isnan(o.friction)) {
    if (!setup.table_samples.empty()) {
      throw BadInput("--friction: the table's rows of '" + o.material + "' came from the DEM: their launches do not "
                     "depend on a friction; give --speed-factor, --offset, --elevation, --drag");
    }
    truth.friction_wall = o.friction;
  }
  truth.drag_diameter_factor = o.drag;
  truth.launch_angle_offset_rad = o.offset_deg / kDegPerRad;
  truth.launch_speed_factor = o.speed_factor;
  truth.launch_elevation_offset_rad = o.elevation_deg / kDegPerRad;
  cal::check_parameters(truth);
  cal::PatternModelOptions model_options;
  model_options.sample_count = o.samples;
  const spread::metrics::TrayLayout layout = spread::metrics::tray_layout_covering(o.half_width_m, o.tray_width_m);
  const cal::PatternModel model(setup, layout, model_options);
  cal::TrayNoise noise;
  noise.relative_sd = o.relative_noise_percent / 100.0;
  noise.granule_mass_g = o.granule_mass_g;
  noise.floor_sd_g = o.floor_g;
  noise.resolution_g = o.resolution_g;
  const cal::SyntheticTrayTest test = cal::synthetic_tray_test(model, truth, o.mass_g, o.passes, noise, o.seed);
  char text[512];
  std::vector<std::string> comments;
  std::snprintf(text, sizeof text,
                "Synthetic tray test: %d trays of %.2f m, %d pass(es), grams; position_m = tray centre from the "
                "tractor centre line (left negative).",
                layout.tray_count, layout.tray_width_m, o.passes);
  comments.emplace_back(text);
  std::snprintf(text, sizeof text,
                "Made by spread calibrate synth: '%s' of %s at %g rpm, %d samples, friction %.4g, drag diameter "
                "factor %.4g, launch-angle offset %.4g deg, %.4g g per pass in the trays.",
                o.material.c_str(), o.tables.c_str(), o.rpm, o.samples, truth.friction_wall,
                truth.drag_diameter_factor, o.offset_deg, o.mass_g);
  comments.emplace_back(text);
  std::snprintf(text, sizeof text, "Launches: %s, launch speed factor %.4g, launch elevation offset %.4g deg.",
                setup.table_samples.empty() ? "the analytic model"
                                            : ("the table's DEM row at " + std::to_string(static_cast<int>(setup.table_row_rpm)) + " rpm").c_str(),
                o.speed_factor, o.elevation_deg);
  comments.emplace_back(text);
  std::snprintf(text, sizeof text,
                "Noise per tray and pass: Poisson count of %.4g g granules, plus normal with sd^2 = (%.4g %% of the "
                "tray)^2 + (%.4g g)^2, readings below 0 written as 0, rounded to %.4g g; seed %llu.",
                o.granule_mass_g, o.relative_noise_percent, o.floor_g, o.resolution_g,
                static_cast<unsigned long long>(o.seed));
  comments.emplace_back(text);
  cal::write_tray_csv(o.output, test.position_m, test.pass_mass_g, comments);
  if (o.json) {
    json out{{"output", o.output},
             {"trays", layout.tray_count},
             {"tray_width_m", layout.tray_width_m},
             {"passes", o.passes},
             {"truth", {{"friction_wall", truth.friction_wall},
                        {"drag_diameter_factor", truth.drag_diameter_factor},
                        {"launch_angle_offset_deg", o.offset_deg},
                        {"launch_speed_factor", o.speed_factor},
                        {"launch_elevation_offset_deg", o.elevation_deg}}},
             {"seed", o.seed}};
    std::cout << out.dump(2) << "\n";
    return;
  }
  if (setup.table_samples.empty()) {
    std::printf("wrote %s: %d trays of %.2f m, %d pass(es), friction %.4g, drag %.4g, offset %.4g deg\n",
                o.output.c_str(), layout.tray_count, layout.tray_width_m, o.passes, truth.friction_wall,
                truth.drag_diameter_factor, o.offset_deg);
  } else {
    std::printf("wrote %s: %d trays of %.2f m, %d pass(es), the DEM row at %g rpm with launch speed factor %.4g, "
                "offset %.4g deg, elevation %.4g deg, drag %.4g\n",
                o.output.c_str(), layout.tray_count, layout.tray_width_m, o.passes, setup.table_row_rpm,
                o.speed_factor, o.offset_deg, o.elevation_deg, truth.drag_diameter_factor);
  }
}

}  // namespace spread::cli::calibrate
