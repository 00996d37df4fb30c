// spread inspect FILE [--json]: what a launch-table file holds — machine, materials with their rpm
// rows and sample counts, provenance and statistics of every run. A file that cannot be used gets one
// clear message per TableErrorKind (exit 2).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "libspread/analysis/predict/landing_grid.hpp"
#include "libspread/analysis/size_classes/launch_sizes.hpp"
#include "libspread/io/tables/material_schema.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "tools/spread/command_registry.hpp"
#include "tools/spread/error_exit.hpp"
#include "tools/spread/table_session.hpp"

namespace spread::cli::cmd_inspect {
namespace {

using nlohmann::json;
using spread::tables::TableErrorKind;

// The user-facing explanation of each kind, after the reader's own message (which names the file).
const char* advice(TableErrorKind kind) {
  switch (kind) {
    case TableErrorKind::kMissing: return "check the path";
    case TableErrorKind::kNotOurs: return "this is not a launch-table file written by lookup_builder";
    case TableErrorKind::kCorrupt: return "the file is damaged; rebuild it with lookup_builder --rebuild";
    case TableErrorKind::kWrongVersion: return "written by another libspread format version; rebuild it with this version";
    case TableErrorKind::kEmpty: return "no runs yet; run lookup_builder on the scene";
    case TableErrorKind::kIo: return "the file could not be read (locked, permissions)";
    case TableErrorKind::kScene:
    case TableErrorKind::kArgument: break;  // not a file's kinds
  }
  return "";
}

const char* kind_code(TableErrorKind kind) {
  switch (kind) {
    case TableErrorKind::kMissing: return "missing";
    case TableErrorKind::kNotOurs: return "not_ours";
    case TableErrorKind::kCorrupt: return "corrupt";
    case TableErrorKind::kWrongVersion: return "wrong_version";
    case TableErrorKind::kEmpty: return "empty";
    case TableErrorKind::kIo: return "io";
    case TableErrorKind::kScene: return "scene";
    case TableErrorKind::kArgument: return "argument";
  }
  return "unknown";
}

json parse_or_text(const std::string& text) {
  json parsed = json::parse(text, nullptr, /*allow_exceptions=*/false);
  return parsed.is_discarded() ? json(text) : parsed;
}

// The size guide number and uniformity index of a material's launch samples, its rows pooled: the sheet's
// figures for a sieve material (to within sampling), what a sieve test would give for a lognormal one.
spread::size_classes::LaunchSizes material_sizes(const spread::tables::TableContents& c, const std::string& material) {
  std::vector<spread::tables::LaunchSample> samples;
  for (const auto& run : c.runs) {
    if (run.material == material) samples.insert(samples.end(), run.samples.begin(), run.samples.end());
  }
  return spread::size_classes::launch_sizes(samples);
}

json to_json(const spread::tables::TableContents& c, const std::string& path) {
  json out;
  out["file"] = path;
  out["format_version"] = c.format_version;
  out["record_layout"] = spread::tables::kSampleLayout;
  const auto& m = c.machine;
  out["machine"] = {{"name", m.name},
                    {"disc_radius_m", m.disc_radius_m},
                    {"disc_height_m", m.disc_height_m},
                    {"disc_spacing_m", m.disc_spacing_m},
                    {"disc_count", m.disc_count},
                    {"vane_count", m.vane_count},
                    {"cone_angle_rad", m.cone_angle_rad},
                    {"rotation_sense", m.rotation_sense}};
  json materials = json::array();
  for (const auto& mat : c.materials) {
    json rpm = json::array(), counts = json::array();
    for (const auto& run : c.runs) {
      if (run.material != mat.name) continue;
      rpm.push_back(run.rpm);
      counts.push_back(run.samples.size());
    }
    json entry = {{"name", mat.name}};
    for (const auto& q : spread::tables::kMaterialQuantities) entry[std::string(q.name)] = mat.*q.member;
    const spread::size_classes::LaunchSizes sizes = material_sizes(c, mat.name);
    entry["size_guide_number"] = sizes.size_guide_number;
    entry["uniformity_index"] = sizes.uniformity_index;
    entry["d50_mm"] = sizes.d50_mm;
    entry["rpm"] = rpm;
    entry["sample_counts"] = counts;
    materials.push_back(std::move(entry));
  }
  out["materials"] = materials;
  json runs = json::array();
  for (const auto& run : c.runs) {
    runs.push_back({{"material", run.material},
                    {"rpm", run.rpm},
                    {"sample_count", run.samples.size()},
                    {"source", run.source},
                    {"effects", run.effects},
                    {"dt_contact_s", run.dt_contact_s},
                    {"dt_flight_s", run.dt_flight_s},
                    {"particle_count", run.particle_count},
                    {"scene_hash", run.scene_hash},
                    {"software_version", run.software_version},
                    {"created_utc", run.created_utc},
                    {"stats", parse_or_text(run.stats_json)},
                    {"convergence", parse_or_text(run.convergence_json)}});
  }
  out["runs"] = runs;
  return out;
}

void print_text(const spread::tables::TableContents& c, const std::string& path) {
  const auto& m = c.machine;
  std::cout << path << ": launch table, format version " << c.format_version << "\n"
            << "machine " << m.name << ": R " << m.disc_radius_m << " m, height " << m.disc_height_m << " m, "
            << m.disc_count << " disc(s) " << m.disc_spacing_m << " m apart, " << m.vane_count << " vanes, cone "
            << m.cone_angle_rad << " rad, rotation sense " << (m.rotation_sense > 0 ? "+1" : "-1") << "\n";
  // What predictions answer from the landing grid (predict refuses beyond it, --fly-outside-domain flies).
  const auto domain = spread::predict::landing_domain_for(m.disc_height_m);
  std::cout << "landing grid: disc heights " << domain.min_disc_height_m << "-" << domain.max_disc_height_m
            << " m, winds up to " << domain.max_wind_m_s << " m/s, for materials whose runs fly drag alone\n";
  for (const auto& mat : c.materials) {
    std::cout << "material \"" << mat.name << "\": " << mat.density_kg_m3 << " kg/m3, d " << mat.diameter_mean_m
              << " m (sd " << mat.diameter_sd_m << "), mu_wall " << mat.friction_wall << "\n";
    const spread::size_classes::LaunchSizes sizes = material_sizes(c, mat.name);
    std::cout << "  launched granules by mass: SGN " << std::lround(sizes.size_guide_number) << ", UI "
              << std::lround(sizes.uniformity_index) << " (d50 " << sizes.d50_mm << " mm)\n";
    for (const auto& run : c.runs) {
      if (run.material != mat.name) continue;
      std::cout << "  " << std::setw(7) << run.rpm << " rpm  " << std::setw(6) << run.samples.size()
                << " samples  " << run.source << "  scene " << run.scene_hash << "  v" << run.software_version
                << "  " << run.created_utc << "\n    stats " << run.stats_json << "\n";
    }
  }
}

spread::cli::CommandRegistration reg{"inspect", [](CLI::App& app, int& exit_code) {
  struct Options {
    std::string file;
    bool json = false;
  };
  static Options options;
  auto* sub = app.add_subcommand("inspect", "show what a launch-table file holds (machine, materials, rpm rows, provenance)");
  sub->add_option("file", options.file, "table file (SQLite) written by lookup_builder")->required();
  sub->add_flag("--json", options.json, "machine-readable output on stdout");
  sub->callback([&exit_code] {
    try {
      const spread::cli::TableSession session(options.file, "");
      const spread::tables::TableContents& contents = session.contents();
      if (options.json) {
        std::cout << to_json(contents, options.file).dump(2) << "\n";
      } else {
        print_text(contents, options.file);
      }
      exit_code = spread::cli::kExitOk;
    } catch (const spread::tables::TableError& e) {
      // The JSON reader gets the error on stdout too; stderr and the exit code are main()'s, as for every
      // command, with the advice for this kind of damage.
      if (options.json) {
        std::cout << json{{"error", {{"kind", kind_code(e.kind())}, {"message", e.what()}, {"file", options.file}}}}.dump(2)
                  << "\n";
      }
      throw spread::Error(e.kind(), e.where(), std::string(e.what()) + " (" + advice(e.kind()) + ")");
    }
  });
}};

}  // namespace
}  // namespace spread::cli::cmd_inspect
