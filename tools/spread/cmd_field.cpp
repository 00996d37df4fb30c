// spread field --tables FILE --material NAME --rpm R --boundary FIELD.geojson --bout W --rate KG_HA
//              [--track TRACK.csv | --headland N --reference-edge I] [--border] [--no-section-control]
//              [--sections N] [--speed KMH] [--look-ahead S] [--gate-travel S] [--field-wind E,N]
//              [--cell M] [--compare] [--compare-bout W2] [--grid OUT.csv] [--map OUT.png] [--json]
//       or     --scene SCENE.toml [--set KEY=VALUE ...] with its [field] section, options beside it replacing keys
// The whole field (libspread/analysis/field, docs/field.md): the boundary (GeoJSON, longitude/latitude
// projected to its UTM zone with PROJ, or metres in a named CRS), a plan of headland rounds and tramlines at
// the bout width or a recorded track, driven with the ECU's own logic in the loop (libspread/control, its
// predictions over the C API as firmware_sim makes them): section control over worked ground, border mode on
// the outermost round, wind compensation, the discs' speed lag and the gates' travel. Each moment is spread
// with the discs' ground pattern at their actual state, and the as-applied map's numbers follow: field CV,
// the area under 80 %, within 80–120 % and over 120 % of the target rate, the mass beyond the boundary.
// --compare runs the strategies a user weighs — section control off and on, border mode off and on, the
// bout width and --compare-bout, calm and --field-wind — and prints them as one table.
// A wind over a field has a direction in the field: --field-wind (east, north), not the machine's --wind.
// Bad input → a message naming it on stderr, exit code 2, before any work.
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/analysis/field/as_applied.hpp"
#include "libspread/analysis/field/field_map_plot.hpp"
#include "libspread/analysis/field/field_summary.hpp"
#include "libspread/analysis/field/geojson_boundary.hpp"
#include "capi/cpp/capi_spread_predictor.hpp"
#include "libspread/analysis/field/machine_in_loop.hpp"
#include "libspread/analysis/field/plan.hpp"
#include "libspread/analysis/field/projection.hpp"
#include "libspread/analysis/field/rate_grid_csv.hpp"
#include "libspread/analysis/field/track_csv.hpp"
#include "libspread/io/scene/scene.hpp"
#include "tools/spread/command_registry.hpp"
#include "tools/spread/number_format.hpp"
#include "tools/spread/prediction_args.hpp"
#include "tools/spread/table_session.hpp"

