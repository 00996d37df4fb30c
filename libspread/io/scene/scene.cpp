#include "libspread/io/scene/scene.hpp"

#include <cstdio>
#include <stdexcept>
#include <type_traits>
#include <variant>

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
  if (!product_notes.empty()) {
    if (!out.empty() && out.back() != '\n') out += '\n';
    for (const std::string& note : product_notes) out += note + "\n";
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

// Adds `section.key = value` for each key of `keys` whose row makes it an input of a run of `role`, in the
// rows' order (the canonical text's order: docs/table-format.md "Inputs hash").
template <typename Owner, std::size_t kCount>
void add_inputs(CanonicalText& t, const char* section, const Owner& owner, const std::array<Key<Owner>, kCount>& keys,
                RunInput role) {
  for (const Key<Owner>& key : keys) {
    if (key.run_input != role || (key.input_when != nullptr && !key.input_when(owner))) continue;
    const std::string name = std::string(section) + "." + std::string(key.name);
    std::visit(
        [&](const auto& field) {
          using F = std::decay_t<decltype(field)>;
          if constexpr (std::is_same_v<F, double Owner::*> || std::is_same_v<F, int Owner::*> ||
                        std::is_same_v<F, std::string Owner::*>) {
            t.add(name.c_str(), owner.*field);
          } else if constexpr (std::is_same_v<F, std::uint64_t Owner::*>) {
            t.add(name.c_str(), static_cast<std::int64_t>(owner.*field));
          } else if constexpr (std::is_same_v<F, std::array<double, 2> Owner::*>) {
            for (std::size_t k = 0; k < 2; ++k) t.add((name + "[" + std::to_string(k) + "]").c_str(), (owner.*field)[k]);
          } else if constexpr (std::is_same_v<F, Choice<Owner>>) {
            t.add(name.c_str(), std::string(choice_name(field.names, field.get(owner))));
          } else {
            throw std::logic_error(name + ": a run input of a type the canonical text does not write");
          }
        },
        key.field);
  }
}

}  // namespace

namespace {
// One material's name, quantities and sieve analysis under `prefix`. A lognormal material has no sieve
// lines, so its text (and every table built before sieve feeds existed) is unchanged.
void add_material(CanonicalText& t, const std::string& prefix, const Material& material) {
  t.add((prefix + "name").c_str(), material.name);
  for (const tables::MaterialQuantity& q : tables::kMaterialQuantities) {
    t.add((prefix + std::string(q.name)).c_str(), material.*q.member);
  }
  for (const tables::MaterialList& list : tables::kMaterialSieveLists) {
    const std::vector<double>& values = material.sieve.*list.member;
    for (std::size_t i = 0; i < values.size(); ++i)
      t.add((prefix + std::string(list.name) + "[" + std::to_string(i) + "]").c_str(), values[i]);
  }
}
}  // namespace

std::string Scene::run_inputs_text(const Material& material, double rpm) const {
  // The key rows say which values are a run's inputs (scene_keys.hpp, Key::run_input); the materials'
  // quantities and the effects are inputs of every run.
  CanonicalText t;
  add_inputs(t, "machine", machine, kMachineKeys, RunInput::kAlways);
  add_inputs(t, "inlet", inlet, kInletKeys, RunInput::kAlways);
  if (!material.is_blend()) {
    add_material(t, "material.", material);
  } else {
    // A blend's run: every component's quantities and mass fraction (they meet on the disc), not its
    // nutrient contents (which change no launch).
    t.add("material.name", material.name);
    for (std::size_t j = 0; j < material.components.size(); ++j) {
      const std::string prefix = "material.components[" + std::to_string(j) + "].";
      add_material(t, prefix, material.components[j].material);
      t.add((prefix + "mass_fraction").c_str(), material.components[j].mass_fraction);
    }
  }
  t.add("rpm", rpm);
  add_inputs(t, "air", air, kAirKeys, RunInput::kAlways);
  t.add("effects", effect::to_string(effects));
  add_inputs(t, "numerics", numerics, kNumericsKeys, RunInput::kAlways);
  add_inputs(t, "sweep", sweep, kSweepKeys, RunInput::kAlways);
  const RunInput source = sweep.source == LaunchSource::kAnalytic ? RunInput::kAnalytic : RunInput::kDem;
  add_inputs(t, "numerics", numerics, kNumericsKeys, source);
  add_inputs(t, "sweep", sweep, kSweepKeys, source);
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
