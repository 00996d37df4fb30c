#pragma once
// The accuracy–cost study: for each numerical knob of the product — flight integrator and
// step, DEM steps per contact N_c and mesh size ξ, simulated particle count, table rpm spacing and
// samples per run, partitioned vs monolithic DEM — measure the error against a tight reference and
// the cost (wall time, bytes), and name the cheapest setting within 1 % error.
//
// Every study returns the same plain shape (Study): a table that becomes a CSV, plots, a
// recommendation, and a few named figures (`figures`) that the tests assert on. `spread accuracy`
// (tools/spread/cmd_accuracy.cpp) runs them all and writes docs/accuracy-cost.md with write_report().
// Timings are wall-clock medians from this one process: on a shared machine compare rows of one run only.
#include <cmath>
#include <limits>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace spread::accuracy {

inline constexpr double kErrorBudget = 0.01;  // "within 1 %": relative error the recommendation accepts

struct StudyOptions {
  bool quick = false;            // small grids: the test-suite variant (well under a minute)
  std::string scene_path;        // launches, machine and material (scenes/default.toml)
  std::string material;          // empty: the scene's [simulate] material
  double rpm = 500.0;            // disc speed of the flight and particle-count studies (r/min)
  std::ostream* progress = nullptr;  // one line per measured point; nullptr = silent
  // Sampling study only: a launch table file (e.g. the main job's DEM table), how the report names it,
  // and the rpm of the row it cuts into subsets (the material's row closest to it).
  std::string table_path;
  std::string table_path_shown;
  double sampling_rpm = 600.0;           // r/min
};

struct Series {
  std::string label;
  std::vector<double> x, y;
};

// A log–log (or lin–log) line plot of error against cost.
struct Plot {
  std::string file;              // PNG name, e.g. "flight.png"
  std::string title, x_label, y_label;
  bool log_x = true, log_y = true;
  std::vector<Series> series;
  double threshold_y = std::numeric_limits<double>::quiet_NaN();  // dashed line (the 1 % budget)
};

struct Study {
  std::string name;              // "flight", "dem", ... (CSV file <name>.csv)
  std::string title;             // section heading of the report
  std::string method;            // markdown: what was measured against what
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;  // formatted cells, one per column
  std::vector<Plot> plots;
  std::string recommendation;    // markdown: the cheapest setting within the budget, and the default
  std::map<std::string, double> figures;  // named numbers for tests and the summary
};

Study flight_study(const StudyOptions& options);
Study dem_study(const StudyOptions& options);
Study particle_count_study(const StudyOptions& options);
Study table_study(const StudyOptions& options);
Study partition_study(const StudyOptions& options);
// Needs options.table_path (throws std::invalid_argument without it).
Study sampling_study(const StudyOptions& options);

// <dir>/<name>.csv and the plots' PNGs for every study, and <dir>/<report_name> (markdown, plots linked
// relative to the report: `image_prefix` + file). Throws std::runtime_error naming a file it cannot write.
void write_study_files(const std::vector<Study>& studies, const std::string& dir);
void write_report(const std::vector<Study>& studies, const StudyOptions& options, const std::string& command,
                  double total_wall_s, const std::string& path, const std::string& image_prefix);

// scenes/default.toml of the source tree this library was built from.
std::string default_scene_path();

// A scene path as the report shows it: relative to that source tree when inside it (the committed
// report must not name the machine it was generated on), else as given.
std::string scene_display_name(const std::string& path);

// Cell formatting shared by the studies: %.4g, or "—" for NaN.
std::string cell(double value);

}  // namespace spread::accuracy
