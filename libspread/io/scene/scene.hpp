#pragma once
// A scene: everything one run or one table sweep needs — machine, inlet, materials, air, effects,
// numerics, sweep, outputs (docs/scene-format.md lists every key with its unit and default).
// Read from TOML by load_scene_file()/parse_scene(); `--set key=value` overrides are applied to the TOML
// tree before validation, so an override is checked exactly like a value in the file.
// The struct is plain data: modules map it to their own settings (the DEM engine, flight, lookup_builder).
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/core/effect_registry.hpp"
#include "libspread/core/error.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::scene {

// Same fields as the table's material rows; one type so a scene material goes into a table unchanged.
using Material = tables::Material;

enum class DiscModel { kAnalytic, kMesh, kStl };     // "analytic" | "mesh" | "stl"
// Default mesh size ξ/R: the coarsest the accuracy study (docs/accuracy-cost.md, DEM) measured within 1 %
// on the seed's Appendix-1 cone.
inline constexpr double kDefaultMeshSizePerRadius = 0.01;
enum class Integrator { kSymplecticEuler, kVelocityVerlet };  // "symplectic_euler" | "velocity_verlet"
enum class ContactModel { kHertzThornton, kLinear };  // "hertz_thornton" (alias "hertz_mindlin") | "linear"
enum class FlightScheme { kRk4, kDopri5 };            // "rk4" | "dopri5"
enum class LaunchSource { kAnalytic, kDem };          // "analytic" | "dem"
// Spin of analytic launch samples (see libspread/physics/launch/analytic_launch.hpp):
// Launch spin of the analytic source:
// "rolling" (default): the granule rolls along the vane face as it is pushed out, as DEM granules do:
//   ω = sense·Ω ẑ + (n × v_rel)/(d/2), n = sense·e_θ the vane face normal, v_rel = ṡ along the vane,
//   i.e. about the disc axis against the disc's sense on a flat disc (|ω| ≈ ṡ/(d/2), thousands of rad/s);
// "sliding": the granule keeps its orientation relative to the vane and turns with the disc (sense·Ω ẑ).
enum class SpinModel { kSliding, kRolling };

struct Machine {
  std::string name = "machine";
  double disc_radius_m = 0.29;        // R: rim radius (horizontal)
  double disc_height_m = 0.28;        // height of the disc rim above the ground
  int disc_count = 2;                 // 1 or 2
  double disc_spacing_m = 0.8;        // centre to centre, lateral (two discs)
  int rotation_sense = 1;             // +1: left disc counter-clockwise seen from above; -1: clockwise
  double cone_angle_rad = 0.0;        // surface rises outward at this angle (0 = flat)
  int vane_count = 2;
  double vane_start_radius_m = 0.0;   // inner end of the vanes
  double vane_end_radius_m = 0.0;     // outer end; 0 in the file = disc_radius_m (resolved on load)
  double vane_height_m = 0.036;
  double vane_pitch_rad = 0.0;        // 0 = radial vanes; > 0 leans the vane backwards
  DiscModel disc_model = DiscModel::kAnalytic;
  double mesh_size_m = 0.0;           // ξ, triangle size of the generated mesh (disc_model = "mesh");
                                      // 0 in the file = kDefaultMeshSizePerRadius · disc_radius_m (on load)
  // disc_model = "stl": the disc (with its vanes) is this triangle mesh instead of the generated one.
  // Relative paths are taken from the scene file's directory (load_scene_file resolves them).
  std::string stl_path;
  double stl_scale = 1.0;             // STL coordinates × stl_scale = metres (0.001 for a file in mm)
  double rpm = 500.0;                 // disc speed of a `simulate` run (rev/min)
};

// The machine row of a launch table for this machine (docs/table-format.md).
tables::Machine table_machine(const Machine& machine);

