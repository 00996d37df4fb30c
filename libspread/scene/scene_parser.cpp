// TOML → Scene. toml++ is heavy to compile: in the library only this file and the drum's scene reader
// (libspread/drum/drum_scene.cpp) include it.
// Order: parse the text, merge the --set overrides into the tree, read every section while recording
// the keys it knows (anything left over is an "unknown key" error), then validate the values.
#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "libspread/scene/scene.hpp"
#include "libspread/tables/material_schema.hpp"

namespace spread::scene {
namespace {

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// ---- overrides -------------------------------------------------------------------------------------

bool is_bare_key_segment(const std::string& segment) {
  if (segment.empty()) return false;
  for (char c : segment) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

std::string quote_toml_string(const std::string& raw) {
  std::string out = "\"";
  for (char c : raw) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

bool is_index(const std::string& key) {
  return !key.empty() && key.find_first_not_of("0123456789") == std::string::npos;
}

// Puts `value` at `key` of `dest`; tables merge key by key, arrays take integer keys as indices.
void merge_node(toml::table& dest, const std::string& key, toml::node& value, const std::string& where);

void merge_into_array(toml::array& dest, toml::table& indices, const std::string& where) {
  for (auto&& [index_key, value] : indices) {
    const std::string index_text(index_key.str());
    const std::string path = where + "." + index_text;
    if (!is_index(index_text)) throw SceneError(path + ": expected an array index");
    // from_chars, not stoul: an index too long for size_t is out of range too, not an exception
    // escaping the parser (found by fuzz_scene_parser: materials.888888888888888888888881.…).
    std::size_t index = 0;
    const auto [end, error] = std::from_chars(index_text.data(), index_text.data() + index_text.size(), index);
    if (error != std::errc() || end != index_text.data() + index_text.size() || index >= dest.size()) {
      throw SceneError(path + ": index out of range (the array has " + std::to_string(dest.size()) + " elements)");
    }
    toml::node& element = *dest.get(index);
    if (auto* element_table = element.as_table(); element_table != nullptr && value.is_table()) {
      for (auto&& [k, v] : *value.as_table()) merge_node(*element_table, std::string(k.str()), v, path);
    } else {
      value.visit([&](auto&& concrete) { dest.replace(dest.cbegin() + static_cast<std::ptrdiff_t>(index), std::move(concrete)); });
    }
  }
}

void merge_node(toml::table& dest, const std::string& key, toml::node& value, const std::string& where) {
  const std::string path = where.empty() ? key : where + "." + key;
  toml::node* existing = dest.get(key);
  if (existing != nullptr && existing->is_table() && value.is_table()) {
    for (auto&& [k, v] : *value.as_table()) merge_node(*existing->as_table(), std::string(k.str()), v, path);
    return;
  }
  if (existing != nullptr && existing->is_array() && value.is_table()) {
    merge_into_array(*existing->as_array(), *value.as_table(), path);
    return;
  }
  value.visit([&](auto&& concrete) { dest.insert_or_assign(key, std::move(concrete)); });
}

void apply_override(toml::table& root, const std::string& assignment, const std::string& source) {
  const std::size_t equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw SceneError(source + ": --set " + assignment + ": expected key=value");
  }
  const std::string key = assignment.substr(0, equals);
  const std::string value = assignment.substr(equals + 1);
  std::stringstream segments(key);
  for (std::string segment; std::getline(segments, segment, '.');) {
    if (!is_bare_key_segment(segment)) throw SceneError(source + ": --set " + key + ": not a dotted key");
  }
  if (key.back() == '.') throw SceneError(source + ": --set " + key + ": not a dotted key");
  toml::table parsed;
  try {
    parsed = toml::parse(key + " = " + value);
  } catch (const toml::parse_error&) {
    try {  // a bare word: take it as a string (`--set simulate.material=Urea`)
      parsed = toml::parse(key + " = " + quote_toml_string(value));
    } catch (const toml::parse_error& e) {
      throw SceneError(source + ": --set " + key + ": cannot parse value: " + std::string(e.description()));
    }
  }
  try {
    for (auto&& [k, v] : parsed) merge_node(root, std::string(k.str()), v, "");
  } catch (const SceneError& e) {
    throw SceneError(source + ": --set " + assignment + ": " + e.what());
  }
}

// ---- typed reading with unknown-key detection ------------------------------------------------------

class Section {
 public:
  Section(const toml::table* table, std::string path, const std::string& source)
      : table_(table), path_(std::move(path)), source_(source) {}

  std::string key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw SceneError(source_ + ": " + key_path(key) + ": " + problem);
  }

  const toml::node* get(const std::string& key) {
    used_.insert(key);
    return table_ != nullptr ? table_->get(key) : nullptr;
  }
  // Whether the scene (or an override) sets the key, as opposed to leaving it at its default.
  bool present(const std::string& key) const { return table_ != nullptr && table_->get(key) != nullptr; }

  double number(const std::string& key, double fallback) {
    const toml::node* node = get(key);
    if (node == nullptr) return fallback;
    return to_number(*node, key);
  }

  double to_number(const toml::node& node, const std::string& key) const {
    if (const auto* f = node.as_floating_point()) {
      const double value = f->get();
      if (!std::isfinite(value)) fail(key, "must be a finite number, got " + format_number(value));
      return value;
    }
    if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
    fail(key, std::string("expected a number, got ") + type_name(node));
  }

  std::int64_t integer(const std::string& key, std::int64_t fallback) {
    const toml::node* node = get(key);
    if (node == nullptr) return fallback;
    if (const auto* i = node->as_integer()) return i->get();
    fail(key, std::string("expected an integer, got ") + type_name(*node));
  }

  int small_integer(const std::string& key, int fallback) {
    const std::int64_t value = integer(key, fallback);
    if (value < -1'000'000'000 || value > 1'000'000'000) fail(key, "out of range, got " + std::to_string(value));
    return static_cast<int>(value);
  }

  bool boolean(const std::string& key, bool fallback) {
    const toml::node* node = get(key);
    if (node == nullptr) return fallback;
    if (const auto* b = node->as_boolean()) return b->get();
    fail(key, std::string("expected true or false, got ") + type_name(*node));
  }

  std::string string(const std::string& key, const std::string& fallback) {
    const toml::node* node = get(key);
    if (node == nullptr) return fallback;
    if (const auto* s = node->as_string()) return s->get();
    fail(key, std::string("expected a string, got ") + type_name(*node));
  }

  std::vector<double> numbers(const std::string& key, const std::vector<double>& fallback) {
    const toml::node* node = get(key);
    if (node == nullptr) return fallback;
    const toml::array* array = node->as_array();
    if (array == nullptr) fail(key, std::string("expected an array of numbers, got ") + type_name(*node));
    std::vector<double> values;
    for (std::size_t i = 0; i < array->size(); ++i) {
      values.push_back(to_number(*array->get(i), key + "[" + std::to_string(i) + "]"));
    }
    return values;
  }

  std::vector<std::string> strings(const std::string& key, const std::vector<std::string>& fallback) {
    const toml::node* node = get(key);
    if (node == nullptr) return fallback;
    const toml::array* array = node->as_array();
    if (array == nullptr) fail(key, std::string("expected an array of strings, got ") + type_name(*node));
    std::vector<std::string> values;
    for (std::size_t i = 0; i < array->size(); ++i) {
      const auto* s = array->get(i)->as_string();
      if (s == nullptr) fail(key + "[" + std::to_string(i) + "]", "expected a string");
      values.push_back(s->get());
    }
    return values;
  }

  template <typename Enum>
  Enum choice(const std::string& key, Enum fallback, const std::vector<std::pair<std::string, Enum>>& options) {
    const std::string text = string(key, "");
    if (text.empty() && get(key) == nullptr) return fallback;
    std::string allowed;
    for (const auto& [name, value] : options) {
      if (name == text) return value;
      allowed += (allowed.empty() ? "\"" : ", \"") + name + "\"";
    }
    fail(key, "unknown value \"" + text + "\" (expected one of " + allowed + ")");
  }

  // Every key of the table must have been asked for.
  void finish() const {
    if (table_ == nullptr) return;
    for (auto&& [key, value] : *table_) {
      const std::string name(key.str());
      if (used_.count(name) == 0) fail(name, "unknown key");
    }
  }

 private:
  static const char* type_name(const toml::node& node) {
    switch (node.type()) {
      case toml::node_type::table: return "a table";
      case toml::node_type::array: return "an array";
      case toml::node_type::string: return "a string";
      case toml::node_type::integer: return "an integer";
      case toml::node_type::floating_point: return "a number";
      case toml::node_type::boolean: return "a boolean";
      default: return "a date/time";
    }
  }

  const toml::table* table_;
  std::string path_;
  const std::string& source_;
  std::set<std::string> used_;
};

const toml::table* sub_table(const toml::table& root, const std::string& key, const std::string& source) {
  const toml::node* node = root.get(key);
  if (node == nullptr) return nullptr;
  if (!node->is_table()) throw SceneError(source + ": " + key + ": expected a table ([" + key + "])");
  return node->as_table();
}

// ---- validation helpers ----------------------------------------------------------------------------

struct Checker {
  const std::string& source;
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw SceneError(source + ": " + key + ": " + problem);
  }
  void positive(const std::string& key, double value) const {
    if (!(value > 0.0)) fail(key, "must be > 0, got " + format_number(value));
  }
  void non_negative(const std::string& key, double value) const {
    if (!(value >= 0.0)) fail(key, "must be >= 0, got " + format_number(value));
  }
  void positive_at_most(const std::string& key, double value, double hi) const {
    positive(key, value);
    if (!(value <= hi)) fail(key, "must be <= " + format_number(hi) + ", got " + format_number(value));
  }
  void non_negative_at_most(const std::string& key, double value, double hi) const {
    non_negative(key, value);
    if (!(value <= hi)) fail(key, "must be <= " + format_number(hi) + ", got " + format_number(value));
  }
  // A schema's bounds: "must be in [lo, hi]" for a closed interval, else the bound that is broken.
  void within(const std::string& key, double value, const tables::Bounds& b) const {
    const bool low_ok = b.low_open ? value > b.low : value >= b.low;
    const bool high_ok = b.high_open ? value < b.high : value <= b.high;
    if (low_ok && high_ok) return;
    if (!b.low_open && !b.high_open) in_range(key, value, b.low, b.high);
    if (!low_ok) fail(key, std::string(b.low_open ? "must be > " : "must be >= ") + format_number(b.low) + ", got " + format_number(value));
    fail(key, std::string(b.high_open ? "must be < " : "must be <= ") + format_number(b.high) + ", got " + format_number(value));
  }
  void in_range(const std::string& key, double value, double lo, double hi) const {
    if (!(value >= lo && value <= hi)) {
      fail(key, "must be in [" + format_number(lo) + ", " + format_number(hi) + "], got " + format_number(value));
    }
  }
};

void read_machine(const toml::table& root, Scene& scene) {
  Section s(sub_table(root, "machine", scene.source_name), "machine", scene.source_name);
  Machine& m = scene.machine;
  m.name = s.string("name", m.name);
  m.disc_radius_m = s.number("disc_radius_m", m.disc_radius_m);
  m.disc_height_m = s.number("disc_height_m", m.disc_height_m);
  m.disc_count = s.small_integer("disc_count", m.disc_count);
  m.disc_spacing_m = s.number("disc_spacing_m", m.disc_spacing_m);
  m.rotation_sense = s.small_integer("rotation_sense", m.rotation_sense);
  m.cone_angle_rad = s.number("cone_angle_rad", m.cone_angle_rad);
  m.vane_count = s.small_integer("vane_count", m.vane_count);
  m.vane_start_radius_m = s.number("vane_start_radius_m", m.vane_start_radius_m);
  m.vane_end_radius_m = s.number("vane_end_radius_m", m.vane_end_radius_m);
  m.vane_height_m = s.number("vane_height_m", m.vane_height_m);
  m.vane_pitch_rad = s.number("vane_pitch_rad", m.vane_pitch_rad);
  m.disc_model = s.choice<DiscModel>("disc_model", m.disc_model,
                                     {{"analytic", DiscModel::kAnalytic}, {"mesh", DiscModel::kMesh},
                                      {"stl", DiscModel::kStl}});
  m.mesh_size_m = s.number("mesh_size_m", m.mesh_size_m);
  m.stl_path = s.string("stl_path", m.stl_path);
  m.stl_scale = s.number("stl_scale", m.stl_scale);
  m.rpm = s.number("rpm", m.rpm);
  s.finish();
}

void read_inlet(const toml::table& root, Scene& scene) {
  Section s(sub_table(root, "inlet", scene.source_name), "inlet", scene.source_name);
  Inlet& in = scene.inlet;
  in.radius_m = s.number("radius_m", in.radius_m);
  in.offset_m = s.number("offset_m", in.offset_m);
  in.angle_rad = s.number("angle_rad", in.angle_rad);
  in.drop_height_m = s.number("drop_height_m", in.drop_height_m);
  in.mass_flow_kg_s = s.number("mass_flow_kg_s", in.mass_flow_kg_s);
  s.finish();
}

void read_materials(const toml::table& root, Scene& scene) {
  const toml::node* node = root.get("materials");
  if (node == nullptr) return;
  const toml::array* array = node->as_array();
  if (array == nullptr) throw SceneError(scene.source_name + ": materials: expected an array of tables ([[materials]])");
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::string path = "materials[" + std::to_string(i) + "]";
    const toml::table* table = array->get(i)->as_table();
    if (table == nullptr) throw SceneError(scene.source_name + ": " + path + ": expected a table");
    Section s(table, path, scene.source_name);
    Material m;
    m.name = s.string("name", "");
    for (const tables::MaterialQuantity& q : tables::kMaterialQuantities) {
      const std::string key(q.name);
      // A required quantity left out reads as 0, which its bounds (> 0) then refuse naming the key.
      m.*q.member = s.number(key, std::isnan(q.scene_default) ? 0.0 : q.scene_default);
    }
    s.finish();
    scene.materials.push_back(std::move(m));
  }
}

