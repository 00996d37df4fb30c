#include "libspread/io/scene/scene.hpp"

#include <cstdio>

#include "libspread/io/scene/scene_keys.hpp"
#include "libspread/io/tables/material_schema.hpp"
#include "libspread/io/tables/scene_hash.hpp"

namespace spread::scene {

const Material* Scene::find_material(const std::string& name) const {
  for (const Material& m : materials) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::string Scene::provenance_text() const {
  std::string out = text;
  if (!overrides.empty()) {
    if (!out.empty() && out.back() != '\n') out += '\n';
    out += "# overrides applied after the text above:\n";
    for (const std::string& o : overrides) out += "# --set " + o + "\n";
  }
  return out;
}

std::string Scene::hash() const { return tables::fnv1a64_hex(provenance_text()); }

namespace {

// "key = value\n" with a double in round-trip precision.
class CanonicalText {
 public:
  void add(const char* key, double value) {
    char digits[40];
    std::snprintf(digits, sizeof digits, "%.17g", value);
    line(key, digits);
  }
  void add(const char* key, std::int64_t value) { line(key, std::to_string(value)); }
  void add(const char* key, int value) { line(key, std::to_string(value)); }
  void add(const char* key, const std::string& value) { line(key, "\"" + value + "\""); }
  void add(const char* key, const char* value) { add(key, std::string(value)); }
  std::string text;

 private:
  void line(const char* key, const std::string& value) { text += std::string(key) + " = " + value + "\n"; }
};

}  // namespace

std::string Scene::run_inputs_text(const Material& material, double rpm) const {
  CanonicalText t;
  const Machine& m = machine;
  t.add("machine.name", m.name);
  t.add("machine.disc_radius_m", m.disc_radius_m);
  t.add("machine.disc_height_m", m.disc_height_m);
  t.add("machine.disc_count", m.disc_count);
  t.add("machine.disc_spacing_m", m.disc_spacing_m);
  t.add("machine.rotation_sense", m.rotation_sense);
  t.add("machine.cone_angle_rad", m.cone_angle_rad);
  t.add("machine.vane_count", m.vane_count);
  t.add("machine.vane_start_radius_m", m.vane_start_radius_m);
  t.add("machine.vane_end_radius_m", m.vane_end_radius_m);
  t.add("machine.vane_height_m", m.vane_height_m);
  t.add("machine.vane_pitch_rad", m.vane_pitch_rad);
  t.add("machine.disc_model", to_string(m.disc_model));
  if (m.disc_model == DiscModel::kMesh) t.add("machine.mesh_size_m", m.mesh_size_m);
  if (m.disc_model == DiscModel::kStl) {
    t.add("machine.stl_path", m.stl_path);
    t.add("machine.stl_scale", m.stl_scale);
  }
  t.add("inlet.radius_m", inlet.radius_m);
  t.add("inlet.offset_m", inlet.offset_m);
  t.add("inlet.angle_rad", inlet.angle_rad);
  t.add("inlet.drop_height_m", inlet.drop_height_m);
  t.add("inlet.mass_flow_kg_s", inlet.mass_flow_kg_s);
  t.add("material.name", material.name);
  for (const tables::MaterialQuantity& q : tables::kMaterialQuantities) {
    t.add(("material." + std::string(q.name)).c_str(), material.*q.member);
  }
  t.add("rpm", rpm);
  t.add("air.density_kg_m3", air.density_kg_m3);
  t.add("air.viscosity_pa_s", air.viscosity_pa_s);
  t.add("air.wind_m_s[0]", air.wind_m_s[0]);
  t.add("air.wind_m_s[1]", air.wind_m_s[1]);
  t.add("effects", effect::to_string(effects));
  t.add("numerics.seed", static_cast<std::int64_t>(numerics.seed));
  t.add("sweep.source", to_string(sweep.source));
  t.add("sweep.samples_per_run", sweep.samples_per_run);
  if (sweep.source == LaunchSource::kAnalytic) {
    t.add("sweep.spin_model", to_string(sweep.spin_model));
  } else {
    t.add("numerics.duration_s", numerics.duration_s);
    t.add("numerics.dt_contact_s", numerics.dt_contact_s);
    t.add("numerics.steps_per_contact", numerics.steps_per_contact);
    t.add("numerics.integrator", to_string(numerics.integrator));
    t.add("numerics.contact_model", to_string(numerics.contact_model));
    t.add("numerics.flight_scheme", to_string(numerics.flight_scheme));
    t.add("numerics.flight_dt_s", numerics.flight_dt_s);
    t.add("numerics.flight_tolerance", numerics.flight_tolerance);
    t.add("numerics.collector_radius_m", numerics.collector_radius_m);
    t.add("sweep.batch_s", sweep.batch_s);
    t.add("sweep.convergence_tolerance", sweep.convergence_tolerance);
    t.add("sweep.particle_budget", sweep.particle_budget);
    t.add("sweep.working_width_ci_m", sweep.working_width_ci_m);
  }
  return t.text;
}

std::string Scene::run_inputs_hash(const Material& material, double rpm) const {
  return tables::fnv1a64_hex(run_inputs_text(material, rpm));
}

bool Scene::same_run_inputs(const std::string& stored_inputs_hash, const Material& material, double rpm) const {
  std::string inputs = run_inputs_text(material, rpm);
  if (stored_inputs_hash == tables::fnv1a64_hex(inputs)) return true;
  static const std::string kLine = std::string("numerics.contact_model = \"") + to_string(ContactModel::kHertzThornton) + "\"\n";
  static const std::string kOldLine = "numerics.contact_model = \"hertz_mindlin\"\n";
  const std::size_t at = inputs.find(kLine);
  if (at == std::string::npos) return false;
  inputs.replace(at, kLine.size(), kOldLine);
  return stored_inputs_hash == tables::fnv1a64_hex(inputs);
}

std::vector<const Material*> Scene::sweep_materials() const {
  std::vector<const Material*> list;
  if (sweep.materials.empty()) {
    for (const Material& m : materials) list.push_back(&m);
  } else {
    for (const std::string& name : sweep.materials) list.push_back(find_material(name));
  }
  return list;
}

std::vector<double> Scene::sweep_rpms() const {
  return sweep.rpm.empty() ? std::vector<double>{machine.rpm} : sweep.rpm;
}

// The first spelling of each value in the reader's rows (scene_keys.hpp).
const char* to_string(DiscModel value) { return choice_name(kDiscModelNames, static_cast<int>(value)).data(); }
const char* to_string(Integrator value) { return choice_name(kIntegratorNames, static_cast<int>(value)).data(); }
// The Hertz law by what it is (Thornton's tangential law). Tables built before the rename spell it
// "hertz_mindlin" in their inputs text: Scene::same_run_inputs takes both as the same law.
const char* to_string(ContactModel value) { return value == ContactModel::kHertzThornton ? "hertz_thornton" : "linear"; }
const char* to_string(FlightScheme value) { return choice_name(kFlightSchemeNames, static_cast<int>(value)).data(); }
const char* to_string(LaunchSource value) { return choice_name(kLaunchSourceNames, static_cast<int>(value)).data(); }
const char* to_string(SpinModel value) { return choice_name(kSpinModelNames, static_cast<int>(value)).data(); }

tables::Machine table_machine(const Machine& m) {
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

}  // namespace spread::scene