struct Inlet {
  double radius_m = 0.0145;           // radius of the inlet circle
  double offset_m = 0.1;              // distance of the inlet centre from the disc centre
  double angle_rad = 0.0;             // angle of the inlet centre, from +x, counter-clockwise
  double drop_height_m = 0.05;        // release height above the disc surface
  double mass_flow_kg_s = 0.11;
  // The drop-point turns (degrees, [low, high], low <= 0 <= high) over which this machine's launches,
  // turned about the disc axis, were checked against DEM rows built at the turned drop point
  // (tools/drop_point_check.py, docs/building-tables.md "The drop-point turn against DEM rows"). Written into
  // the table; the searches over settings (chart, border, wind) never turn a drop point beyond it.
  std::array<double, 2> validated_turn_deg{0.0, 0.0};
};

struct Air {
  double density_kg_m3 = 1.225;
  double viscosity_pa_s = 1.81e-5;    // dynamic viscosity
  std::array<double, 2> wind_m_s{0.0, 0.0};  // horizontal wind (x, y)
};

// Exactly the effects that run (docs/design.md §7): bits of the effect registry
// (libspread/core/effect_registry.hpp), named there as in the TOML list.
using effect::EffectSet;

struct Numerics {
  std::uint64_t seed = 1;
  double duration_s = 0.4;            // simulated time of a DEM run
  double dt_contact_s = 0.0;          // 0 = automatic, t_c / steps_per_contact (docs/design.md §2)
  int steps_per_contact = 15;         // N_c
  Integrator integrator = Integrator::kSymplecticEuler;
  ContactModel contact_model = ContactModel::kHertzThornton;
  FlightScheme flight_scheme = FlightScheme::kDopri5;
  double flight_dt_s = 1e-3;          // RK4 step, or first trial step of dopri5
  double flight_tolerance = 1e-3;     // dopri5 relative tolerance (docs/accuracy-cost.md, flight)
  double collector_radius_m = 0.0;    // 0 = disc_radius_m (resolved on load)
  int threads = 0;                    // 0 = all hardware threads
};

struct Sweep {
  std::vector<double> rpm;                 // table rows (rev/min); empty = [machine.rpm]
  std::vector<std::string> materials;      // empty = every material of the scene
  LaunchSource source = LaunchSource::kAnalytic;
  int samples_per_run = 2000;
  std::string output = "tables.sqlite";    // relative paths are relative to the working directory
  SpinModel spin_model = SpinModel::kRolling;  // analytic source only
  // DEM source only (lookup_builder): the disc is simulated in batches of batch_s; after each batch the
  // launches so far are flown and R̄, ξ (Eqs. 51–52) computed; the run stops when both changed by at most
  // convergence_tolerance (relative) since the previous batch and at least samples_per_run granules were
  // launched, or when particle_budget launches (0 = no limit) or numerics.duration_s is reached.
  double batch_s = 0.05;                   // simulated time per batch (s)
  double convergence_tolerance = 0.02;     // relative change of R̄ and ξ between batches
  int particle_budget = 0;                 // launched granules; 0 = only the time budget
  // Besides, the run goes on until the 95 % interval of the working width predicted from its launches
  // alone (to-and-fro, CV 15 %, 0.5 m trays, the stored height) is within ± this; 0 = no such rule.
  double working_width_ci_m = 0.5;         // m
};

// A product library: [[products]] entries with the keys of a [[materials]] entry (scenes/products.toml,
// docs/products.md). A material entry's `product = "NAME"` starts from that product's values; the
// entry's own keys replace them (its size keys replace the product's sizes as a whole).
struct Products {
  std::string file;  // relative paths are taken from the scene file's directory; "" = no library
};

struct Outputs {
  std::string directory = ".";
  int vtk_every_steps = 0;            // 0 = no VTK output
  bool launch_csv = false;
  bool pattern_png = false;
};

