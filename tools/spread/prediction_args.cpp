#include "tools/spread/prediction_args.hpp"

#include "libspread/core/strict_number.hpp"
#include "tools/spread/number_format.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace spread::cli {

void add_prediction_args(CLI::App& sub, PredictionArgs& args) {
  sub.add_option("--tables", args.tables, "launch-table file (SQLite) written by lookup_builder")->required();
  sub.add_option("--material", args.material, "material name as in the table")->required();
  sub.add_option("--rpm", args.rpm,
                 "disc speed (r/min) of both discs, within the material's table rows; required unless both "
                 "--left-rpm and --right-rpm are given");
  sub.add_option("--height", args.height_m, "disc height above the ground (m); default: the table's");
  sub.add_option("--wind", args.wind, "wind VX,VY (m/s; x lateral to the right, y forward)");
  sub.add_option("--cv-target", args.cv_target_percent, "CV target for the working widths (%)");
  sub.add_option("--tray-width", args.tray_width_m, "collecting tray width (m)");
  sub.add_option("--drop-point-turn", args.drop_point_turn_deg,
                 "drop point turned from the table's (degrees, counter-clockwise from above on the left disc, "
                 "mirrored on the right), within ±180");
  const char* side[2] = {"left", "right"};
  for (int d = 0; d < 2; ++d) {
    sub.add_option(kDiscRpmOption[d], args.disc_rpm[d],
                   std::string("the ") + side[d] + " disc's own speed (r/min; as the driver sees it), instead of --rpm");
    sub.add_option(kDiscDropPointOption[d], args.disc_drop_point_turn_deg[d],
                   std::string("the ") + side[d] + " disc's own drop-point turn (degrees, as --drop-point-turn for that "
                   "disc), instead of --drop-point-turn");
  }
}

double disc_drop_point_turn_rad(const PredictionArgs& args, int disc) {
  const double deg = args.disc_drop_point_turn_deg[disc];
  if (std::isnan(deg)) return deg;
  if (!std::isfinite(deg) || std::abs(deg) > 180.0) {
    throw BadInput(std::string(kDiscDropPointOption[disc]) + " " + std::to_string(deg) +
                   ": the drop point turns within -180..180 degrees of the table's");
  }
  return deg * kRadPerDeg;
}

void check_disc_settings(const PredictionArgs& args) {
  const bool both_rpm = !std::isnan(args.disc_rpm[0]) && !std::isnan(args.disc_rpm[1]);
  if (!both_rpm && args.rpm == 0.0) {
    throw BadInput("--rpm is required (or both --left-rpm and --right-rpm)");
  }
  if (both_rpm && args.rpm != 0.0) {
    throw BadInput("--rpm " + format("%g", args.rpm) + " would be unused: both --left-rpm and --right-rpm are given");
  }
  const bool both_turns = !std::isnan(args.disc_drop_point_turn_deg[0]) && !std::isnan(args.disc_drop_point_turn_deg[1]);
  if (both_turns && args.drop_point_turn_deg != 0.0) {
    throw BadInput("--drop-point-turn " + format("%g", args.drop_point_turn_deg) +
                   " would be unused: both --left-drop-point-turn and --right-drop-point-turn are given");
  }
}

std::string disc_speed_outside(const PredictionArgs& args, double min_rpm, double max_rpm) {
  for (int d = 0; d < 2; ++d) {
    const bool own = !std::isnan(args.disc_rpm[d]);
    const double rpm = own ? args.disc_rpm[d] : args.rpm;
    if (!(rpm >= min_rpm && rpm <= max_rpm)) {
      return std::string(own ? kDiscRpmOption[d] : "--rpm") + " " + format("%g", rpm);
    }
  }
  return {};
}

double drop_point_turn_rad(const PredictionArgs& args) {
  if (!std::isfinite(args.drop_point_turn_deg) || std::abs(args.drop_point_turn_deg) > 180.0) {
    throw BadInput("--drop-point-turn " + std::to_string(args.drop_point_turn_deg) +
                   ": the drop point turns within -180..180 degrees of the table's");
  }
  return args.drop_point_turn_deg * kRadPerDeg;
}

WindXY parse_wind(const std::string& text) {
  std::vector<double> components;
  std::string_view bad;
  if (!parse_number_list(text, components, bad) || components.size() != 2) {
    throw BadInput("--wind '" + text + "': expected VX,VY in m/s, e.g. --wind 2,-1");
  }
  return WindXY{components[0], components[1]};
}

predict::PredictionRequest prediction_request(const PredictionArgs& args) {
  predict::PredictionRequest request;
  request.material = args.material;
  request.rpm = args.rpm;
  request.disc_height_m = args.height_m;
  const WindXY wind = parse_wind(args.wind);
  request.wind_x_m_s = wind.x_m_s;
  request.wind_y_m_s = wind.y_m_s;
  request.cv_target = args.cv_target_percent / 100.0;
  request.tray_width_m = args.tray_width_m;
  request.drop_point_turn_rad = drop_point_turn_rad(args);
  check_disc_settings(args);
  for (int d = 0; d < 2; ++d) {
    request.disc_rpm[static_cast<std::size_t>(d)] = args.disc_rpm[d];
    request.disc_drop_point_turn_rad[static_cast<std::size_t>(d)] = disc_drop_point_turn_rad(args, d);
  }
  return request;
}

}  // namespace spread::cli
