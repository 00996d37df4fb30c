// spread border --tables FILE --material NAME --rpm R --width W [--edge border|edge] [--side right|left]
//               [--gap M] [--max-beyond PCT] [--tolerance PCT] [--max-over-applied PCT] [--min-edge-rate PCT]
//               [--wind VX,VY]
//               [--drop-point-turn DEG] [--left-/--right-...] [--json]
// The last bout along a field edge: the setting of the edge-side disc (speed, drop point, flow) for
// border spreading (nothing over the edge line: a road, a path, water with --gap 1 or 3) or edge
// spreading (full rate to the edge: another field), and the profile of this pass plus the passes before
// it over every bout the last pass reaches, with the mass beyond the edge line and the under- and
// over-applied strips
// (libspread/analysis/predict/edge_spreading.hpp; docs/field-calibration.md "Border and edge spreading").
// Bad input → a message naming it on stderr, exit code 2, before any work.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/analysis/calibration/machine_scales.hpp"
#include "libspread/analysis/predict/edge_spreading.hpp"
#include "tools/spread/command_registry.hpp"
#include "tools/spread/number_format.hpp"
#include "tools/spread/prediction_args.hpp"
#include "tools/spread/table_session.hpp"

namespace spread::cli::cmd_border {
namespace {

using nlohmann::json;
using spread::cli::BadInput;
namespace pr = spread::predict;

struct Options : spread::cli::PredictionArgs {
  double bout_width_m = 0.0;
  std::string kind = "border";
  std::string side = "right";
  double gap_m = 0.0;
  double max_beyond_percent = 0.1;
  double tolerance_percent = 10.0;
  double min_edge_rate_percent = 80.0;
  double max_over_applied_percent = 5.0;
  double drop_point_range_deg = 90.0;
  bool json = false;
  std::string scales;  // the machine's scales file; "" = none
};

std::string strips_text(std::span<const std::pair<double, double>> strips) {
  std::string text;
  for (const auto& [from, to] : strips) text += (text.empty() ? "" : ", ") + format("%.1f", from) + format(" to %.1f m", to);
  return text.empty() ? "none" : text;
}

json strips_json(std::span<const std::pair<double, double>> strips) {
  json list = json::array();
  for (const auto& [from, to] : strips) list.push_back({from, to});
  return list;
}

json profile_json(const pr::EdgeProfile& p) {
  json rate = json::array(), centres = json::array();
  for (std::size_t k = 0; k < p.rate.size(); ++k) {
    centres.push_back(p.trays.centre_m(static_cast<int>(k)));
    rate.push_back(p.rate[k]);
  }
  return {{"edge_line_m", p.edge_line_m},
          {"mass_beyond_percent", 100.0 * p.mass_beyond_fraction},
          {"max_rate_inside_percent", 100.0 * p.max_rate_inside},
          {"max_rate_field_percent", 100.0 * p.max_rate_field},
          {"rate_at_edge_percent", 100.0 * p.rate_at_edge},
          {"mean_rate_last_bout_percent", 100.0 * p.mean_rate_last_bout},
          {"under_applied_last_bout_m", p.under_applied_last_bout_m},
          {"most_over_applied_bout", p.most_over_applied_bout},
          {"most_over_applied_m", p.most_over_applied_m},
          {"judged_from_m", p.judged_from_m},
          {"over_limit_percent", 100.0 * p.over_limit},
          {"under_limit_percent", 100.0 * p.under_limit},
          {"missing_inside_m", p.missing_inside_m},
          {"under_applied_m", strips_json(p.under_applied_m)},
          {"over_applied_m", strips_json(p.over_applied_m)},
          {"meets", p.meets},
          {"tray_width_m", p.trays.tray_width_m},
          {"centres_m", centres},
          {"rate_fraction", rate}};
}

void print_profile(const char* title, const pr::EdgeProfile& p, double bout_width_m) {
  std::printf("  %s: beyond the edge line %s of this pass's mass; the last bout gets %s of the field's rate on "
              "average, at most %s, %s over the tray width ending at the edge line\n",
              title, format("%.3f %%", 100.0 * p.mass_beyond_fraction).c_str(),
              format("%.0f %%", 100.0 * p.mean_rate_last_bout).c_str(),
              format("%.0f %%", 100.0 * p.max_rate_inside).c_str(), format("%.0f %%", 100.0 * p.rate_at_edge).c_str());
  std::printf("    last bout under-applied (below %s) over %s of its %s\n", format("%.0f %%", 100.0 * p.under_limit).c_str(),
              format("%.1f m", p.under_applied_last_bout_m).c_str(),
              format("%.1f m", p.edge_line_m + 0.5 * bout_width_m).c_str());
  const std::string worst = p.most_over_applied_m <= 0.0 ? std::string("no bout")
                            : p.most_over_applied_bout == 0
                                ? format("the last bout, %.1f m", p.most_over_applied_m)
                                : "bout " + std::to_string(p.most_over_applied_bout) + " before the last" +
                                      format(", %.1f m", p.most_over_applied_m);
  std::printf("    judged from %s to the edge line: highest rate %s; most over-applied (above %s): %s\n",
              format("%.1f m", p.judged_from_m).c_str(), format("%.0f %%", 100.0 * p.max_rate_field).c_str(),
              format("%.0f %%", 100.0 * p.over_limit).c_str(), worst.c_str());
  std::printf("    under-applied strips: %s; over-applied strips: %s\n", strips_text(p.under_applied_m).c_str(),
              strips_text(p.over_applied_m).c_str());
}

void run(const Options& o, int& exit_code) {
  // Everything checked before any work.
  if (!(o.bout_width_m > 0.0) || !std::isfinite(o.bout_width_m)) {
    throw BadInput("--width is required: the bout width (m) whose last tramline lies half of it from the edge");
  }
  pr::EdgeRequest edge;
  if (o.kind == "border") {
    edge.kind = pr::EdgeKind::kBorder;
  } else if (o.kind == "edge") {
    edge.kind = pr::EdgeKind::kEdge;
  } else {
    throw BadInput("--edge '" + o.kind + "': border (nothing over the edge line) or edge (full rate to it)");
  }
  if (o.side != "right" && o.side != "left") throw BadInput("--side '" + o.side + "': right or left");
  edge.side = o.side == "right" ? pr::kRightDisc : pr::kLeftDisc;
  if (!(o.gap_m >= 0.0 && o.gap_m < 0.5 * o.bout_width_m)) {
    throw BadInput("--gap " + format("%g", o.gap_m) + ": from 0 m up to half the bout width (" +
                   format("%g m", 0.5 * o.bout_width_m) + ")");
  }
  edge.gap_m = o.gap_m;
  if (!(o.max_beyond_percent > 0.0 && o.max_beyond_percent <= 100.0)) {
    throw BadInput("--max-beyond " + format("%g", o.max_beyond_percent) + ": a share in (0, 100] %");
  }
  if (!(o.tolerance_percent > 0.0 && o.tolerance_percent <= 100.0)) {
    throw BadInput("--tolerance " + format("%g", o.tolerance_percent) + ": in (0, 100] %");
  }
  if (!(o.min_edge_rate_percent > 0.0 && o.min_edge_rate_percent <= 100.0)) {
    throw BadInput("--min-edge-rate " + format("%g", o.min_edge_rate_percent) + ": in (0, 100] %");
  }
  if (!(o.max_over_applied_percent >= 0.0 && o.max_over_applied_percent <= 100.0)) {
    throw BadInput("--max-over-applied " + format("%g", o.max_over_applied_percent) + ": a share of a bout in [0, 100] %");
  }
  edge.max_over_applied_fraction = o.max_over_applied_percent / 100.0;
  edge.max_beyond_fraction = o.max_beyond_percent / 100.0;
  edge.rate_tolerance = o.tolerance_percent / 100.0;
  edge.min_edge_rate = o.min_edge_rate_percent / 100.0;
  if (!(o.drop_point_range_deg >= 0.0 && o.drop_point_range_deg <= 180.0)) {
    throw BadInput("--drop-point-range " + format("%g", o.drop_point_range_deg) + ": within 0..180 degrees");
  }
  edge.max_drop_point_turn_rad = o.drop_point_range_deg * kRadPerDeg;
  pr::PredictionRequest normal = spread::cli::prediction_request(o);
  normal.bout_width_m = o.bout_width_m;
  std::optional<spread::calibration::DropPointScale> scale;
  if (!o.scales.empty()) scale = spread::calibration::read_machine_scales(o.scales).drop_point;

  spread::cli::TableSession session(o.tables);
  pr::Predictor& predictor = session.predictor();
  if (!predictor.find_material(o.material)) throw BadInput("--material '" + o.material + "' is not in " + o.tables);
  if (predictor.machine().disc_count < 2) throw BadInput(o.tables + ": a one-disc machine has no edge-side disc to set apart");
  const pr::EdgeResult r = pr::find_edge_setting(predictor, normal, edge);
  if (r.status != pr::PredictStatus::kOk) {
    throw BadInput(std::string("the normal setting is refused: ") + pr::to_string(r.status) +
                   (r.status == pr::PredictStatus::kRpmOutsideTable ? " (--rpm outside the table's rows)" : ""));
  }
  const pr::EdgeSetting& s = r.setting;
  const char* side_name = edge.side == pr::kRightDisc ? "right" : "left";
  // A drop point as printed: its turn, and with --scales its mark on the machine's drop-point scale.
  const auto turn_text = [&](double turn_rad) {
    const double turn_deg = turn_rad / kRadPerDeg;
    return format("%+.1f deg", turn_deg) +
           (scale ? " (scale " + spread::calibration::drop_point_mark(*scale, turn_deg) + ")" : std::string());
  };
  const auto mark_json = [&](double turn_rad) {
    return scale && std::isfinite(turn_rad) ? json(spread::calibration::drop_point_mark(*scale, turn_rad / kRadPerDeg))
                                            : json(nullptr);
  };
  if (o.json) {
    json out{{"tables", o.tables},
             {"material", o.material},
             {"edge", pr::to_string(edge.kind)},
             {"side", side_name},
             {"bout_width_m", o.bout_width_m},
             {"gap_m", o.gap_m},
             {"setting", {{"disc", side_name},
                          {"rpm", s.disc.rpm},
                          {"drop_point_turn_deg", s.disc.drop_point_turn_rad / kRadPerDeg},
                          {"drop_point_mark", mark_json(s.disc.drop_point_turn_rad)},
                          {"field_side_drop_point_mark", mark_json(s.field_side_drop_point_turn_rad)},
                          {"flow_percent", 100.0 * s.flow_fraction},
                          // null: the field-side disc keeps the field's drop point
                          {"field_side_drop_point_turn_deg",
                           std::isnan(s.field_side_drop_point_turn_rad)
                               ? json(nullptr)
                               : json(s.field_side_drop_point_turn_rad / kRadPerDeg)}}},
             {"profile", profile_json(r.profile)},
             {"normal_profile", profile_json(r.normal_profile)},
             {"predictions", r.predictions}};
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("%s spreading, the edge on the %s, last tramline %s from the field edge, edge line %s from it\n",
                pr::to_string(edge.kind), side_name, format("%g m", 0.5 * o.bout_width_m).c_str(),
                format("%g m", r.profile.edge_line_m).c_str());
    std::printf("  the %s disc: %s, drop point turned %s, flow %s of normal (%s)\n", side_name,
                format("%.0f rpm", s.disc.rpm).c_str(), turn_text(s.disc.drop_point_turn_rad).c_str(),
                format("%.0f %%", 100.0 * s.flow_fraction).c_str(),
                r.profile.meets ? "meets the thresholds" : "NO setting searched meets the thresholds; the closest");
    if (!std::isnan(s.field_side_drop_point_turn_rad)) {
      const char* other_name = edge.side == pr::kRightDisc ? "left" : "right";
      std::printf("  and the %s disc on this pass: drop point turned %s (its speed and flow as the field's: it throws "
                  "over the line at the field's setting)\n",
                  other_name, turn_text(s.field_side_drop_point_turn_rad).c_str());
    }
    print_profile("with it", r.profile, o.bout_width_m);
    if (!r.profile.meets && edge.kind == pr::EdgeKind::kBorder) {
      // Why not: what reaches over the line with the edge-side disc off.
      pr::EdgeProfile off;
      pr::EdgeSetting none = s;
      none.flow_fraction = 0.0;
      if (pr::edge_profile(predictor, normal, edge, none, off) == pr::PredictStatus::kOk) {
        std::printf("  why: with the %s disc off, %s of this pass's mass still lands beyond the line (the other disc "
                    "and the passes before reach it): move the last tramline in or lower the field's speed\n",
                    side_name, format("%.3f %%", 100.0 * off.mass_beyond_fraction).c_str());
      }
    }
    print_profile("at the normal setting", r.normal_profile, o.bout_width_m);
    std::printf("  (x from the last tramline, towards the edge; rates as a share of the field's; %d predictions)\n",
                r.predictions);
  }
  exit_code = spread::cli::kExitOk;
}

spread::cli::CommandRegistration reg{"border", [](CLI::App& app, int& exit_code) {
  static Options options;
  auto* sub = app.add_subcommand("border", "border and edge spreading: the edge-side disc's setting for the last bout along a field edge");
  spread::cli::add_prediction_args(*sub, options);
  sub->add_option("--width", options.bout_width_m, "bout width (m); the last tramline lies half of it from the field edge");
  sub->add_option("--edge", options.kind, "border (road, path, water: nothing over the edge line) or edge (another field: full rate to the edge)")
      ->capture_default_str();
  sub->add_option("--side", options.side, "side of the edge as the driver sees it: right or left")->capture_default_str();
  sub->add_option("--gap", options.gap_m, "edge line this far inside the field edge (m): water 1 with a border device, 3 without")
      ->capture_default_str();
  sub->add_option("--max-beyond", options.max_beyond_percent, "border: most of this pass's mass beyond the edge line (%)")
      ->capture_default_str();
  sub->add_option("--tolerance", options.tolerance_percent, "inside: over-applied above 100 + this, under-applied below 100 - this (%)")
      ->capture_default_str();
  sub->add_option("--max-over-applied", options.max_over_applied_percent,
                  "of any bout the last pass reaches, at most this much of its width over-applied, none of it by more than the tolerance (%)")
      ->capture_default_str();
  sub->add_option("--min-edge-rate", options.min_edge_rate_percent, "edge: the rate at the edge line at least this of the field's (%)")
      ->capture_default_str();
  sub->add_option("--drop-point-range", options.drop_point_range_deg,
                  "each disc's drop point searched: turns within ± this of the field's setting (degrees)")
      ->capture_default_str();
  sub->add_flag("--json", options.json, "machine-readable output on stdout");
  sub->add_option("--scales", options.scales,
                  "the machine's scales file (TOML): each drop point also on its drop-point scale, e.g. "
                  "scenes/field/default_scales.toml");
  sub->callback([&exit_code] { run(options, exit_code); });
}};

}  // namespace
}  // namespace spread::cli::cmd_border