// [field]: a field run of `spread field --scene` (docs/field.md): the boundary, the plan and the machine in
// the loop. No key of it is an input of a table run (the tables are the machine's; the field is where it
// drives). Relative paths are taken from the scene file's directory.
struct FieldRun {
  std::string boundary;                      // GeoJSON Polygon of the field; "" = none (give --boundary)
  std::string track;                         // recorded track (CSV) instead of a plan; "" = the plan
  std::string material;                      // "" = the [simulate] material
  double rpm = 0.0;                          // the field's disc speed (rev/min); 0 = machine.rpm
  double rate_kg_ha = 200.0;                 // target rate
  double bout_width_m = 24.0;                // tramline spacing and metered width
  int headland_passes = 1;                   // headland rounds
  int reference_edge = -1;                   // tramlines parallel to this boundary edge; −1 = the longest
  std::array<double, 2> wind_m_s{0.0, 0.0};  // wind over the field (east, north)
  int section_count = 8;
  bool section_control = true;
  bool border = false;                       // border mode on the outermost headland round
  double speed_km_h = 12.0;
  double look_ahead_s = 0.5;                 // section control's turn-on and turn-off time
  double gate_travel_s = 1.0;                // a metering gate from shut to the field's flow
  double cell_m = 0.5;                       // the rate grid's cell
};

struct Scene {
  std::string source_name;            // file path (or a label) used in every error message
  std::string text;                   // the TOML text as read
  std::vector<std::string> overrides; // "key=value" as given, in order
  Machine machine;
  Inlet inlet;
  Products products;
  std::vector<Material> materials;    // in file order, names unique, products resolved
  // One comment line per material taken from a product: its values as resolved, so that the provenance
  // (provenance_text) says what the library gave, whatever the library file holds later.
  std::vector<std::string> product_notes;
  std::string simulate_material;      // [simulate] material; default = first material
  Air air;
  EffectSet effects = effect::kDefault;
  Numerics numerics;
  Sweep sweep;
  Outputs outputs;
  FieldRun field;

  bool has(EffectSet effect) const { return (effects & effect) == effect; }
  const Material* find_material(const std::string& name) const;  // nullptr when absent
  // The text plus the overrides (as trailing comment lines): what provenance records.
  std::string provenance_text() const;
  // tables::fnv1a64_hex(provenance_text()).
  std::string hash() const;
  // Every value that can change the launch samples of one (material, rpm) run, one "key = value" line
  // each, in a fixed order (doubles in round-trip precision): the scene's comments, its other materials
  // and rpm rows, threads and outputs do not appear. Its hash is stored with the run (Run::inputs_hash),
  // so a builder can tell whether an existing run came from the same inputs.
  std::string run_inputs_text(const Material& material, double rpm) const;
  std::string run_inputs_hash(const Material& material, double rpm) const;
  // True when a stored run's inputs_hash says it came from these inputs: run_inputs_hash, or, with the
  // Hertz law, the hash of the same text spelling the law "hertz_mindlin" as tables built before the
  // rename did (the same law, so the same run: docs/table-format.md "Inputs hash").
  bool same_run_inputs(const std::string& stored_inputs_hash, const Material& material, double rpm) const;
  // The sweep's materials resolved (all scene materials when the list is empty).
  std::vector<const Material*> sweep_materials() const;
  // The sweep's rpm list resolved ([machine.rpm] when the list is empty).
  std::vector<double> sweep_rpms() const;
};

// Bad scene: the message reads "<source>: <dotted.key>: <problem>".
// The one error type's kScene (libspread/core/error.hpp); where() is "<source>: <dotted.key>".
class SceneError : public Error {
 public:
  explicit SceneError(const std::string& what) : Error(ErrorKind::kScene, where_of(what), what) {}

 private:
  static std::string where_of(const std::string& what) {
    const std::size_t first = what.find(": ");
    const std::size_t second = first == std::string::npos ? first : what.find(": ", first + 2);
    return what.substr(0, second);
  }
};

// overrides: "dotted.key=value", the value parsed as a TOML value (a bare word that is not valid TOML
// is taken as a string, so `--set simulate.material=Urea` works). Array elements by index:
// "materials.0.density_kg_m3=1800".
Scene parse_scene(const std::string& toml_text, const std::string& source_name,
                  const std::vector<std::string>& overrides = {});
Scene load_scene_file(const std::string& path, const std::vector<std::string>& overrides = {});

const char* to_string(DiscModel value);
const char* to_string(Integrator value);
const char* to_string(ContactModel value);
const char* to_string(FlightScheme value);
const char* to_string(LaunchSource value);
const char* to_string(SpinModel value);

}  // namespace spread::scene
