#include "lookup_builder/table_build.hpp"

#include <chrono>
#include <cstdio>

#include "libspread/tables/table_writer.hpp"
#include "lookup_builder/run_source.hpp"

namespace spread::lookup {
namespace {

tables::Machine table_machine(const scene::Machine& m) {
  tables::Machine out;
  out.name = m.name;
  out.disc_radius_m = m.disc_radius_m;
  out.disc_height_m = m.disc_height_m;
  out.disc_spacing_m = m.disc_spacing_m;
  out.disc_count = m.disc_count;
  out.vane_count = m.vane_count;
  out.cone_angle_rad = m.cone_angle_rad;
  out.rotation_sense = m.rotation_sense;
  return out;
}

std::string format_rpm(double rpm) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", rpm);
  return text;
}

}  // namespace

BuildSummary build_tables(const scene::Scene& scene, const BuildOptions& options) {
  BuildSummary summary;
  summary.output_path = options.output_path.empty() ? scene.sweep.output : options.output_path;
  const RunSource source = make_run_source(scene);  // refuses unavailable sources before any write

  const std::vector<const scene::Material*> materials = scene.sweep_materials();
  const std::vector<double> rpms = scene.sweep_rpms();
  tables::TableWriter writer(summary.output_path);
  writer.write_machine(table_machine(scene.machine));
  std::vector<tables::Material> rows;
  for (const scene::Material* m : materials) rows.push_back(*m);
  writer.write_materials(rows);
  writer.write_meta("machine_scene_hash", scene.hash());

  const int total = static_cast<int>(materials.size() * rpms.size());
  int index = 0;
  for (const scene::Material* material : materials) {
    for (double rpm : rpms) {
      ++index;
      const std::string label = "[" + std::to_string(index) + "/" + std::to_string(total) + "] " + material->name +
                                " @ " + format_rpm(rpm) + " rpm";
      if (!options.rebuild && writer.has_run(material->name, rpm)) {
        ++summary.runs_skipped;
        if (options.progress != nullptr) *options.progress << label << ": exists, skipped\n" << std::flush;
        continue;
      }
      const auto start = std::chrono::steady_clock::now();
      const tables::Run run = source(*material, rpm);
      writer.write_run(run, options.rebuild);
      ++summary.runs_written;
      if (options.progress != nullptr) {
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char timing[48];
        std::snprintf(timing, sizeof timing, "%.3f s", seconds);
        *options.progress << label << ": " << run.samples.size() << " samples (" << run.source << ", " << timing
                          << ")\n"
                          << std::flush;
      }
    }
  }
  return summary;
}

}  // namespace spread::lookup
