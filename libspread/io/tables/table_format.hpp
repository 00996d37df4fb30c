#pragma once
// Launch tables in SQLite (docs/design.md §4): one file per machine; per (material, rpm) run the launch
// samples as a little-endian float32 BLOB with an explicit record layout, plus provenance.
// docs/table-format.md describes the schema for people writing their own readers.
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/core/error.hpp"
#include "libspread/core/sieve_analysis.hpp"

namespace spread::tables {

inline constexpr std::int32_t kApplicationId = 0x53505244;  // 'SPRD' in PRAGMA application_id
// PRAGMA user_version. 2: row checksums (row_checksum.hpp) and runs.inputs_hash. 3: blends
// (`blend_components`). Writers write kFormatVersion; readers also read kOldestReadableVersion on: a
// version-2 file is a version-3 file without blends (its tables and records are the same).
inline constexpr std::int32_t kFormatVersion = 3;
inline constexpr std::int32_t kOldestReadableVersion = 2;

// One launch-off state. Stored as kSampleFloats little-endian float32 in this order; the layout string
// kSampleLayout is stored with every run and checked on read.
// Velocities are normalised by the rim speed ω·R and spins by the disc speed ω, so rows of one material
// interpolate well in rpm (docs/design.md §4). Positions are relative to the disc centre (inertial frame,
// z up, disc surface at the rim = 0 for a flat disc).
struct LaunchSample {
  float x_m, y_m, z_m;
  float t_s;                          // launch time after the granule was fed
  float vx_norm, vy_norm, vz_norm;    // velocity / (ω R)
  float wx_norm, wy_norm, wz_norm;    // spin / ω
  float diameter_m;
  float mass_kg;
};
inline constexpr int kSampleFloats = 12;
inline constexpr const char* kSampleLayout =
    "x_m,y_m,z_m,t_s,vx_per_rim_speed,vy_per_rim_speed,vz_per_rim_speed,"
    "wx_per_disc_speed,wy_per_disc_speed,wz_per_disc_speed,diameter_m,mass_kg";

// Machine geometry, one row per file.
struct Machine {
  std::string name;
  double disc_radius_m = 0.0;     // R, for ω R
  double disc_height_m = 0.0;     // default height of the disc above the ground
  double disc_spacing_m = 0.0;    // centre to centre, lateral (two discs)
  int disc_count = 2;             // 1 or 2
  int vane_count = 0;
  double cone_angle_rad = 0.0;
  // +1: the (left) disc turns counter-clockwise seen from above; the right disc turns the other way.
  int rotation_sense = 1;
};

struct BlendComponent;

struct Material {
  std::string name;
  double density_kg_m3 = 0.0;
  double diameter_mean_m = 0.0;        // lognormal feed (Sect. 3.2)
  double diameter_sd_m = 0.0;
  double friction_wall = 0.0;          // particle–disc/vane sliding friction
  double friction_particle = 0.0;
  double restitution = 0.0;
  double youngs_modulus_pa = 0.0;
  double poisson_ratio = 0.0;
  double rolling_friction = 0.0;
  // The feed's sizes as a sieve analysis (a scene's `sieve_mm` and `sieve_retained_pct`); empty: the
  // lognormal above. Not a column of the file: a sieve material's row holds the analysis's number mean and
  // sd in diameter_mean_m and diameter_sd_m, the analysis itself is in its runs' scene_text and inputs_hash,
  // and its launch records carry each granule's diameter (docs/products.md "In the table").
  SieveAnalysis sieve;
  // Non-empty: the material is a blend of these components, fed together onto the disc (docs/products.md
  // "Blends"); the quantities above are then unused (each component has its own). Not a column of
  // `materials`: a table stores each component as a material row of its own, named
  // blend_component_name(), and the blend in `blend_components`.
  std::vector<BlendComponent> components;
  bool is_blend() const { return !components.empty(); }
};

// One component of a blend: a material of its own (its density, friction and sizes) and its share of the
// blend's mass. Nutrient contents are % of the component's mass (fertiliser grades: N, P as P2O5, K as
// K2O); 0 when the component carries none of that nutrient.
struct BlendComponent {
  Material material;            // never a blend itself
  double mass_fraction = 0.0;   // in (0, 1]; a blend's fractions sum to 1
  double n_pct = 0.0;
  double p2o5_pct = 0.0;
  double k2o_pct = 0.0;
};
// The nutrients a component can carry, in this order everywhere (tables, CLI, C API).
struct Nutrient {
  const char* name;                  // as a grade names it
  const char* key;                   // the scene key, the table column
  double BlendComponent::* member;
};
inline constexpr int kNutrientCount = 3;
inline constexpr Nutrient kNutrients[kNutrientCount] = {{"N", "n_pct", &BlendComponent::n_pct},
                                                        {"P2O5", "p2o5_pct", &BlendComponent::p2o5_pct},
                                                        {"K2O", "k2o_pct", &BlendComponent::k2o_pct}};
// A blend's fractions may be rounded as a recipe gives them: they must sum to 1 within this.
inline constexpr double kBlendFractionTolerance = 1e-3;

// The name of a blend component's material row in a table: "<blend> / <component>".
std::string blend_component_name(const std::string& blend, const std::string& component);
// "" when the blend's components are usable: at least one, each fraction in (0, 1], the fractions summing
// to 1 within kBlendFractionTolerance, nutrients in [0, 100] with their sum <= 100, names non-empty and
// unique, no component a blend itself; otherwise the first problem as "components[i].<key>: <problem>"
// (or "components: <problem>").
std::string blend_problem(const std::vector<BlendComponent>& components);
// One component's own values (name, fraction, nutrients, not a blend): "" or "<key>: <problem>".
std::string blend_component_problem(const BlendComponent& component);

// A blend as a table holds it (`blend_components`): each component a material row of its own
// (blend_component_name()), whose runs are the launches of that component from the blend's DEM runs.
struct BlendRowComponent {
  std::string material;          // the component's `materials` row
  double mass_fraction = 0.0;
  double n_pct = 0.0, p2o5_pct = 0.0, k2o_pct = 0.0;
};
struct Blend {
  std::string name;
  std::vector<BlendRowComponent> components;  // in the blend's order (`position`)
};
// "" or the first problem of a stored blend: its components' fractions and nutrients as blend_problem()
// checks a scene's ("blend NAME: components[i].<key>: <problem>").
BlendComponent as_blend_component(const BlendRowComponent& row);
std::string stored_blend_problem(const Blend& blend);

// Provenance and content of one (material, rpm) run.
struct Run {
  std::string material;
  double rpm = 0.0;
  std::string source;                  // "analytic" or "dem"
  std::vector<LaunchSample> samples;
  std::string scene_hash;              // hex FNV-1a 64 of scene_text
  // hex FNV-1a 64 of the canonical text of every scene value that can change this run's samples
  // (scene::Scene::run_inputs_text): a rerun with the same inputs_hash would write the same run.
  std::string inputs_hash;
  std::string scene_text;
  std::string effects;                 // comma list of the effects that ran
  double dt_contact_s = 0.0;           // 0 for analytic runs
  double dt_flight_s = 0.0;
  std::int64_t particle_count = 0;
  std::string software_version;
  std::string created_utc;             // ISO 8601
  std::string stats_json;              // summary statistics (speed mean/sd, angles, R̄, ξ, ...)
  std::string convergence_json;        // convergence history, "[]" when none
};

// Why a table file could not be used. Each has its own C API status code.
// A table file's problems are kinds of the one error type (libspread/core/error.hpp): kMissing, kNotOurs,
// kCorrupt, kWrongVersion, kEmpty, kIo.
using TableErrorKind = ErrorKind;


// Physical plausibility of the stored values, shared by the reader (a violation is TableError kCorrupt),
// TableWriter (std::invalid_argument) and the scene reader (the same upper bounds): "" when every value
// is usable, otherwise the first violation as "<field> = <value>: <requirement>". The bounds are far
// outside any spreader, yet they keep a damaged value that is still a valid number (a granule of
// 4.4e25 kg, a disc 150 m up) out of the predictor, and they match what the predictor accepts, so a
// file problem is reported as one and never as the caller's out-of-range argument.
// Rules (docs/table-format.md, "Plausibility"):
//   machine   disc_radius_m in (0, 5]; disc_height_m in [0, 100] (PredictorLimits::max_disc_height_m);
//             disc_spacing_m in [0, 20]; |cone_angle_rad| < pi/2; disc_count 1 or 2; vane_count 0..64;
//             rotation_sense +1 or -1;
//   material  density_kg_m3 in (0, 25000]; diameter_mean_m in (0, 0.1]; diameter_sd_m in [0, 0.1];
//             friction_wall, friction_particle, rolling_friction in [0, 10]; restitution in [0, 1];
//             youngs_modulus_pa in [0, 1e13]; poisson_ratio in (-1, 0.5];
//   run       rpm in (0, 10000]; dt_contact_s, dt_flight_s finite >= 0; per sample: |x_m|, |y_m|, |z_m|
//             <= 1000, |t_s| <= 1e6, each velocity / rim speed within +-100, each spin / disc speed within
//             +-1e5, diameter_m in (0, 0.1], and mass_kg within the density bounds for its diameter
//             (mass / (pi d^3 / 6) in [1, 25000] kg/m^3) ("sample <index> <field>").
struct PlausibleLimits {
  static constexpr double kMaxDiscRadius_m = 5.0;
  static constexpr double kMaxDiscHeight_m = 100.0;
  static constexpr double kMaxDiscSpacing_m = 20.0;
  static constexpr int kMaxVaneCount = 64;
  static constexpr double kMaxDensity_kg_m3 = 25'000.0;  // above osmium's 22,600
  static constexpr double kMinSampleDensity_kg_m3 = 1.0;
  static constexpr double kMaxDiameter_m = 0.1;          // a 10 cm stone
  static constexpr double kMaxFriction = 10.0;
  static constexpr double kMaxYoungsModulus_pa = 1e13;   // diamond is 1.2e12
  static constexpr double kMaxRpm = 10'000.0;            // spreader discs turn at 500-1,200 rpm
  static constexpr double kMaxSamplePosition_m = 1000.0;  // as spread_trajectory's launch position
  static constexpr double kMaxSampleTime_s = 1e6;
  static constexpr double kMaxVelocityPerRimSpeed = 100.0;
  static constexpr double kMaxSpinPerDiscSpeed = 1e5;
};

std::string machine_problem(const Machine& machine);
std::string material_problem(const Material& material);
std::string run_values_problem(const Run& run);  // run_record_problem, then samples_problem of run.samples
std::string run_record_problem(const Run& run);  // the run's own numbers (rpm, time steps)
std::string samples_problem(std::span<const LaunchSample> samples);

// The flight effects a run was built with: the string value of "flight_effects" in its stats_json (a
// comma list of flight effect names, "" for none), or nothing when the run does not record them (files
// written before runs did). A plain scan of the compact JSON the writers produce, so readers need no
// JSON library.
std::optional<std::string> recorded_flight_effects(const Run& run);

// The file's path is where the problem is; the message begins with it.
class TableError : public Error {
 public:
  TableError(TableErrorKind kind, const std::string& what) : Error(kind, path_of(what), what) {}

 private:
  static std::string path_of(const std::string& what) { return what.substr(0, what.find(": ")); }
};

}  // namespace spread::tables