void read_simulate(const toml::table& root, Scene& scene) {
  Section s(sub_table(root, "simulate", scene.source_name), "simulate", scene.source_name);
  scene.simulate_material = s.string("material", "");
  s.finish();
}

void read_air(const toml::table& root, Scene& scene) {
  Section s(sub_table(root, "air", scene.source_name), "air", scene.source_name);
  Air& air = scene.air;
  air.density_kg_m3 = s.number("density_kg_m3", air.density_kg_m3);
  air.viscosity_pa_s = s.number("viscosity_pa_s", air.viscosity_pa_s);
  const std::vector<double> wind = s.numbers("wind_m_s", {air.wind_m_s[0], air.wind_m_s[1]});
  if (wind.size() != 2) s.fail("wind_m_s", "expected [vx, vy], got " + std::to_string(wind.size()) + " values");
  air.wind_m_s = {wind[0], wind[1]};
  s.finish();
}

void read_effects(const toml::table& root, Scene& scene) {
  const toml::table* table = sub_table(root, "effects", scene.source_name);
  Section s(table, "effects", scene.source_name);
  if (table == nullptr || table->get("enabled") == nullptr) {
    s.finish();
    return;  // defaults of Effects
  }
  const std::vector<std::string> names = s.strings("enabled", {});
  s.finish();
  EffectSet effects = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string key = "enabled[" + std::to_string(i) + "]";
    const effect::Effect* row = effect::find(names[i]);
    if (row == nullptr) {
      s.fail(key, "unknown effect \"" + names[i] + "\" (known: " + effect::names_of(effect::kAll) + ")");
    }
    if ((effects & row->bit) != 0) s.fail(key, "effect \"" + names[i] + "\" listed twice");
    effects |= row->bit;
  }
  for (const effect::Effect& row : effect::kRegistry) {
    const EffectSet missing = (effects & row.bit) != 0 ? row.requires_effects & ~effects : 0u;
    if (missing != 0) {
      s.fail("enabled", "effect \"" + std::string(row.name) + "\" needs " + effect::names_of(missing) +
                            ": add it to the list or remove \"" + std::string(row.name) + "\"");
    }
  }
  scene.effects = effects;
}

