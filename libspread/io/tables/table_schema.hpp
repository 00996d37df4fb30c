#pragma once
// SQL schema of format version kFormatVersion (docs/table-format.md). Changing a table or a column
// meaning means bumping kFormatVersion: readers refuse other versions (TableErrorKind::kWrongVersion).
namespace spread::tables::detail {

inline constexpr const char* kSchemaSql = R"sql(
CREATE TABLE machine (
  id INTEGER PRIMARY KEY CHECK (id = 1),
  name TEXT NOT NULL,
  disc_radius_m REAL NOT NULL,
  disc_height_m REAL NOT NULL,
  disc_spacing_m REAL NOT NULL,
  disc_count INTEGER NOT NULL,
  vane_count INTEGER NOT NULL,
  cone_angle_rad REAL NOT NULL,
  rotation_sense INTEGER NOT NULL,
  checksum TEXT NOT NULL
);
CREATE TABLE materials (
  name TEXT NOT NULL UNIQUE,
  density_kg_m3 REAL NOT NULL,
  diameter_mean_m REAL NOT NULL,
  diameter_sd_m REAL NOT NULL,
  friction_wall REAL NOT NULL,
  friction_particle REAL NOT NULL,
  restitution REAL NOT NULL,
  youngs_modulus_pa REAL NOT NULL,
  poisson_ratio REAL NOT NULL,
  rolling_friction REAL NOT NULL,
  checksum TEXT NOT NULL
);
CREATE TABLE runs (
  material TEXT NOT NULL,
  rpm REAL NOT NULL,
  source TEXT NOT NULL,
  sample_count INTEGER NOT NULL,
  record_layout TEXT NOT NULL,
  record_bytes INTEGER NOT NULL,
  samples BLOB NOT NULL,
  scene_hash TEXT NOT NULL,
  inputs_hash TEXT NOT NULL,
  scene_text TEXT NOT NULL,
  effects TEXT NOT NULL,
  dt_contact_s REAL NOT NULL,
  dt_flight_s REAL NOT NULL,
  particle_count INTEGER NOT NULL,
  software_version TEXT NOT NULL,
  created_utc TEXT NOT NULL,
  stats_json TEXT NOT NULL,
  convergence_json TEXT NOT NULL,
  checksum TEXT NOT NULL,
  UNIQUE (material, rpm)
);
CREATE TABLE blend_components (
  blend TEXT NOT NULL,
  position INTEGER NOT NULL,
  material TEXT NOT NULL UNIQUE,
  mass_fraction REAL NOT NULL,
  n_pct REAL NOT NULL,
  p2o5_pct REAL NOT NULL,
  k2o_pct REAL NOT NULL,
  checksum TEXT NOT NULL,
  UNIQUE (blend, position)
);
CREATE TABLE meta (
  key TEXT PRIMARY KEY,
  value TEXT NOT NULL
);
)sql";

}  // namespace spread::tables::detail
