#include "libspread/analysis/calibration/calibrated_table.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "libspread/analysis/calibration/scene_of_run.hpp"
#include "libspread/physics/launch/launch_statistics.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"

namespace spread::calibration {
namespace {

namespace fs = std::filesystem;

std::string format_parameters(const PatternParameters& p) {
  char text[160];
  std::snprintf(text, sizeof text, "calibrated_friction_wall=%.4f,drag_diameter_factor=%.4f,launch_angle_offset_deg=%.3f",
                p.friction_wall, p.drag_diameter_factor, p.launch_angle_offset_rad * 180.0 / kPi);
  std::string out = text;
  if (p.launch_speed_factor != 1.0 || p.launch_elevation_offset_rad != 0.0) {
    std::snprintf(text, sizeof text, ",launch_speed_factor=%.4f,launch_elevation_offset_deg=%.3f", p.launch_speed_factor,
                  p.launch_elevation_offset_rad * 180.0 / kPi);
    out += text;
  }
  return out;
}

}  // namespace

std::vector<double> non_analytic_rows(const tables::TableContents& contents, const std::string& material) {
  std::vector<double> rpm;
  for (const tables::Run& run : contents.runs) {
    if (run.material == material && run.source != "analytic") rpm.push_back(run.rpm);
  }
  return rpm;
}

std::string calibrated_material_name(const std::string& material, const std::string& date_yyyy_mm_dd) {
  return material + " (calibrated " + date_yyyy_mm_dd + ")";
}

std::string tagged_material_name(const std::string& material, const std::string& tag) {
  const std::string prefix = material + " (";
  const bool tagged = tag.size() > prefix.size() && tag.compare(0, prefix.size(), prefix) == 0 && tag.back() == ')';
  return tagged ? tag : prefix + tag + ")";
}

CalibratedTableSummary write_calibrated_table(const CalibratedTableRequest& request) {
  check_parameters(request.parameters);
  if (request.output_path.empty()) throw std::invalid_argument("output table: no path given");
  std::error_code ec;
  if (fs::exists(request.output_path, ec)) {
    throw std::invalid_argument("output table " + request.output_path +
                                " exists: a calibration writes a new file and never overwrites one");
  }
  // Reading validates the original (ours, right version, not corrupt) before anything is written.
  const tables::TableContents contents = tables::read_table_file(request.original_path);
  const tables::Material* base = nullptr;
  for (const tables::Material& m : contents.materials) {
    if (m.name == request.material) base = &m;
    if (m.name == request.new_material_name) {
      throw std::invalid_argument("material '" + request.new_material_name + "' is already in " + request.original_path);
    }
  }
  if (base == nullptr) throw std::invalid_argument("material '" + request.material + "' is not in " + request.original_path);
  std::vector<const tables::Run*> rows;
  for (const tables::Run& run : contents.runs) {
    if (run.material == request.material) rows.push_back(&run);
  }
  if (rows.empty()) throw std::invalid_argument("material '" + request.material + "' has no runs to rebuild");
  const std::vector<double> dem_rpm = non_analytic_rows(contents, request.material);

  const tables::Material calibrated = calibrated_material(*base, request.parameters, request.new_material_name);
  // Build every run before touching the disk: a model failure leaves no partial file behind.
  std::vector<tables::Run> runs;
  for (const tables::Run* original : rows) {
    const bool analytic = original->source == "analytic" || request.allow_analytic_for_dem;
    PatternSetup setup = pattern_setup_from_table(contents, request.material, original->rpm, analytic);
    tables::Run run;
    run.material = request.new_material_name;
    run.rpm = original->rpm;
    if (analytic) {
      run.source = "analytic";
      run.samples = calibrated_launch_samples(setup, request.parameters, original->rpm,
                                              static_cast<int>(original->samples.size()));
      run.effects = std::string("analytic_vane_sliding,spin_") + scene::to_string(setup.spin_model) + "," +
                    format_parameters(request.parameters) + (original->source == "analytic" ? "" : ",replaces_dem_run");
    } else {
      // The DEM row's own granules, every one of them, with the fitted launch correction: the row stays a
      // DEM row (interpolated by quantile cells, its scatter kept).
      run.source = original->source;
      run.samples = corrected_launch_samples(original->samples, request.parameters, contents.machine.rotation_sense);
      run.effects = original->effects + (original->effects.empty() ? "" : ",") + format_parameters(request.parameters);
    }
    run.scene_text = original->scene_text;
    run.scene_hash = original->scene_hash;
    run.particle_count = static_cast<std::int64_t>(run.samples.size());
    run.software_version = SPREAD_VERSION_STRING;
    run.created_utc = tables::utc_now_iso8601();
    const double rim_speed_m_s = original->rpm * 2.0 * kPi / 60.0 * contents.machine.disc_radius_m;
    // The flight effects the original row's launches are flown with travel with the new row: predict
    // flies a row with its recorded effects (all of them when none is recorded).
    nlohmann::json stats = nlohmann::json::parse(launch::to_json(launch::launch_statistics(run.samples, rim_speed_m_s)));
    if (const std::optional<std::string> effects = tables::recorded_flight_effects(*original)) {
      stats["flight_effects"] = *effects;
    }
    run.stats_json = stats.dump();
    run.convergence_json = "[]";
    runs.push_back(std::move(run));
  }

  fs::copy_file(request.original_path, request.output_path, fs::copy_options::none, ec);
  if (ec) {
    throw tables::TableError(tables::TableErrorKind::kIo,
                             "cannot copy " + request.original_path + " to " + request.output_path + ": " + ec.message());
  }
  CalibratedTableSummary summary;
  summary.output_path = request.output_path;
  summary.material = request.new_material_name;
  if (request.allow_analytic_for_dem) summary.replaced_dem_rpm = dem_rpm;
  try {
    tables::TableWriter writer(request.output_path);
    writer.write_materials({calibrated});
    writer.write_meta("calibration:" + request.new_material_name, request.calibration_json);
    for (const tables::Run& run : runs) {
      writer.write_run(run);
      summary.rpm_rows.push_back(run.rpm);
    }
  } catch (...) {
    fs::remove(request.output_path, ec);
    fs::remove(request.output_path + "-journal", ec);
    throw;
  }
  summary.samples_per_run = static_cast<int>(runs.front().samples.size());
  return summary;
}

}  // namespace spread::calibration