void read_numerics(const toml::table& root, Scene& scene) {
  Section s(sub_table(root, "numerics", scene.source_name), "numerics", scene.source_name);
  Numerics& n = scene.numerics;
  const std::int64_t seed = s.integer("seed", static_cast<std::int64_t>(n.seed));
  if (seed < 0) s.fail("seed", "must be >= 0, got " + std::to_string(seed));
  n.seed = static_cast<std::uint64_t>(seed);
  n.duration_s = s.number("duration_s", n.duration_s);
  n.dt_contact_s = s.number("dt_contact_s", n.dt_contact_s);
  n.steps_per_contact = s.small_integer("steps_per_contact", n.steps_per_contact);
  n.integrator = s.choice<Integrator>("integrator", n.integrator,
                                      {{"symplectic_euler", Integrator::kSymplecticEuler},
                                       {"velocity_verlet", Integrator::kVelocityVerlet}});
  n.contact_model = s.choice<ContactModel>("contact_model", n.contact_model,
                                           {{"hertz_thornton", ContactModel::kHertzThornton},
                                            {"hertz_mindlin", ContactModel::kHertzThornton},  // alias: the older name
                                            {"linear", ContactModel::kLinear}});
  n.flight_scheme = s.choice<FlightScheme>("flight_scheme", n.flight_scheme,
                                           {{"rk4", FlightScheme::kRk4}, {"dopri5", FlightScheme::kDopri5}});
  n.flight_dt_s = s.number("flight_dt_s", n.flight_dt_s);
  n.flight_tolerance = s.number("flight_tolerance", n.flight_tolerance);
  n.collector_radius_m = s.number("collector_radius_m", n.collector_radius_m);
  n.threads = s.small_integer("threads", n.threads);
  s.finish();
}

