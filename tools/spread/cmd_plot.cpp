// spread plot --tables FILE --material NAME --rpm N --out PREFIX [--what pattern,transverse,cv]
//             [--height M] [--wind VX,VY] [--cv-target PCT] [--tray-width W] [--cell M] [--json]
// PNGs of one prediction: PREFIX_pattern.png (ground pattern of the whole machine), PREFIX_transverse.png
// (trays, with the overlapped profile at the to-and-fro working width), PREFIX_cv.png (CV(W) for
// to-and-fro and racetrack). Masses are per kilogram discharged by the machine (the predictor's mass
// fractions read as kg per kg), so the plots' kg/g axes are "per kg discharged". Uses the C++ predictor directly: the landings a ground pattern needs are not
// part of the C API. Prints the written paths (JSON with --json).
#include <cmath>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/analysis/plot/plot.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "tools/spread/command_registry.hpp"
#include "tools/spread/prediction_args.hpp"
#include "tools/spread/table_session.hpp"

namespace spread::cli::cmd_plot {
namespace {

using nlohmann::json;
using spread::cli::BadInput;

struct Options : spread::cli::PredictionArgs {
  std::string out_prefix;
  std::string what = "pattern,transverse,cv";
  double cell_m = 0.25;
  bool json = false;
};

std::set<std::string> parse_what(const std::string& text) {
  std::set<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item != "pattern" && item != "transverse" && item != "cv") {
      throw BadInput("--what: unknown plot '" + item + "' (known: pattern, transverse, cv)");
    }
    out.insert(item);
  }
  if (out.empty()) throw BadInput("--what: name at least one of pattern, transverse, cv");
  return out;
}

std::string refusal(spread::predict::PredictStatus status, const Options& o,
                    const spread::predict::Predictor& predictor) {
  using S = spread::predict::PredictStatus;
  std::ostringstream out;
  if (status == S::kUnknownMaterial) {
    out << "--material '" << o.material << "' is not in " << o.tables << "; materials:";
    for (std::size_t i = 0; i < predictor.material_count(); ++i) out << " " << predictor.material(i).name;
  } else if (status == S::kRpmOutsideTable) {
    const auto i = *predictor.find_material(o.material);
    out << spread::cli::disc_speed_outside(o, predictor.min_rpm(i), predictor.max_rpm(i))
        << " is outside the table rows of '" << o.material << "' [" << predictor.min_rpm(i) << ", "
        << predictor.max_rpm(i) << "] rpm";
  } else {
    out << to_string(status) << " (check --rpm, --height >= 0, --cv-target > 0, --tray-width in [0.05, 100] m)";
  }
  return out.str();
}

void run(const Options& o, int& exit_code) {
  const auto what = parse_what(o.what);
  if (o.out_prefix.empty()) throw BadInput("--out: give a path prefix for the PNG files");
  if (!(o.cell_m > 0.0) || !std::isfinite(o.cell_m)) throw BadInput("--cell must be a positive number of metres");

  spread::predict::PredictionRequest request = spread::cli::prediction_request(o);

  spread::cli::TableSession session(o.tables);
  spread::predict::Predictor& predictor = session.predictor();
  spread::predict::Prediction p;
  const auto status = predictor.predict(request, p);
  if (status != spread::predict::PredictStatus::kOk) throw BadInput(refusal(status, o, predictor));

  const auto& machine = predictor.machine();
  const spread::metrics::MachineLayout discs{machine.disc_count, machine.disc_spacing_m};
  std::ostringstream title;
  title << o.material << " at " << p.discs[spread::predict::kLeftDisc].rpm;
  if (machine.disc_count == 2 && !(p.discs[spread::predict::kLeftDisc] == p.discs[spread::predict::kRightDisc])) {
    title << " / " << p.discs[spread::predict::kRightDisc].rpm << " rpm (left / right)";
  } else {
    title << " rpm";
  }
  json written = json::object();

  if (what.count("pattern")) {
    // Landings are already in the machine frame (both discs): one "disc" at x = 0 places them as they are.
    const auto pattern = spread::metrics::ground_pattern(p.landing_x_m, p.landing_y_m, p.landing_mass_fraction,
                                                         spread::metrics::MachineLayout{1, 0.0}, o.cell_m);
    const std::string path = o.out_prefix + "_pattern.png";
    spread::plot::write_ground_pattern_png(pattern, path, title.str() + ": ground pattern per kg discharged", discs);
    written["pattern"] = path;
  }
  if (what.count("transverse")) {
    spread::plot::TransverseOptions options;
    options.series_label = "predicted";
    // The overlap is drawn over whole trays: the widest whole number within the working width. Rounded
    // to the nearest (11.31 m on 0.5 m trays to 11.5 m) it showed a bout beyond the working width, with
    // a CV above the target at what the title called the working width.
    const double trays_within = std::floor(p.working_width_to_and_fro_m / p.trays.tray_width_m + 1e-9);
    options.bout_width_m = trays_within >= 2.0 ? trays_within * p.trays.tray_width_m : 0.0;
    options.cv_target = request.cv_target;
    const std::string path = o.out_prefix + "_transverse.png";
    spread::plot::write_transverse_png(p.tray_mass_fraction, p.trays, path,
                                       title.str() + ": transverse distribution per kg discharged", options);
    written["transverse"] = path;
  }
  if (what.count("cv")) {
    std::vector<double> widths;
    for (int n = 2; n <= p.trays.tray_count; ++n) widths.push_back(n * p.trays.tray_width_m);
    std::vector<double> to_and_fro(widths.size()), racetrack(widths.size());
    // To-and-fro with the return pass as it meets the wind (the outgoing pattern itself in still air).
    for (std::size_t i = 0; i < widths.size(); ++i) {
      to_and_fro[i] = spread::metrics::cv_at_trays(p.tray_mass_fraction, p.return_tray_mass_fraction, p.trays,
                                                   static_cast<int>(i) + 2, {});
    }
    spread::metrics::cv_curve(p.tray_mass_fraction, p.trays, widths, spread::metrics::Overlap::kRacetrack, racetrack);
    const std::string path = o.out_prefix + "_cv.png";
    spread::plot::write_cv_curve_png(widths, to_and_fro, racetrack, request.cv_target, path, title.str() + ": CV(W)");
    written["cv"] = path;
  }

  if (o.json) {
    std::cout << json{{"written", written},
                      {"working_width_to_and_fro_m", p.working_width_to_and_fro_m},
                      {"working_width_racetrack_m", p.working_width_racetrack_m},
                      {"throw_width_m", p.throw_width_m}}
                     .dump(2)
              << "\n";
  } else {
    for (const auto& [kind, path] : written.items()) std::cout << path.get<std::string>() << "\n";
  }
  exit_code = spread::cli::kExitOk;
}

spread::cli::CommandRegistration reg{"plot", [](CLI::App& app, int& exit_code) {
  static Options options;
  auto* sub = app.add_subcommand("plot", "PNG plots of a prediction: ground pattern, transverse distribution, CV(W)");
  spread::cli::add_prediction_args(*sub, options);
  sub->add_option("--out", options.out_prefix, "path prefix of the PNG files (PREFIX_pattern.png, ...)")->required();
  sub->add_option("--what", options.what, "plots to write: pattern,transverse,cv");
  sub->add_option("--cell", options.cell_m, "ground-pattern cell size (m)");
  sub->add_flag("--json", options.json, "machine-readable output on stdout");
  sub->callback([&exit_code] { run(options, exit_code); });
}};

}  // namespace
}  // namespace spread::cli::cmd_plot
