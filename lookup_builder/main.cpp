// lookup_builder SCENE [--output FILE] [--set key=value]... [--rebuild]
// Builds the launch-table file of a scene's machine: every material × rpm of [sweep].
// Exit codes: 0 done, 2 bad input (scene, overrides, output file not ours), 1 a run failed.
#include <CLI/CLI.hpp>

#include <iostream>

#include "libspread/tables/table_format.hpp"
#include "lookup_builder/run_source.hpp"
#include "lookup_builder/table_build.hpp"

int main(int argc, char** argv) {
  CLI::App app{"lookup_builder: build launch tables (SQLite) for a machine from a scene (libspread " SPREAD_VERSION_STRING
               ")"};
  app.set_version_flag("--version", SPREAD_VERSION_STRING);
  std::string scene_path;
  std::string output;
  std::vector<std::string> overrides;
  bool rebuild = false;
  app.add_option("scene", scene_path, "scene file (TOML), see docs/scene-format.md")->required();
  app.add_option("--output,-o", output, "table file to create or extend (default: sweep.output of the scene)");
  app.add_option("--set", overrides, "override a scene value: dotted.key=value (repeatable)");
  app.add_flag("--rebuild", rebuild, "redo runs that already exist in the output file");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }

  try {
    const spread::scene::Scene scene = spread::scene::load_scene_file(scene_path, overrides);
    spread::lookup::BuildOptions options;
    options.output_path = output;
    options.rebuild = rebuild;
    options.progress = &std::cerr;
    const auto summary = spread::lookup::build_tables(scene, options);
    std::cerr << "lookup_builder: " << summary.output_path << ": " << summary.runs_written << " runs written, "
              << summary.runs_skipped << " skipped\n";
    return 0;
  } catch (const spread::scene::SceneError& e) {
    std::cerr << "lookup_builder: error: " << e.what() << "\n";
    return 2;
  } catch (const spread::lookup::SourceUnavailableError& e) {
    std::cerr << "lookup_builder: error: " << e.what() << "\n";
    return 2;
  } catch (const spread::tables::TableError& e) {
    std::cerr << "lookup_builder: error: " << e.what() << "\n";
    return e.kind() == spread::tables::TableErrorKind::kIo ? 1 : 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "lookup_builder: error: " << scene_path << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "lookup_builder: error: " << e.what() << "\n";
    return 1;
  }
}