void read_sweep(const toml::table& root, Scene& scene) {
  Section s(sub_table(root, "sweep", scene.source_name), "sweep", scene.source_name);
  Sweep& sw = scene.sweep;
  sw.rpm = s.numbers("rpm", sw.rpm);
  sw.materials = s.strings("materials", sw.materials);
  sw.source = s.choice<LaunchSource>("source", sw.source,
                                     {{"analytic", LaunchSource::kAnalytic}, {"dem", LaunchSource::kDem}});
  sw.samples_per_run = s.small_integer("samples_per_run", sw.samples_per_run);
  sw.output = s.string("output", sw.output);
  sw.spin_model = s.choice<SpinModel>("spin_model", sw.spin_model,
                                      {{"rolling", SpinModel::kRolling}, {"sliding", SpinModel::kSliding}});
  sw.batch_s = s.number("batch_s", sw.batch_s);
  sw.convergence_tolerance = s.number("convergence_tolerance", sw.convergence_tolerance);
  sw.particle_budget = s.small_integer("particle_budget", sw.particle_budget);
  sw.working_width_ci_m = s.number("working_width_ci_m", sw.working_width_ci_m);
  // A key of the other launch source would be recorded as provenance yet never act: refuse it.
  if (sw.source == LaunchSource::kDem && s.present("spin_model")) {
    s.fail("spin_model", "applies to the analytic source only, but sweep.source is \"dem\" (DEM launches carry "
                         "their own spin): remove the key or set sweep.source = \"analytic\"");
  }
  if (sw.source == LaunchSource::kAnalytic) {
    for (const char* key : {"batch_s", "convergence_tolerance", "particle_budget", "working_width_ci_m"}) {
      if (s.present(key)) {
        s.fail(key, "applies to the DEM source only, but sweep.source is \"analytic\": remove the key or set "
                    "sweep.source = \"dem\"");
      }
    }

  }
  s.finish();
}

