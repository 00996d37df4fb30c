#include "libspread/scene/scene.hpp"

#include "libspread/tables/scene_hash.hpp"

namespace spread::scene {

std::string effects_to_string(const Effects& effects) {
  const bool on[] = {effects.particle_contact, effects.wall_contact, effects.rotation, effects.rolling,
                     effects.drag,             effects.magnus,       effects.spin_decay, effects.wind};
  std::string list;
  for (std::size_t i = 0; i < kEffectNames.size(); ++i) {
    if (!on[i]) continue;
    if (!list.empty()) list += ',';
    list += kEffectNames[i];
  }
  return list;
}

std::string flight_effects_to_string(const Effects& effects) {
  std::string list;
  auto add = [&list](bool on, const char* name) {
    if (!on) return;
    if (!list.empty()) list += ',';
    list += name;
  };
  add(effects.drag, "drag");
  add(effects.magnus, "magnus");
  add(effects.spin_decay, "spin_decay");
  add(effects.wind, "wind");
  return list;
}

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

const char* to_string(DiscModel value) {
  switch (value) {
    case DiscModel::kAnalytic: return "analytic";
    case DiscModel::kMesh: return "mesh";
    case DiscModel::kStl: return "stl";
  }
  return "?";
}
const char* to_string(Integrator value) {
  return value == Integrator::kSymplecticEuler ? "symplectic_euler" : "velocity_verlet";
}
const char* to_string(ContactModel value) { return value == ContactModel::kHertzMindlin ? "hertz_mindlin" : "linear"; }
const char* to_string(FlightScheme value) { return value == FlightScheme::kRk4 ? "rk4" : "dopri5"; }
const char* to_string(LaunchSource value) { return value == LaunchSource::kAnalytic ? "analytic" : "dem"; }
const char* to_string(SpinModel value) { return value == SpinModel::kSliding ? "sliding" : "rolling"; }

}  // namespace spread::scene
