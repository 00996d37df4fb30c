#pragma once
// A small valid table (machine, two materials, runs) for the table tests, and raw SQL on a file.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <string>

#include "libspread/io/tables/table_writer.hpp"

namespace spread::testing {

inline tables::Machine sample_machine() {
  tables::Machine m;
  m.name = "test-machine";
  m.disc_radius_m = 0.29;
  m.disc_height_m = 0.28;
  m.disc_spacing_m = 0.8;
  m.disc_count = 2;
  m.vane_count = 2;
  m.cone_angle_rad = 0.157;
  m.rotation_sense = 1;
  return m;
}

inline tables::Material sample_material(const std::string& name, double friction) {
  tables::Material m;
  m.name = name;
  m.density_kg_m3 = 1800.0;
  m.diameter_mean_m = 3.2e-3;
  m.diameter_sd_m = 0.6e-3;
  m.friction_wall = friction;
  m.friction_particle = friction;
  m.restitution = 0.5;
  m.youngs_modulus_pa = 5e7;
  m.poisson_ratio = 0.25;
  m.rolling_friction = 0.05;
  return m;
}

inline tables::Run sample_run(const std::string& material, double rpm, int sample_count) {
  tables::Run run;
  run.material = material;
  run.rpm = rpm;
  run.source = "analytic";
  for (int k = 0; k < sample_count; ++k) {
    const float f = static_cast<float>(k) + static_cast<float>(rpm) * 1e-3f;
    // Awkward values on purpose: negative, tiny, and not exactly representable in decimal.
    run.samples.push_back(tables::LaunchSample{0.29f, -0.1f * f, 1.6e-3f, 0.1f + f, 0.8f, -0.3f, 0.05f,
                                               1e-7f, -2.5f, 1.0f, 3.2e-3f + 1e-6f * f, 3.1e-5f});
  }
  run.scene_hash = "0123456789abcdef";
  run.scene_text = "[machine]\nname = \"test\"\n";
  run.effects = "analytic_vane_sliding";
  run.dt_contact_s = 1e-6;
  run.dt_flight_s = 1e-3;
  run.particle_count = sample_count;
  run.software_version = "0.1.0";
  run.created_utc = "2024-01-01T00:00:00Z";
  run.stats_json = "{\"speed_mean\":16.0}";
  run.convergence_json = "[]";
  return run;
}

// Machine, materials "A" and "B", runs A@450, A@600, B@450 with `samples` samples each.
inline void write_sample_table(const std::string& path, int samples = 64) {
  tables::TableWriter writer(path);
  writer.write_machine(sample_machine());
  writer.write_materials({sample_material("A", 0.4), sample_material("B", 0.6)});
  writer.write_run(sample_run("A", 450.0, samples));
  writer.write_run(sample_run("A", 600.0, samples));
  writer.write_run(sample_run("B", 450.0, samples));
}

// Runs SQL on a file with the plain sqlite3 API, as a foreign tool (or a vandal) would.
inline void raw_exec(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  EXPECT_EQ(rc, SQLITE_OK) << (error != nullptr ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

}  // namespace spread::testing