void read_outputs(const toml::table& root, Scene& scene) {
  Section s(sub_table(root, "outputs", scene.source_name), "outputs", scene.source_name);
  Outputs& o = scene.outputs;
  o.directory = s.string("directory", o.directory);
  o.vtk_every_steps = s.small_integer("vtk_every_steps", o.vtk_every_steps);
  o.launch_csv = s.boolean("launch_csv", o.launch_csv);
  o.pattern_png = s.boolean("pattern_png", o.pattern_png);
  s.finish();
}

void check_top_level_keys(const toml::table& root, const std::string& source) {
  static const std::set<std::string> known{"machine", "inlet",    "materials", "simulate", "air",
                                           "effects", "numerics", "sweep",     "outputs"};
  for (auto&& [key, value] : root) {
    const std::string name(key.str());
    if (known.count(name) == 0) throw SceneError(source + ": " + name + ": unknown key");
  }
}

// ---- validation ------------------------------------------------------------------------------------

void validate(Scene& scene) {
  const Checker c{scene.source_name};
  Machine& m = scene.machine;
  if (m.name.empty()) c.fail("machine.name", "must not be empty");
  // Upper bounds: the table file's plausibility limits (tables::PlausibleLimits), so that a scene the
  // builder accepts always gives a table the reader and the predictor accept.
  using L = tables::PlausibleLimits;
  c.positive_at_most("machine.disc_radius_m", m.disc_radius_m, L::kMaxDiscRadius_m);
  c.positive_at_most("machine.disc_height_m", m.disc_height_m, L::kMaxDiscHeight_m);
  if (m.disc_count != 1 && m.disc_count != 2) c.fail("machine.disc_count", "must be 1 or 2, got " + std::to_string(m.disc_count));
  c.non_negative_at_most("machine.disc_spacing_m", m.disc_spacing_m, L::kMaxDiscSpacing_m);
  if (m.disc_count == 2 && !(m.disc_spacing_m >= 2.0 * m.disc_radius_m)) {
    c.fail("machine.disc_spacing_m", "must be >= 2 x disc_radius_m = " + format_number(2.0 * m.disc_radius_m) +
                                         " for two discs, got " + format_number(m.disc_spacing_m));
  }
  if (m.rotation_sense != 1 && m.rotation_sense != -1) {
    c.fail("machine.rotation_sense", "must be +1 or -1, got " + std::to_string(m.rotation_sense));
  }
  c.in_range("machine.cone_angle_rad", m.cone_angle_rad, 0.0, 1.2);
  if (m.vane_count < 0 || m.vane_count > 64) c.fail("machine.vane_count", "must be in [0, 64], got " + std::to_string(m.vane_count));
  if (m.vane_end_radius_m == 0.0) m.vane_end_radius_m = m.disc_radius_m;
  c.non_negative("machine.vane_start_radius_m", m.vane_start_radius_m);
  c.positive("machine.vane_end_radius_m", m.vane_end_radius_m);
  if (m.vane_end_radius_m > m.disc_radius_m * (1.0 + 1e-12)) {
    c.fail("machine.vane_end_radius_m", "must be <= disc_radius_m = " + format_number(m.disc_radius_m) + ", got " +
                                            format_number(m.vane_end_radius_m));
  }
  if (!(m.vane_start_radius_m < m.vane_end_radius_m)) {
    c.fail("machine.vane_start_radius_m", "must be < vane_end_radius_m = " + format_number(m.vane_end_radius_m) +
                                              ", got " + format_number(m.vane_start_radius_m));
  }
  if (m.vane_count > 0) c.positive("machine.vane_height_m", m.vane_height_m);
  c.in_range("machine.vane_pitch_rad", m.vane_pitch_rad, -1.2, 1.2);
  if (m.mesh_size_m == 0.0) m.mesh_size_m = kDefaultMeshSizePerRadius * m.disc_radius_m;
  c.positive("machine.mesh_size_m", m.mesh_size_m);
  // The file itself (exists, is STL, has triangles) is checked where it is read (dem::config_from_scene).
  if (m.disc_model == DiscModel::kStl && m.stl_path.empty()) c.fail("machine.stl_path", "required when disc_model = \"stl\"");
  if (m.disc_model != DiscModel::kStl && !m.stl_path.empty())
    c.fail("machine.stl_path", "is only used with disc_model = \"stl\" (disc_model is \"" + std::string(to_string(m.disc_model)) + "\")");
  c.positive("machine.stl_scale", m.stl_scale);
  c.positive_at_most("machine.rpm", m.rpm, L::kMaxRpm);

  const Inlet& in = scene.inlet;
  c.positive("inlet.radius_m", in.radius_m);
  c.non_negative("inlet.offset_m", in.offset_m);
  if (!(in.offset_m + in.radius_m <= m.disc_radius_m)) {
    c.fail("inlet.offset_m", "inlet circle reaches beyond the disc rim (offset_m + radius_m = " +
                                 format_number(in.offset_m + in.radius_m) + " > disc_radius_m = " +
                                 format_number(m.disc_radius_m) + ")");
  }
  c.non_negative("inlet.drop_height_m", in.drop_height_m);
  c.positive("inlet.mass_flow_kg_s", in.mass_flow_kg_s);

  if (scene.materials.empty()) c.fail("materials", "at least one [[materials]] entry is required");
  std::set<std::string> names;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& mat = scene.materials[i];
    const std::string p = "materials[" + std::to_string(i) + "].";
    if (mat.name.empty()) c.fail(p + "name", "must be given and not empty");
    if (!names.insert(mat.name).second) c.fail(p + "name", "duplicate material name \"" + mat.name + "\"");
    for (const tables::MaterialQuantity& q : tables::kMaterialQuantities) {
      const std::string key = p + std::string(q.name);
      const double value = mat.*q.member;
      c.within(key, value, q.scene_bounds);
      // A value for an effect that is off would be recorded as provenance yet never act: refuse it.
      if (q.effect != 0 && !scene.has(q.effect) && value != q.scene_default) {
        const std::string effect_name(effect::row(q.effect).name);
        c.fail(key, "is " + format_number(value) + " but the `" + effect_name + "` effect is off: add \"" +
                        effect_name + "\" to effects.enabled or remove the key");
      }
    }
  }
  if ((scene.air.wind_m_s[0] != 0.0 || scene.air.wind_m_s[1] != 0.0) && !scene.has(effect::kWind)) {
    c.fail("air.wind_m_s", "is not zero but the `wind` effect is off: add \"wind\" to effects.enabled or set it to [0.0, 0.0]");
  }
  if (scene.simulate_material.empty()) {
    scene.simulate_material = scene.materials.front().name;
  } else if (scene.find_material(scene.simulate_material) == nullptr) {
    c.fail("simulate.material", "no material named \"" + scene.simulate_material + "\"");
  }

  c.non_negative("air.density_kg_m3", scene.air.density_kg_m3);
  c.positive("air.viscosity_pa_s", scene.air.viscosity_pa_s);

  Numerics& n = scene.numerics;
  c.positive("numerics.duration_s", n.duration_s);
  c.non_negative("numerics.dt_contact_s", n.dt_contact_s);
  if (n.steps_per_contact < 1) c.fail("numerics.steps_per_contact", "must be >= 1, got " + std::to_string(n.steps_per_contact));
  c.positive("numerics.flight_dt_s", n.flight_dt_s);
  if (!(n.flight_tolerance > 0.0 && n.flight_tolerance < 1.0)) {
    c.fail("numerics.flight_tolerance", "must be in (0, 1), got " + format_number(n.flight_tolerance));
  }
  c.non_negative("numerics.collector_radius_m", n.collector_radius_m);
  if (n.collector_radius_m == 0.0) n.collector_radius_m = m.disc_radius_m;
  if (n.collector_radius_m < m.disc_radius_m) {
    c.fail("numerics.collector_radius_m", "must be >= disc_radius_m = " + format_number(m.disc_radius_m) + ", got " +
                                              format_number(n.collector_radius_m));
  }
  if (n.threads < 0) c.fail("numerics.threads", "must be >= 0, got " + std::to_string(n.threads));

  Sweep& sw = scene.sweep;
  std::set<double> seen_rpm;
  for (std::size_t i = 0; i < sw.rpm.size(); ++i) {
    c.positive_at_most("sweep.rpm[" + std::to_string(i) + "]", sw.rpm[i], L::kMaxRpm);
    if (!seen_rpm.insert(sw.rpm[i]).second) c.fail("sweep.rpm[" + std::to_string(i) + "]", "duplicate rpm " + format_number(sw.rpm[i]));
  }
  std::set<std::string> seen_material;
  for (std::size_t i = 0; i < sw.materials.size(); ++i) {
    const std::string key = "sweep.materials[" + std::to_string(i) + "]";
    if (scene.find_material(sw.materials[i]) == nullptr) c.fail(key, "no material named \"" + sw.materials[i] + "\"");
    if (!seen_material.insert(sw.materials[i]).second) c.fail(key, "material \"" + sw.materials[i] + "\" listed twice");
  }
  if (sw.samples_per_run < 1 || sw.samples_per_run > 10'000'000) {
    c.fail("sweep.samples_per_run", "must be in [1, 10000000], got " + std::to_string(sw.samples_per_run));
  }
  if (sw.output.empty()) c.fail("sweep.output", "must not be empty");
  c.positive("sweep.batch_s", sw.batch_s);
  c.positive("sweep.convergence_tolerance", sw.convergence_tolerance);
  if (sw.particle_budget < 0) c.fail("sweep.particle_budget", "must be >= 0, got " + std::to_string(sw.particle_budget));
  if (!(sw.working_width_ci_m >= 0.0 && sw.working_width_ci_m <= 100.0)) {
    c.fail("sweep.working_width_ci_m", "must be in [0, 100] m (0: no such rule), got " +
                                           std::to_string(sw.working_width_ci_m));
  }
  if (scene.outputs.vtk_every_steps < 0) {
    c.fail("outputs.vtk_every_steps", "must be >= 0, got " + std::to_string(scene.outputs.vtk_every_steps));
  }
  if (scene.outputs.directory.empty()) c.fail("outputs.directory", "must not be empty");
}

}  // namespace

