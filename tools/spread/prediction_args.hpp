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
};

// Adds --tables, --material, --rpm (required), --height, --wind, --cv-target, --tray-width and
// --drop-point-turn.
void add_prediction_args(CLI::App& sub, PredictionArgs& args);

// --drop-point-turn in radians; BadInput naming it outside ±180 degrees.
double drop_point_turn_rad(const PredictionArgs& args);

struct WindXY {
  double x_m_s = 0.0;  // lateral, to the right
  double y_m_s = 0.0;  // forward
};

// "VX,VY" in m/s; BadInput naming --wind otherwise.
WindXY parse_wind(const std::string& text);

// The Predictor's request of these arguments (material, rpm, height, wind, CV target, tray width; the
// rest at its defaults). `args` must outlive it (the material is a view).
predict::PredictionRequest prediction_request(const PredictionArgs& args);

}  // namespace spread::cli