namespace spread::cli::cmd_field {
namespace {

using nlohmann::json;
using spread::cli::BadInput;
namespace fd = spread::field;
namespace pr = spread::predict;

struct Options : spread::cli::PredictionArgs {
  std::string scene;
  std::vector<std::string> set;
  std::string boundary;
  std::string track;
  double bout_width_m = 0.0;
  double rate_kg_ha = 0.0;
  int headland = 1;
  int reference_edge = -1;
  double cell_m = 0.5;
  bool border = false;
  bool no_section_control = false;
  int sections = 8;
  double speed_km_h = 12.0;
  double look_ahead_s = 0.5;
  double gate_travel_s = 1.0;
  std::string field_wind = "0,0";
  bool compare = false;
  double compare_bout_m = 18.0;
  std::string grid;
  std::string map;
  bool json = false;
};

// What a run varies: the comparisons a user weighs.
struct Strategy {
  bool section_control = true;
  bool border = false;
  double bout_width_m = 0.0;
};

// One field run: its strategy and numbers.
struct Row {
  bool section_control = true;
  bool border = false;
  double bout_width_m = 0.0;
  double wind_east_m_s = 0.0, wind_north_m_s = 0.0;
  fd::FieldSummary summary;
  double tray_cv = 0.0;  // the tray test's to-and-fro CV at this bout (fraction)
  std::size_t steps = 0;
  std::size_t section_switches = 0;
  std::int64_t planner_searches = 0;
  std::string map;  // its map's PNG ("": none)
};

// A scene's [field] (docs/scene-format.md) for every option not given on the command line; the tables are
// the scene's sweep.output unless --tables names them.
void apply_scene(const CLI::App& sub, Options& o) {
  if (o.scene.empty()) {
    if (!o.set.empty()) throw BadInput("--set: there is no --scene to set keys of");
    return;
  }
  const spread::scene::Scene scene = spread::scene::load_scene_file(o.scene, o.set);
  const spread::scene::FieldRun& f = scene.field;
  const auto unset = [&](const char* option) { return sub.count(option) == 0; };
  if (unset("--tables")) o.tables = scene.sweep.output;
  if (unset("--material")) o.material = f.material.empty() ? scene.simulate_material : f.material;
  if (unset("--rpm")) o.rpm = f.rpm > 0.0 ? f.rpm : scene.machine.rpm;
  if (unset("--boundary")) o.boundary = f.boundary;
  if (unset("--track")) o.track = f.track;
  if (unset("--rate")) o.rate_kg_ha = f.rate_kg_ha;
  if (unset("--bout")) o.bout_width_m = f.bout_width_m;
  if (unset("--headland")) o.headland = f.headland_passes;
  if (unset("--reference-edge")) o.reference_edge = f.reference_edge;
  if (unset("--field-wind")) o.field_wind = format("%.17g", f.wind_m_s[0]) + "," + format("%.17g", f.wind_m_s[1]);
  if (unset("--sections")) o.sections = f.section_count;
  if (unset("--no-section-control")) o.no_section_control = !f.section_control;
  if (unset("--border")) o.border = f.border;
  if (unset("--speed")) o.speed_km_h = f.speed_km_h;
  if (unset("--look-ahead")) o.look_ahead_s = f.look_ahead_s;
  if (unset("--gate-travel")) o.gate_travel_s = f.gate_travel_s;
  if (unset("--cell")) o.cell_m = f.cell_m;
}

void check(const Options& o) {
  if (o.tables.empty()) throw BadInput("--tables is required (or a --scene whose sweep.output names them)");
  if (o.material.empty()) throw BadInput("--material is required (or a --scene naming field.material)");
  if (!(o.rpm > 0.0)) throw BadInput("--rpm is required: the field's disc speed (or a --scene)");
  if (o.boundary.empty()) throw BadInput("--boundary is required: the field's GeoJSON file (or a --scene naming field.boundary)");
  if (!(o.bout_width_m > 0.0 && o.bout_width_m <= 100.0)) throw BadInput("--bout is required: the bout width in (0, 100] m");
  if (!(o.rate_kg_ha > 0.0) || !std::isfinite(o.rate_kg_ha)) throw BadInput("--rate is required: the target rate (kg/ha) > 0");
  if (!(o.cell_m >= 0.1 && o.cell_m <= 5.0)) throw BadInput("--cell " + format("%g", o.cell_m) + ": a cell of 0.1 to 5 m");
  if (o.sections < 1 || o.sections > 16) throw BadInput("--sections " + std::to_string(o.sections) + ": the machine has 1 to 16 sections");
  if (!(o.speed_km_h > 0.0 && o.speed_km_h <= 40.0)) throw BadInput("--speed " + format("%g", o.speed_km_h) + ": a ground speed in (0, 40] km/h");
  for (const auto& [name, v] : {std::pair{"--look-ahead", o.look_ahead_s}, std::pair{"--gate-travel", o.gate_travel_s}}) {
    if (!(v >= 0.0 && v <= 10.0)) throw BadInput(std::string(name) + " " + format("%g", v) + ": a time in [0, 10] s");
  }
  // The ECU runs the field's disc speed at the table's drop point and height: it takes no other.
  if (o.drop_point_turn_deg != 0.0 || !std::isnan(o.height_m) || !std::isnan(o.disc_rpm[0]) || !std::isnan(o.disc_rpm[1]) ||
      !std::isnan(o.disc_drop_point_turn_deg[0]) || !std::isnan(o.disc_drop_point_turn_deg[1])) {
    throw BadInput("the ECU in the loop runs --rpm at the table's drop point and height: --drop-point-turn, --height and "
                   "each disc's own settings are not taken by spread field");
  }
  if (o.wind != "0,0") {
    throw BadInput("--wind: a wind over a field has a direction in the field; give --field-wind EAST,NORTH (m/s)");
  }
  if (o.compare && !(o.compare_bout_m > 0.0 && o.compare_bout_m <= 100.0)) {
    throw BadInput("--compare-bout " + format("%g", o.compare_bout_m) + ": a bout width in (0, 100] m");
  }
}

std::vector<fd::Pass> passes_for(const Options& o, const fd::Boundary& boundary, double bout_width_m) {
  if (!o.track.empty()) return fd::read_track_csv(o.track, boundary);
  fd::PlanSettings plan;
  plan.bout_width_m = bout_width_m;
  plan.headland_passes = o.headland;
  plan.reference_edge = o.reference_edge;
  return fd::plan_field(boundary, plan);
}

// The progress line of a long run, on stderr (stdout keeps the answer): every tenth of its steps.
std::function<void(std::size_t, std::size_t)> progress_lines() {
  return [printed = -1](std::size_t done, std::size_t total) mutable {
    if (total < 20 * fd::kProgressSteps) return;
    const int tenth = static_cast<int>(10 * done / total);
    if (tenth <= printed) return;
    printed = tenth;
    std::fprintf(stderr, "spread field: %d %% (%zu of %zu steps)\n", 10 * tenth, done, total);
  };
}

Row run_one(const Options& o, pr::Predictor& predictor, firmware::SpreadPredictor& ecu, const fd::Boundary& boundary,
            const Strategy& strategy, spread::cli::WindXY wind, fd::MachineRun* keep, const std::string& map) {
  pr::PredictionRequest request = spread::cli::prediction_request(o);
  request.bout_width_m = strategy.bout_width_m;
  request.tray_width_m = o.cell_m;
  Row row;
  row.section_control = strategy.section_control;
  row.border = strategy.border;
  row.bout_width_m = strategy.bout_width_m;
  row.wind_east_m_s = wind.x_m_s;
  row.wind_north_m_s = wind.y_m_s;
  pr::Prediction tray;
  const pr::PredictStatus status = predictor.predict(request, tray);
  if (status != pr::PredictStatus::kOk) throw BadInput(std::string("the setting is refused: ") + pr::to_string(status));
  row.tray_cv = tray.cv_to_and_fro;
  fd::MachineSettings m;
  m.target_rate_kg_ha = o.rate_kg_ha;
  m.bout_width_m = strategy.bout_width_m;
  m.rpm = o.rpm;
  m.cell_m = o.cell_m;
  m.speed_m_s = o.speed_km_h / 3.6;
  m.section_count = o.sections;
  m.section_control = strategy.section_control;
  m.border = strategy.border;
  m.wind_east_m_s = wind.x_m_s;
  m.wind_north_m_s = wind.y_m_s;
  m.look_ahead_on_s = m.look_ahead_off_s = o.look_ahead_s;
  m.gate_full_travel_s = o.gate_travel_s;
  m.progress = progress_lines();
  request.wind_x_m_s = request.wind_y_m_s = 0.0;
  fd::MachineRun run = fd::run_machine(boundary, passes_for(o, boundary, strategy.bout_width_m), ecu, predictor, request, m);
  row.summary = fd::summarise(run.applied, boundary, o.rate_kg_ha);
  row.steps = run.loop_steps;
  row.section_switches = run.section_switches;
  row.planner_searches = run.planner_searches;
  if (!map.empty()) {
    fd::write_field_map_png(map, run.applied.grid, boundary, run.passes, o.rate_kg_ha,
                            o.material + format(" at %g rpm", o.rpm) + format(", %g m bouts", strategy.bout_width_m) +
                                (strategy.section_control ? ", section control" : "") +
                                (strategy.border ? ", border mode" : "") +
                                (wind.x_m_s != 0.0 || wind.y_m_s != 0.0 ? ", wind" : "") +
                                format(": field CV %.1f %%", 100.0 * row.summary.cv));
    row.map = map;
  }
  if (keep) *keep = std::move(run);
  return row;
}

json row_json(const Row& r) {
  const fd::FieldSummary& s = r.summary;
  const double area = s.field_area_m2 > 0.0 ? s.field_area_m2 : 1.0;
  return {{"section_control", r.section_control},
          {"border", r.border},
          {"bout_width_m", r.bout_width_m},
          {"wind_east_m_s", r.wind_east_m_s},
          {"wind_north_m_s", r.wind_north_m_s},
          {"field_cv_percent", 100.0 * s.cv},
          {"tray_cv_to_and_fro_percent", 100.0 * r.tray_cv},
          {"mean_rate_kg_ha", s.mean_rate_kg_ha},
          {"under_80_percent_area_ha", s.under_area_m2 / 1e4},
          {"within_80_120_percent_area_ha", s.within_area_m2 / 1e4},
          {"over_120_percent_area_ha", s.over_area_m2 / 1e4},
          {"under_80_percent_area_percent", 100.0 * s.under_area_m2 / area},
          {"over_120_percent_area_percent", 100.0 * s.over_area_m2 / area},
          {"metered_kg", s.metered_kg},
          {"applied_kg", s.applied_kg},
          {"beyond_boundary_kg", s.beyond_kg},
          {"beyond_boundary_percent", 100.0 * s.beyond_fraction},
          {"not_landed_kg", s.not_landed_kg},
          {"section_switches", r.section_switches},
          {"ecu_searches", r.planner_searches},
          {"loop_steps", r.steps},
          {"map_png", r.map}};
}

void print_row(const Row& r) {
  const fd::FieldSummary& s = r.summary;
  const double area = s.field_area_m2;
  const std::string wind = format("%.1f", r.wind_east_m_s) + "," + format("%.1f", r.wind_north_m_s);
  std::printf("%-8s %-7s %6s %12s %8s %8s %8s %9s %9s %10s %8s\n", r.section_control ? "on" : "off", r.border ? "border" : "normal",
              format("%g", r.bout_width_m).c_str(), wind.c_str(),
              format("%.1f", 100.0 * s.cv).c_str(), format("%.1f", 100.0 * r.tray_cv).c_str(),
              format("%.1f", 100.0 * s.under_area_m2 / area).c_str(), format("%.1f", 100.0 * s.within_area_m2 / area).c_str(),
              format("%.1f", 100.0 * s.over_area_m2 / area).c_str(), format("%.1f", s.beyond_kg).c_str(),
              format("%.2f", 100.0 * s.beyond_fraction).c_str());
}

void print_table(const std::vector<Row>& rows) {
  std::printf("%-8s %-7s %6s %12s %8s %8s %8s %9s %9s %10s %8s\n", "sections", "mode", "bout_m", "wind_E,N_m/s", "fieldCV%", "trayCV%",
              "<80%", "80-120%", ">120%", "beyond_kg", "beyond%");
  for (const Row& r : rows) print_row(r);
}

void print_summary(const Options& o, const fd::Boundary& boundary, const Row& r) {
  const fd::FieldSummary& s = r.summary;
  std::printf("field %s: %s in %s, %zu cells of %s inside\n", o.boundary.c_str(), format("%.2f ha", boundary.area_m2 / 1e4).c_str(),
              boundary.crs.c_str(), s.cells_inside, format("%g m", o.cell_m).c_str());
  std::printf("field CV %s (the tray test at %s: %s to-and-fro); mean rate %s of %s\n", format("%.1f %%", 100.0 * s.cv).c_str(),
              format("%g m", r.bout_width_m).c_str(), format("%.1f %%", 100.0 * r.tray_cv).c_str(),
              format("%.0f kg/ha", s.mean_rate_kg_ha).c_str(), format("%.0f kg/ha", o.rate_kg_ha).c_str());
  std::printf("area under 80 %%: %s (%s); 80-120 %%: %s (%s); over 120 %%: %s (%s)\n",
              format("%.2f ha", s.under_area_m2 / 1e4).c_str(), format("%.1f %%", 100.0 * s.under_area_m2 / s.field_area_m2).c_str(),
              format("%.2f ha", s.within_area_m2 / 1e4).c_str(), format("%.1f %%", 100.0 * s.within_area_m2 / s.field_area_m2).c_str(),
              format("%.2f ha", s.over_area_m2 / 1e4).c_str(), format("%.1f %%", 100.0 * s.over_area_m2 / s.field_area_m2).c_str());
  std::printf("metered %s; in the field %s; beyond the boundary %s (%s of metered); not landed %s\n",
              format("%.1f kg", s.metered_kg).c_str(), format("%.1f kg", s.applied_kg).c_str(),
              format("%.1f kg", s.beyond_kg).c_str(), format("%.2f %%", 100.0 * s.beyond_fraction).c_str(),
              format("%.1f kg", s.not_landed_kg).c_str());
}

// --map as given for one run; with --compare each run's map beside it: am_bach.png → am_bach_sc_border_10m_wind.png.
std::string map_path(const Options& o, const Strategy& s, bool windy) {
  if (o.map.empty() || !o.compare) return o.map;
  const std::size_t dot = o.map.rfind('.');
  const std::string stem = dot == std::string::npos ? o.map : o.map.substr(0, dot);
  const std::string ext = dot == std::string::npos ? ".png" : o.map.substr(dot);
  return stem + (s.section_control ? "_sc" : "_nosc") + (s.border ? "_border_" : "_normal_") +
         format("%gm_", s.bout_width_m) + (windy ? "wind" : "calm") + ext;
}

// The runs asked for: one, or --compare's every combination of section control off and on, border mode off
// and on, --bout and --compare-bout, calm and --field-wind (when one is given).
std::vector<std::pair<Strategy, bool>> strategies(const Options& o, bool windy, bool two_discs) {
  if (!o.compare) return {{Strategy{!o.no_section_control, o.border, o.bout_width_m}, windy}};
  std::vector<std::pair<Strategy, bool>> out;
  for (const double bout : {o.bout_width_m, o.compare_bout_m}) {
    for (const bool with_wind : windy ? std::vector<bool>{false, true} : std::vector<bool>{false}) {
      for (const bool section_control : {false, true}) {
        for (const bool border : {false, true}) {
          if (!border || two_discs) out.push_back({Strategy{section_control, border, bout}, with_wind});
        }
      }
    }
  }
  return out;
}

void run(const Options& o, int& exit_code) {
  check(o);
  const spread::cli::WindXY wind = spread::cli::parse_wind(o.field_wind);
  const fd::ProjectedRing projected = fd::project_to_metres(fd::read_geojson_boundary(o.boundary));
  const fd::Boundary boundary = fd::make_boundary(projected.ring, projected.crs, o.boundary);
  spread::cli::TableSession session(o.tables);
  pr::Predictor& predictor = session.predictor();
  if (!predictor.find_material(o.material)) throw BadInput("--material '" + o.material + "' is not in " + o.tables);
  const bool two_discs = predictor.machine().disc_count >= 2;
  if (o.border && !two_discs) throw BadInput("--border: a one-disc machine has no edge-side disc");
  // The ECU's predictions through the C API, as firmware_sim makes them, over the session's handle (the
  // table file is read once).
  firmware::CapiSpreadPredictor ecu(session.capi());

  // The first run's grid (--grid) and, with --compare and --map, the runs at --bout in calm side by side.
  std::vector<fd::MachineRun> kept;
  std::vector<std::string> titles;
  std::vector<Row> rows;
  for (const auto& [strategy, with_wind] : strategies(o, wind.x_m_s != 0.0 || wind.y_m_s != 0.0, two_discs)) {
    const bool keep = rows.empty() || (o.compare && !o.map.empty() && !with_wind && strategy.bout_width_m == o.bout_width_m);
    if (keep) kept.emplace_back();
    rows.push_back(run_one(o, predictor, ecu, boundary, strategy, with_wind ? wind : spread::cli::WindXY{},
                           keep ? &kept.back() : nullptr, map_path(o, strategy, with_wind)));
    if (keep) {
      titles.push_back(std::string(strategy.section_control ? "section control" : "no section control") +
                       (strategy.border ? ", border mode" : ", no border mode") +
                       format("\nfield CV %.1f %%", 100.0 * rows.back().summary.cv) +
                       format(", >120 %% %.1f %%", 100.0 * rows.back().summary.over_area_m2 / rows.back().summary.field_area_m2) +
                       format(", beyond %.1f kg", rows.back().summary.beyond_kg));
    }
  }
  const fd::AsApplied& applied = kept.front().applied;
  if (!o.grid.empty()) fd::write_rate_grid_csv(o.grid, applied.grid, fd::inside_mask(applied.grid, boundary.ring), boundary.crs);
  std::string side_by_side;
  if (o.compare && !o.map.empty() && kept.size() > 1) {
    std::vector<fd::MapPanel> panels;
    for (std::size_t i = 0; i < kept.size(); ++i) panels.push_back({&kept[i].applied.grid, &kept[i].passes, titles[i]});
    const std::size_t dot = o.map.rfind('.');
    side_by_side = (dot == std::string::npos ? o.map : o.map.substr(0, dot)) + "_side_by_side" +
                   (dot == std::string::npos ? ".png" : o.map.substr(dot));
    fd::write_field_maps_png(side_by_side, panels, boundary, o.rate_kg_ha,
                             o.material + format(" at %g rpm", o.rpm) + format(", %g m bouts, calm", o.bout_width_m));
  }
  if (o.json) {
    json list = json::array();
    for (const Row& r : rows) list.push_back(row_json(r));
    json out{{"boundary", o.boundary}, {"crs", boundary.crs}, {"boundary_area_ha", boundary.area_m2 / 1e4},
             {"cell_m", o.cell_m}, {"target_rate_kg_ha", o.rate_kg_ha}, {"runs", list}};
    if (!o.grid.empty()) out["grid_csv"] = o.grid;
    if (!side_by_side.empty()) out["maps_side_by_side_png"] = side_by_side;
    std::cout << out.dump(2) << "\n";
  } else {
    print_summary(o, boundary, rows.front());
    if (o.compare) print_table(rows);
    if (!o.grid.empty()) std::printf("rate grid: %s (%s)\n", o.grid.c_str(), boundary.crs.c_str());
    for (const Row& r : rows) {
      if (!r.map.empty()) std::printf("map: %s\n", r.map.c_str());
    }
    if (!side_by_side.empty()) std::printf("maps side by side: %s\n", side_by_side.c_str());
  }
  exit_code = spread::cli::kExitOk;
}

spread::cli::CommandRegistration reg{"field", [](CLI::App& app, int& exit_code) {
  static Options options;
  auto* sub = app.add_subcommand("field", "the whole field: the as-applied map of a plan or a recorded track, field CV, "
                                          "over- and under-applied area, mass beyond the boundary");
  spread::cli::add_prediction_args(*sub, options);
  // A scene's [field] may name them instead.
  for (const char* option : {"--tables", "--material"}) sub->get_option(option)->required(false);
  sub->add_option("--scene", options.scene, "a scene whose [field] gives the run (docs/scene-format.md); options given beside it replace its keys");
  sub->add_option("--set", options.set, "KEY=VALUE: a scene key set (as lookup_builder's --set), e.g. field.border=true");
  sub->add_option("--boundary", options.boundary, "the field's boundary: GeoJSON Polygon (longitude/latitude, or metres with a crs member)");
  sub->add_option("--track", options.track, "a recorded track (CSV: time_s, x_m,y_m or lon_deg,lat_deg, speed_m_s, heading_deg[, spreading]) instead of a plan");
  sub->add_option("--bout", options.bout_width_m, "bout width (m): the tramlines' spacing and the metered flow's width");
  sub->add_option("--rate", options.rate_kg_ha, "target rate (kg/ha)");
  sub->add_option("--headland", options.headland, "headland rounds of the plan (0: tramlines to the boundary)")->capture_default_str();
  sub->add_option("--reference-edge", options.reference_edge, "tramlines parallel to this edge of the boundary (vertex i to i+1; -1: the longest)")
      ->capture_default_str();
  sub->add_option("--cell", options.cell_m, "cell of the rate grid and step along the passes (m)")->capture_default_str();
  sub->add_flag("--no-section-control", options.no_section_control,
                "every section on over each pass, the feed switched at the pass ends (default: sections off over worked ground and beyond the boundary)");
  sub->add_option("--sections", options.sections, "the machine's sections (1 to 16)")->capture_default_str();
  sub->add_option("--speed", options.speed_km_h, "ground speed (km/h)")->capture_default_str();
  sub->add_option("--look-ahead", options.look_ahead_s, "section control's turn-on and turn-off time (s)")->capture_default_str();
  sub->add_option("--gate-travel", options.gate_travel_s, "a metering gate's time from shut to the field's flow (s)")->capture_default_str();
  sub->add_flag("--border", options.border, "border mode on the outermost round (the border setting of `spread border`, boundary on the right)");
  sub->add_option("--field-wind", options.field_wind, "wind over the field, EAST,NORTH (m/s)")->capture_default_str();
  sub->add_flag("--compare", options.compare, "a table of strategies: section control off/on, border off/on, --bout and --compare-bout, calm and --field-wind");
  sub->add_option("--compare-bout", options.compare_bout_m, "the second bout width of --compare (m)")->capture_default_str();
  sub->add_option("--grid", options.grid, "write the as-applied grid as CSV (cell centres in the boundary's CRS, kg/ha)");
  sub->add_option("--map", options.map, "draw the as-applied map (PNG): rate of the target, boundary, passes, legend; "
                                        "with --compare one per run beside it (NAME_sc_border_10m_calm.png)");
  sub->add_flag("--json", options.json, "machine-readable output on stdout");
  sub->callback([&exit_code, sub] {
    apply_scene(*sub, options);
    run(options, exit_code);
  });
}};

}  // namespace
}  // namespace spread::cli::cmd_field
