#include "tests/predict/synthetic_table.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "libspread/core/vec3.hpp"
#include "libspread/io/tables/table_writer.hpp"

namespace spread::testing {

tables::Machine synthetic_machine(int disc_count) {
  tables::Machine m;
  m.name = "synthetic twin disc";
  m.disc_radius_m = 0.3;
  m.disc_height_m = 0.8;
  m.disc_spacing_m = disc_count == 2 ? 1.0 : 0.0;
  m.disc_count = disc_count;
  m.vane_count = 4;
  m.cone_angle_rad = 0.0;
  m.rotation_sense = 1;
  return m;
}

std::vector<tables::LaunchSample> synthetic_samples(double rpm, int count, double density_kg_m3) {
  std::vector<tables::LaunchSample> samples(static_cast<std::size_t>(count));
  // Radial exit speed / ωR from Patterson & Reece for μ ≈ 0.35, slightly rpm dependent so that rows
  // differ after normalisation.
  const double radial_norm = std::sqrt(1.0 + 0.35 * 0.35) - 0.35 + 1e-4 * (rpm - 600.0);
  for (int k = 0; k < count; ++k) {
    const double u = (k + 0.5) / count;
    // Left disc, counter-clockwise: launch points over a 153° arc of the rim whose throws fan out from
    // the left, through the rear, to the right across the centre line (overlap of the two discs).
    const double phi = kPi * (0.75 + 0.85 * u);
    const double c = std::cos(phi), s = std::sin(phi);
    auto& out = samples[static_cast<std::size_t>(k)];
    out.x_m = static_cast<float>(0.3 * c);
    out.y_m = static_cast<float>(0.3 * s);
    out.z_m = 0.0f;
    out.t_s = static_cast<float>(0.05 + 0.01 * u);
    // radial r̂ = (c, s), tangential (CCW) t̂ = (−s, c)
    out.vx_norm = static_cast<float>(radial_norm * c - s);
    out.vy_norm = static_cast<float>(radial_norm * s + c);
    out.vz_norm = 0.02f;
    out.wx_norm = 0.0f;
    out.wy_norm = 0.0f;
    out.wz_norm = 0.5f;
    // Diameters 2.4–3.6 mm, cycling through the arc so every angle sees several sizes.
    const double d = 2.4e-3 + 1.2e-3 * std::fmod(k * 0.618033988749895, 1.0);
    out.diameter_m = static_cast<float>(d);
    out.mass_kg = static_cast<float>(density_kg_m3 * kPi * d * d * d / 6.0);
  }
  return samples;
}

std::vector<SyntheticMaterial> default_synthetic_materials() {
  return {SyntheticMaterial{"can", 1800.0, {500.0, 600.0, 700.0, 800.0}, 256, -1},
          SyntheticMaterial{"urea", 1330.0, {500.0, 700.0}, 256, 200}};
}

namespace {

tables::Material material_row(const SyntheticMaterial& m) {
  tables::Material row;
  row.name = m.name;
  row.density_kg_m3 = m.density_kg_m3;
  row.diameter_mean_m = 3e-3;
  row.diameter_sd_m = 0.35e-3;
  row.friction_wall = 0.35;
  row.friction_particle = 0.4;
  row.restitution = 0.5;
  row.youngs_modulus_pa = 1e8;
  row.poisson_ratio = 0.25;
  row.rolling_friction = 0.01;
  return row;
}

}  // namespace

tables::TableContents synthetic_contents(const std::vector<SyntheticMaterial>& materials, int disc_count) {
  tables::TableContents contents;
  contents.machine = synthetic_machine(disc_count);
  for (const auto& m : materials) contents.materials.push_back(material_row(m));
  for (const auto& m : materials) {
    for (std::size_t i = 0; i < m.rpms.size(); ++i) {
      tables::Run run;
      run.material = m.name;
      run.rpm = m.rpms[i];
      run.source = "analytic";
      const int count = (i == 0 && m.samples_first_row >= 0) ? m.samples_first_row : m.samples_per_row;
      run.samples = synthetic_samples(m.rpms[i], count, m.density_kg_m3);
      run.scene_text = "# synthetic test table (tests/predict/synthetic_table.cpp)";
      run.scene_hash = "0";
      run.effects = "";
      run.software_version = "test";
      run.created_utc = "2024-01-01T00:00:00Z";
      run.stats_json = "{}";
      run.convergence_json = "[]";
      contents.runs.push_back(std::move(run));
    }
  }
  std::sort(contents.materials.begin(), contents.materials.end(),
            [](const auto& a, const auto& b) { return a.name < b.name; });
  std::sort(contents.runs.begin(), contents.runs.end(), [](const auto& a, const auto& b) {
    return a.material != b.material ? a.material < b.material : a.rpm < b.rpm;
  });
  return contents;
}

void write_synthetic_table(const std::string& path, const std::vector<SyntheticMaterial>& materials,
                           int disc_count) {
  const auto contents = synthetic_contents(materials, disc_count);
  std::filesystem::remove(path);
  tables::TableWriter writer(path);
  writer.write_machine(contents.machine);
  writer.write_materials(contents.materials);
  for (const auto& run : contents.runs) writer.write_run(run);
}

void write_table_without_runs(const std::string& path) {
  std::filesystem::remove(path);
  tables::TableWriter writer(path);
  writer.write_machine(synthetic_machine());
  writer.write_materials({material_row(default_synthetic_materials().front())});
}

}  // namespace spread::testing
