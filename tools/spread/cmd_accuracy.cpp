// `spread accuracy`: the accuracy–cost study (libspread/analysis/accuracy). Writes one CSV and PNG
// plots per study into --out and the markdown report (default <out>/accuracy-cost.md). The committed
// docs/accuracy-cost.md is produced by, from the source root:
//   spread accuracy --out docs/accuracy --report docs/accuracy-cost.md
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "libspread/analysis/accuracy/accuracy.hpp"
#include "tools/spread/command_registry.hpp"

namespace spread::cli::cmd_accuracy {
namespace {

namespace accuracy = spread::accuracy;

struct AccuracyOptions {
  bool quick = false;
  std::string out;
  std::string report;
  std::string scene = accuracy::default_scene_path();
  std::string material;
  double rpm = 500.0;
  std::string only;  // comma list of studies; empty = all
  std::string table;  // launch table for the sampling study; empty = that study is left out
  bool verbose = false;
  bool json = false;  // machine-readable summary on stdout instead of the one-line message
};

int run(const AccuracyOptions& o) {
  const std::set<std::string> known{"flight", "dem", "particle_count", "tables", "partition", "sampling"};
  std::set<std::string> wanted;
  std::stringstream list(o.only);
  for (std::string name; std::getline(list, name, ',');) {
    if (!known.count(name)) {
      throw std::invalid_argument("--only: unknown study \"" + name +
                                  "\" (flight, dem, particle_count, tables, partition, sampling)");
    }
    wanted.insert(name);
  }
  auto on = [&](const char* name) { return wanted.empty() || wanted.count(name) > 0; };

  accuracy::StudyOptions so;
  so.quick = o.quick;
  so.scene_path = o.scene;
  so.material = o.material;
  so.rpm = o.rpm;
  so.progress = o.verbose ? &std::cerr : nullptr;
  so.table_path = o.table;
  so.table_path_shown = std::filesystem::path(o.table).filename().string();
  if (wanted.count("sampling") && o.table.empty()) {
    throw std::invalid_argument("--only sampling needs --table (a launch table, e.g. out/default.sqlite of the main job)");
  }
  const std::clock_t cpu_start = std::clock();  // process CPU time: the report's total
  std::vector<accuracy::Study> studies;
  if (on("flight")) studies.push_back(accuracy::flight_study(so));
  if (on("dem")) studies.push_back(accuracy::dem_study(so));
  if (on("particle_count")) studies.push_back(accuracy::particle_count_study(so));
  if (on("tables")) studies.push_back(accuracy::table_study(so));
  if (on("partition")) studies.push_back(accuracy::partition_study(so));
  if (on("sampling") && !o.table.empty()) studies.push_back(accuracy::sampling_study(so));
  const double cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;

  accuracy::write_study_files(studies, o.out);
  const std::string report = o.report.empty() ? o.out + "/accuracy-cost.md" : o.report;
  const auto report_dir = std::filesystem::absolute(report).parent_path();
  std::string prefix = std::filesystem::relative(std::filesystem::absolute(o.out), report_dir).generic_string();
  prefix = (prefix.empty() || prefix == ".") ? "" : prefix + "/";
  std::string command = "spread accuracy";
  if (o.quick) command += " --quick";
  command += " --out " + o.out;
  if (!o.report.empty()) command += " --report " + o.report;
  if (!o.only.empty()) command += " --only " + o.only;
  if (!o.table.empty()) command += " --table " + so.table_path_shown;
  if (o.scene != accuracy::default_scene_path()) command += " --scene " + o.scene;
  if (!o.material.empty()) command += " --material \"" + o.material + "\"";
  if (o.rpm != 500.0) command += " --rpm " + accuracy::cell(o.rpm);
  accuracy::StudyOptions shown = so;
  shown.scene_path = accuracy::scene_display_name(o.scene);
  accuracy::write_report(studies, shown, command, cpu_s, report, prefix);
  if (o.json) {
    // Recommendations (markdown text and the named figures behind them) and every file written.
    nlohmann::json out = {{"command", command}, {"quick", o.quick}, {"cpu_time_s", cpu_s}, {"report", report},
                          {"out", o.out}, {"studies", nlohmann::json::array()}};
    for (const auto& st : studies) {
      nlohmann::json plots = nlohmann::json::array();
      for (const auto& p : st.plots) plots.push_back(o.out + "/" + p.file);
      nlohmann::json figures = nlohmann::json::object();
      for (const auto& [key, value] : st.figures) figures[key] = value;  // NaN (not measured) becomes null
      out["studies"].push_back({{"name", st.name},
                                {"title", st.title},
                                {"csv", o.out + "/" + st.name + ".csv"},
                                {"plots", plots},
                                {"recommendation", st.recommendation},
                                {"figures", figures}});
    }
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << "wrote " << report << " and " << studies.size() << " studies' CSV/PNG in " << o.out << " ("
              << accuracy::cell(cpu_s) << " s CPU)\n";
  }
  return spread::cli::kExitOk;
}

spread::cli::CommandRegistration registration{"accuracy", [](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<AccuracyOptions>();
  auto* sub = app.add_subcommand("accuracy", "Accuracy-cost study: error against time and size, with recommendations");
  sub->add_flag("--quick", options->quick, "Small grids (the test-suite variant, well under a minute)");
  sub->add_option("--out", options->out, "Directory for the CSV and PNG files")->required();
  sub->add_option("--report", options->report, "Markdown report path (default <out>/accuracy-cost.md)");
  sub->add_option("--scene", options->scene, "Scene of the launches and the machine")->capture_default_str();
  sub->add_option("--material", options->material, "Material (default: the scene's [simulate] material)");
  sub->add_option("--rpm", options->rpm, "Disc speed of the flight and particle-count studies (r/min)")
      ->capture_default_str();
  sub->add_option("--only", options->only, "Comma list of studies: flight,dem,particle_count,tables,partition,sampling");
  sub->add_option("--table", options->table,
                  "Launch table for the sampling study (e.g. the main job's out/default.sqlite); without it that study is left out");
  sub->add_flag("--json", options->json, "Machine-readable summary on stdout: recommendations, figures, files");
  sub->add_flag("-v,--verbose", options->verbose, "One progress line per measured point on stderr");
  sub->callback([options, &exit_code] { exit_code = run(*options); });
}};

}  // namespace
}  // namespace spread::cli::cmd_accuracy
