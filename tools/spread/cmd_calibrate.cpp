// spread calibrate rate|tray|pattern — the technician's field tools (docs/field-calibration.md).
//   rate     catch test → flow factor → gate opening for a target rate; the rate error of the current opening
//   tray     tray-test CSV → CV (to-and-fro, racetrack) at a bout width, CV(W), effective working widths
//   synth    a synthetic tray test from the pattern model at known parameters, with seeded noise
//   pattern  fit friction, drag-diameter factor and launch-angle offset of a material to a tray test and
//            write the calibrated material into a NEW table file (the original is only read)
// Every command prints a short report, or JSON with --json. Bad input → a message naming it on stderr,
// exit code 2 (for a CSV: file and line). A run that cannot complete (a refused fit, a plot that cannot
// Each subcommand is a file of its own (cmd_calibrate_<name>.cpp, calibrate_report.hpp); this one registers them.
#include "tools/spread/calibrate_report.hpp"
#include "tools/spread/command_registry.hpp"

namespace spread::cli::cmd_calibrate {
namespace {

using namespace spread::cli::calibrate;

spread::cli::CommandRegistration reg{"calibrate", [](CLI::App& app, int& /*exit_code: failures are thrown, see error_exit.hpp*/) {
  auto* sub = app.add_subcommand("calibrate", "field calibration: catch test (rate), tray test, pattern fit");
  sub->require_subcommand(1);

  static RateOptions rate;
  auto* r = sub->add_subcommand("rate", "flow factor from a catch test; gate opening for a target rate");
  r->add_option("--mass", rate.mass_kg, "mass caught from all outlets (kg)")->required();
  r->add_option("--time", rate.time_s, "catch duration (s)")->required();
  r->add_option("--gate", rate.gate, "gate opening of the catch (the gate scale's unit: mm, %, ...)")->required();
  r->add_option("--mass2", rate.mass2_kg, "second catch: mass (kg) — two catches fit the gate's dead zone");
  r->add_option("--time2", rate.time2_s, "second catch: duration (s)");
  r->add_option("--gate2", rate.gate2, "second catch: gate opening");
  r->add_option("--target-rate", rate.target_rate_kg_ha, "target application rate (kg/ha)")->required();
  r->add_option("--width", rate.width_m, "working (bout) width (m)")->required();
  r->add_option("--speed", rate.speed_km_h, "forward speed (km/h)")->required();
  r->add_option("--current-gate", rate.current_gate, "gate opening to check (default: the catch's)");
  r->add_flag("--json", rate.json, "machine-readable output on stdout");
  r->callback([] { run_rate(rate); });

  static TrayOptions tray;
  auto* t = sub->add_subcommand("tray", "tray test: CV at a bout width, CV(W), effective working widths");
  t->add_option("file", tray.file, "tray-test CSV (position_m and one *_g or *_kg column per pass)")->required();
  t->add_option("--width", tray.width_m, "bout width W (m) for the CVs (default: none)");
  t->add_option("--cv-target", tray.cv_target_percent, "CV target (%) of the effective working width")->capture_default_str();
  t->add_option("--plot", tray.plot_prefix, "write PREFIX_transverse.png and PREFIX_cv.png");
  t->add_flag("--json", tray.json, "machine-readable output on stdout");
  t->add_option("--machine", tray.machine, "machine name, for the report's header");
  t->add_option("--material", tray.material, "material spread, for the report's header");
  t->add_option("--rpm", tray.rpm, "disc speed of the test (r/min), for the report's header");
  spread::cli::add_report_args(*t, tray.report, true);
  t->add_flag("--quick-check", tray.quick_check,
              "4-8 trays across one bout of the field as driven: their CV and how uncertain it is from so few trays");
  t->callback([] { run_tray(tray); });

  static PatternOptions pattern;
  auto* p = sub->add_subcommand("pattern", "fit a material to a tray test; write it into a new table file");
  p->add_option("--tables", pattern.tables,
                 "launch-table file of the machine (read only), made by lookup_builder from its scene: "
                 "lookup_builder scenes/default.toml --output table.sqlite (the DEM takes some minutes)")
      ->required();
  p->add_option("--material", pattern.material, "material name in the table")->required();
  p->add_option("--rpm", pattern.rpm, "disc speed of the tray test (r/min)")->required();
  p->add_option("--trays", pattern.trays, "tray-test CSV")->required();
  p->add_option("--output", pattern.output, "NEW table file: a copy of --tables plus the calibrated material")->required();
  p->add_option("--name", pattern.name, "tag of the calibrated material, kept with the product's name: 'field' for Urea is 'Urea (field)' "
                 "(default: 'Urea (calibrated YYYY-MM-DD)')");
  p->add_option("--fit", pattern.fit,
                "parameters to fit, of friction, drag, offset, speed, elevation (the others keep the table's values); "
                "default friction,drag,offset on analytic rows, speed,offset on DEM rows");
  p->add_option("--samples", pattern.samples, "trajectories per model evaluation")->capture_default_str();
  p->add_option("--kernel", pattern.kernel_m, "landing kernel sd (m); default half the tray width");
  p->add_option("--cv-target", pattern.cv_target_percent, "CV target (%) of the plots")->capture_default_str();
  p->add_option("--width", pattern.width_m,
                "bout width (m): the report's, and the calibrated material's CV there with what to change "
                "when it is above the target");
  p->add_flag("--allow-analytic", pattern.allow_analytic,
              "on a material whose table rows came from the DEM: fit the analytic model and write analytic rows "
              "(default: correct the DEM rows' own launches)");
  p->add_option("--plot", pattern.plot_prefix, "write PREFIX_transverse.png, PREFIX_cv.png, PREFIX_cv_measured.png");
  p->add_flag("--json", pattern.json, "machine-readable output on stdout");
  spread::cli::add_report_args(*p, pattern.report, true);
  p->callback([] { run_pattern(pattern); });

  static SynthOptions synth;
  auto* y = sub->add_subcommand("synth", "write a synthetic tray test made by the pattern model (known answers)");
  y->add_option("--tables", synth.tables, "launch-table file (read only)")->required();
  y->add_option("--material", synth.material, "material name in the table")->required();
  y->add_option("--rpm", synth.rpm, "disc speed (r/min)")->required();
  y->add_option("--output", synth.output, "CSV to write")->required();
  y->add_option("--friction", synth.friction, "friction on the vanes (default: the table's)");
  y->add_option("--drag", synth.drag, "drag diameter factor k")->capture_default_str();
  y->add_option("--offset", synth.offset_deg, "launch-angle offset (deg)")->capture_default_str();
  y->add_option("--speed-factor", synth.speed_factor, "launch speed factor s")->capture_default_str();
  y->add_option("--elevation", synth.elevation_deg, "launch elevation offset (deg)")->capture_default_str();
  y->add_option("--half-width", synth.half_width_m, "trays cover [-this, this] m")->capture_default_str();
  y->add_option("--tray-width", synth.tray_width_m, "tray width (m)")->capture_default_str();
  y->add_option("--passes", synth.passes, "passes (one mass column each)")->capture_default_str();
  y->add_option("--mass", synth.mass_g, "expected mass in all trays per pass (g)")->capture_default_str();
  y->add_option("--relative-noise", synth.relative_noise_percent, "noise sd, % of each tray's mass")->capture_default_str();
  y->add_option("--granule-mass", synth.granule_mass_g, "counting noise: mass of one granule (g); 0 = none")->capture_default_str();
  y->add_option("--floor", synth.floor_g, "additive noise sd (g); readings below 0 are written as 0")->capture_default_str();
  y->add_option("--resolution", synth.resolution_g, "readings rounded to this (g)")->capture_default_str();
  y->add_option("--samples", synth.samples, "trajectories of the model")->capture_default_str();
  y->add_option("--seed", synth.seed, "noise seed")->capture_default_str();
  y->add_flag("--force", synth.force, "replace --output when it exists");
  y->add_flag("--json", synth.json, "machine-readable output on stdout");
  y->callback([] { run_synth(synth); });
}};

}  // namespace
}  // namespace spread::cli::cmd_calibrate
