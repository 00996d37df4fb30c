#include "tools/spread/prediction_args.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace spread::cli {

void add_prediction_args(CLI::App& sub, PredictionArgs& args) {
  sub.add_option("--tables", args.tables, "launch-table file (SQLite) written by lookup_builder")->required();
  sub.add_option("--material", args.material, "material name as in the table")->required();
  sub.add_option("--rpm", args.rpm, "disc speed (r/min), within the material's table rows")->required();
  sub.add_option("--height", args.height_m, "disc height above the ground (m); default: the table's");
  sub.add_option("--wind", args.wind, "wind VX,VY (m/s; x lateral to the right, y forward)");
  sub.add_option("--cv-target", args.cv_target_percent, "CV target for the working widths (%)");
  sub.add_option("--tray-width", args.tray_width_m, "collecting tray width (m)");
  sub.add_option("--drop-point-turn", args.drop_point_turn_deg,
                 "drop point turned from the table's (degrees, counter-clockwise from above on the left disc, "
                 "mirrored on the right), within ±180");
}

double drop_point_turn_rad(const PredictionArgs& args) {
  if (!std::isfinite(args.drop_point_turn_deg) || std::abs(args.drop_point_turn_deg) > 180.0) {
    throw BadInput("--drop-point-turn " + std::to_string(args.drop_point_turn_deg) +
                   ": the drop point turns within -180..180 degrees of the table's");
  }
  return args.drop_point_turn_deg * std::numbers::pi / 180.0;
}

WindXY parse_wind(const std::string& text) {
  std::istringstream in(text);
  WindXY wind;
  char comma = 0;
  if (!(in >> wind.x_m_s >> comma >> wind.y_m_s) || comma != ',' || !(in >> std::ws).eof()) {
    throw BadInput("--wind '" + text + "': expected VX,VY in m/s, e.g. --wind 2,-1");
  }
  return wind;
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
  return request;
}

}  // namespace spread::cli