Scene parse_scene(const std::string& toml_text, const std::string& source_name,
                  const std::vector<std::string>& overrides) {
  Scene scene;
  scene.source_name = source_name;
  scene.text = toml_text;
  scene.overrides = overrides;
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw SceneError(source_name + ":" + std::to_string(e.source().begin.line) + ":" +
                     std::to_string(e.source().begin.column) + ": " + std::string(e.description()));
  }
  for (const std::string& assignment : overrides) apply_override(root, assignment, source_name);
  check_top_level_keys(root, source_name);
  read_machine(root, scene);
  read_inlet(root, scene);
  read_materials(root, scene);
  read_simulate(root, scene);
  read_air(root, scene);
  read_effects(root, scene);
  read_numerics(root, scene);
  read_sweep(root, scene);
  read_outputs(root, scene);
  validate(scene);
  return scene;
}

Scene load_scene_file(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  Scene scene = parse_scene(text.str(), path, overrides);
  // A disc STL named relative to the scene travels with it: resolve against the scene file's directory.
  std::string& stl = scene.machine.stl_path;
  if (!stl.empty() && std::filesystem::path(stl).is_relative())
    stl = (std::filesystem::path(path).parent_path() / stl).lexically_normal().string();
  // Checked here, whatever the launch source: a missing disc file must not wait for the first DEM run
  // (the builder would have created an empty table by then). Its content is checked where it is read.
  if (!stl.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(stl, ec)) {
      throw SceneError(path + ": machine.stl_path: no such file: " + stl + " (relative paths are relative to the scene file)");
    }
  }
  return scene;
}

}  // namespace spread::scene
