#pragma once
// The arguments that name one prediction, shared by `spread predict` and `spread plot`: the same
// option names, defaults, help texts and parsing, so the two commands cannot drift apart.
#include <CLI/CLI.hpp>

#include <limits>
#include <stdexcept>
#include <string>

#include "libspread/analysis/predict/predictor.hpp"
#include "tools/spread/error_exit.hpp"

namespace spread::cli {

struct PredictionArgs {
  std::string tables;                                           // launch-table file (SQLite)
  std::string material;                                         // name as in the table
  double rpm = 0.0;                                             // disc speed, r/min
  double height_m = std::numeric_limits<double>::quiet_NaN();  // NaN: the table's disc height
  std::string wind = "0,0";                                     // "VX,VY", m/s
  double cv_target_percent = 15.0;                              // CV target of the working widths, %
  double tray_width_m = 0.5;                                    // collecting tray width, m
  double drop_point_turn_deg = 0.0;                             // drop point turned from the table's, degrees
  // Each disc's own (NaN: the both-discs value above), [0] left, [1] right as the driver sees them.
  double disc_rpm[2] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  double disc_drop_point_turn_deg[2] = {std::numeric_limits<double>::quiet_NaN(),
                                        std::numeric_limits<double>::quiet_NaN()};
};

// Adds --tables, --material, --rpm, --height, --wind, --cv-target, --tray-width, --drop-point-turn and
// the per-disc --left-rpm, --right-rpm, --left-drop-point-turn, --right-drop-point-turn.
void add_prediction_args(CLI::App& sub, PredictionArgs& args);

// Radians per degree: the CLI takes and prints angles in degrees, the library works in radians.
inline constexpr double kRadPerDeg = 0.017453292519943295;  // π/180

// The option names of each disc's own settings ([0] left, [1] right).
inline constexpr const char* kDiscRpmOption[2] = {"--left-rpm", "--right-rpm"};
inline constexpr const char* kDiscDropPointOption[2] = {"--left-drop-point-turn", "--right-drop-point-turn"};

// --drop-point-turn in radians; BadInput naming it outside ±180 degrees.
double drop_point_turn_rad(const PredictionArgs& args);
// A disc's own --left/right-drop-point-turn in radians (NaN when not given); BadInput outside ±180 degrees.
double disc_drop_point_turn_rad(const PredictionArgs& args, int disc);
// BadInput unless the speeds are complete and none is unused: --rpm, or both --left-rpm and --right-rpm
// (then without --rpm); likewise --drop-point-turn beside both discs' own.
void check_disc_settings(const PredictionArgs& args);
// The disc (0 left, 1 right) whose speed is outside [min_rpm, max_rpm] and the option that gave it, as
// "--right-rpm 900" (empty when none is).
std::string disc_speed_outside(const PredictionArgs& args, double min_rpm, double max_rpm);

struct WindXY {
  double x_m_s = 0.0;  // lateral, to the right
  double y_m_s = 0.0;  // forward
};

// "VX,VY" in m/s; BadInput naming --wind otherwise.
WindXY parse_wind(const std::string& text);

// The Predictor's request of these arguments (material, rpm, height, wind, CV target, tray width, drop
// point, each disc's own settings; the rest at its defaults). `args` must outlive it (the material is a view).
predict::PredictionRequest prediction_request(const PredictionArgs& args);

}  // namespace spread::cli
