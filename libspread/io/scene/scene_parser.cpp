// TOML → Scene, through the TOML document (toml_document.hpp) and the key rows (scene_keys.hpp).
// Order: parse the text, merge the --set overrides into the tree, read every section while recording
// the keys it knows (anything left over is an "unknown key" error), then validate: each key's range and
// effect from its row, then the relations between keys.
#include <cmath>
#include <filesystem>
#include <set>

#include "libspread/io/scene/material_entry.hpp"
#include "libspread/io/scene/product_library.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/scene/scene_key.hpp"
#include "libspread/io/scene/scene_keys.hpp"
#include "libspread/io/scene/toml_document.hpp"
#include "libspread/io/tables/material_schema.hpp"

namespace spread::scene {
namespace {

struct Checker {
  const std::string& source;
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw SceneError(source + ": " + key + ": " + problem);
  }
};

template <typename Owner, std::size_t N>
void read_section(const TomlDocument& doc, const std::string& name, Owner& owner, const std::array<Key<Owner>, N>& keys) {
  TomlSection s = doc.section(name);
  read_keys<Owner>(s, owner, keys);
  s.finish();
}

// The product library a scene names, read when an entry first takes a product from it.
struct LibraryReader {
  Scene& scene;
  std::vector<Material> library;
  std::string path;

  // The product the entry names (`product`), or nullptr when it names none; its note goes into the
  // provenance under `entry`.
  const Material* product_of(TomlSection& s, const std::string& entry) {
    const std::string key(kMaterialProductKey);
    const std::optional<std::string> product = s.string(key);
    if (!product) return nullptr;
    if (scene.products.file.empty()) s.fail(key, "names a product, but the scene names no library ([products] file)");
    if (library.empty()) {
      path = product_library_path(scene.source_name, scene.products.file);
      std::error_code ec;
      if (!std::filesystem::is_regular_file(path, ec)) {
        throw SceneError(scene.source_name + ": products.file: no such library file: " + path +
                         " (relative paths are relative to the scene file)");
      }
      library = read_product_library(path);
    }
    const Material* base = nullptr;
    for (const Material& p : library) base = p.name == *product ? &p : base;
    if (base == nullptr) {
      std::string known;
      for (const Material& p : library) known += (known.empty() ? "\"" : ", \"") + p.name + "\"";
      s.fail(key, "no product \"" + *product + "\" in " + path + " (products: " + known + ")");
    }
    scene.product_notes.push_back(product_note(entry, *base, scene.products.file));
    return base;
  }
};

// A blend entry: its name and its components, each read like a material entry (a product, its own keys
// replacing the product's) with its mass fraction and nutrient contents. The blend has no quantities of
// its own: a quantity key beside `components` is an error, never silently unused.
Material read_blend(TomlSection& s, LibraryReader& reader, const std::string& entry) {
  Material blend;
  blend.name = s.string("name").value_or("");
  for (const tables::MaterialQuantity& q : tables::kMaterialQuantities) {
    if (s.present(std::string(q.name)))
      s.fail(std::string(q.name), "a blend's quantities are its components': give it in each [[" + entry + ".components]]");
  }
  std::vector<TomlSection> sections = s.tables("components");
  for (std::size_t j = 0; j < sections.size(); ++j) {
    TomlSection& c = sections[j];
    tables::BlendComponent component;
    const Material* base = reader.product_of(c, entry + ".components[" + std::to_string(j) + "]");
    component.material = read_material_entry(c, base);
    component.mass_fraction = c.number("mass_fraction").value_or(0.0);
    if (!c.present("mass_fraction")) c.fail("mass_fraction", "missing: each component needs its share of the blend's mass");
    for (const tables::Nutrient& nutrient : tables::kNutrients)
      component.*nutrient.member = c.number(nutrient.key).value_or(0.0);
    c.finish();
    blend.components.push_back(std::move(component));
  }
  const std::string problem = tables::blend_problem(blend.components);
  if (!problem.empty()) {
    const std::size_t colon = problem.find(": ");
    s.fail(problem.substr(0, colon), problem.substr(colon + 2));
  }
  return blend;
}

// Each entry from the schema's defaults, or from the library product it names (`product`), its own keys
// replacing the product's values; an entry with `components` is a blend of them.
void read_materials(const TomlDocument& doc, Scene& scene) {
  LibraryReader reader{scene, {}, {}};
  for (TomlSection& s : doc.array_of_tables("materials")) {
    const std::string entry = "materials[" + std::to_string(scene.materials.size()) + "]";
    if (s.present("components")) {
      if (s.present(std::string(kMaterialProductKey)))
        s.fail(std::string(kMaterialProductKey), "a blend names its products in its components, not itself");
      Material blend = read_blend(s, reader, entry);
      s.finish();
      scene.materials.push_back(std::move(blend));
      continue;
    }
    const Material* base = reader.product_of(s, entry);
    Material m = read_material_entry(s, base);
    s.finish();
    scene.materials.push_back(std::move(m));
  }
}

void read_effects(const TomlDocument& doc, Scene& scene) {
  TomlSection s = doc.section("effects");
  const std::optional<std::vector<std::string>> names = s.strings("enabled");
  s.finish();
  if (!names) return;  // the registry's defaults
  EffectSet effects = 0;
  for (std::size_t i = 0; i < names->size(); ++i) {
    const std::string& name = (*names)[i];
    const std::string key = "enabled[" + std::to_string(i) + "]";
    const effect::Effect* row = effect::find(name);
    if (row == nullptr) {
      s.fail(key, "unknown effect \"" + name + "\" (known: " + effect::names_of(effect::kAll) + ")");
    }
    if ((effects & row->bit) != 0) s.fail(key, "effect \"" + name + "\" listed twice");
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

// A key of the other launch source would be recorded as provenance yet never act: refuse it.
void check_sweep_source_keys(const TomlDocument& doc, const Scene& scene) {
  const TomlSection s = doc.section("sweep");
  if (scene.sweep.source == LaunchSource::kDem && s.present("spin_model")) {
    s.fail("spin_model", "applies to the analytic source only, but sweep.source is \"dem\" (DEM launches carry "
                         "their own spin): remove the key or set sweep.source = \"analytic\"");
  }
  if (scene.sweep.source == LaunchSource::kAnalytic) {
    for (const char* key : {"batch_s", "convergence_tolerance", "particle_budget", "working_width_ci_m"}) {
      if (s.present(key)) {
        s.fail(key, "applies to the DEM source only, but sweep.source is \"analytic\": remove the key or set "
                    "sweep.source = \"dem\"");
      }
    }
  }
}

// ---- validation ------------------------------------------------------------------------------------

template <typename Owner, std::size_t N>
void check_section(const Scene& scene, const std::string& path, const Owner& owner, const std::array<Key<Owner>, N>& keys) {
  check_keys<Owner>(scene.source_name, path, owner, keys, scene.effects);
}

// One material's quantities (a plain material, or a blend's component) against their scene ranges and
// effects; `p` is the entry's key prefix ("materials[0]." or "materials[0].components[1].").
void check_quantities(const Scene& scene, const std::string& p, const Material& mat) {
  for (const tables::MaterialQuantity& q : tables::kMaterialQuantities) {
    const std::string key = p + std::string(q.name);
    const double value = mat.*q.member;
    check_within(scene.source_name, key, value, q.scene_bounds);
    if (q.effect != 0 && !scene.has(q.effect) && value != q.scene_default) {
      fail_effect_off(scene.source_name, key, format_number(value), q.effect);
    }
  }
}

void validate(Scene& scene) {
  const Checker c{scene.source_name};
  Machine& m = scene.machine;
  check_section(scene, "machine", m, kMachineKeys);
  if (m.name.empty()) c.fail("machine.name", "must not be empty");
  if (m.disc_count == 2 && !(m.disc_spacing_m >= 2.0 * m.disc_radius_m)) {
    c.fail("machine.disc_spacing_m", "must be >= 2 x disc_radius_m = " + format_number(2.0 * m.disc_radius_m) +
                                         " for two discs, got " + format_number(m.disc_spacing_m));
  }
  if (m.rotation_sense == 0) c.fail("machine.rotation_sense", "must be +1 or -1, got 0");
  // 0 = the rim (docs/scene-format.md).
  if (m.vane_end_radius_m == 0.0) m.vane_end_radius_m = m.disc_radius_m;
  if (m.vane_end_radius_m > m.disc_radius_m * (1.0 + 1e-12)) {
    c.fail("machine.vane_end_radius_m", "must be <= disc_radius_m = " + format_number(m.disc_radius_m) + ", got " +
                                            format_number(m.vane_end_radius_m));
  }
  if (!(m.vane_start_radius_m < m.vane_end_radius_m)) {
    c.fail("machine.vane_start_radius_m", "must be < vane_end_radius_m = " + format_number(m.vane_end_radius_m) +
                                              ", got " + format_number(m.vane_start_radius_m));
  }
  if (m.vane_count > 0 && !(m.vane_height_m > 0.0)) {
    c.fail("machine.vane_height_m", "must be > 0 when there are vanes, got " + format_number(m.vane_height_m));
  }
  // 0 = the coarsest ξ/R within 1 % (kDefaultMeshSizePerRadius).
  if (m.mesh_size_m == 0.0) m.mesh_size_m = kDefaultMeshSizePerRadius * m.disc_radius_m;
  // The file itself (exists, is STL, has triangles) is checked where it is read (dem::config_from_scene).
  if (m.disc_model == DiscModel::kStl && m.stl_path.empty()) c.fail("machine.stl_path", "required when disc_model = \"stl\"");
  if (m.disc_model != DiscModel::kStl && !m.stl_path.empty())
    c.fail("machine.stl_path", "is only used with disc_model = \"stl\" (disc_model is \"" + std::string(to_string(m.disc_model)) + "\")");

  const Inlet& in = scene.inlet;
  check_section(scene, "inlet", in, kInletKeys);
  if (!(in.offset_m + in.radius_m <= m.disc_radius_m)) {
    c.fail("inlet.offset_m", "inlet circle reaches beyond the disc rim (offset_m + radius_m = " +
                                 format_number(in.offset_m + in.radius_m) + " > disc_radius_m = " +
                                 format_number(m.disc_radius_m) + ")");
  }
  if (!(in.validated_turn_deg[0] >= -180.0 && in.validated_turn_deg[0] <= 0.0 && in.validated_turn_deg[1] >= 0.0 &&
        in.validated_turn_deg[1] <= 180.0)) {
    c.fail("inlet.validated_turn_deg", "must be [low, high] degrees with -180 <= low <= 0 <= high <= 180, got [" +
                                           format_number(in.validated_turn_deg[0]) + ", " +
                                           format_number(in.validated_turn_deg[1]) + "]");
  }

  if (scene.materials.empty()) c.fail("materials", "at least one [[materials]] entry is required");
  std::set<std::string> names;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& mat = scene.materials[i];
    const std::string p = "materials[" + std::to_string(i) + "].";
    if (mat.name.empty()) c.fail(p + "name", "must be given and not empty");
    if (!names.insert(mat.name).second) c.fail(p + "name", "duplicate material name \"" + mat.name + "\"");
    if (!mat.is_blend()) check_quantities(scene, p, mat);
    for (std::size_t j = 0; j < mat.components.size(); ++j)
      check_quantities(scene, p + "components[" + std::to_string(j) + "].", mat.components[j].material);
  }
  check_section(scene, "air", scene.air, kAirKeys);
  if (scene.simulate_material.empty()) {
    scene.simulate_material = scene.materials.front().name;
  } else if (scene.find_material(scene.simulate_material) == nullptr) {
    c.fail("simulate.material", "no material named \"" + scene.simulate_material + "\"");
  }

  Numerics& n = scene.numerics;
  check_section(scene, "numerics", n, kNumericsKeys);
  // 0 = the rim.
  if (n.collector_radius_m == 0.0) n.collector_radius_m = m.disc_radius_m;
  if (n.collector_radius_m < m.disc_radius_m) {
    c.fail("numerics.collector_radius_m", "must be >= disc_radius_m = " + format_number(m.disc_radius_m) + ", got " +
                                              format_number(n.collector_radius_m));
  }

  Sweep& sw = scene.sweep;
  check_section(scene, "sweep", sw, kSweepKeys);
  std::set<double> seen_rpm;
  for (std::size_t i = 0; i < sw.rpm.size(); ++i) {
    if (!seen_rpm.insert(sw.rpm[i]).second) c.fail("sweep.rpm[" + std::to_string(i) + "]", "duplicate rpm " + format_number(sw.rpm[i]));
  }
  std::set<std::string> seen_material;
  for (std::size_t i = 0; i < sw.materials.size(); ++i) {
    const std::string key = "sweep.materials[" + std::to_string(i) + "]";
    if (scene.find_material(sw.materials[i]) == nullptr) c.fail(key, "no material named \"" + sw.materials[i] + "\"");
    if (!seen_material.insert(sw.materials[i]).second) c.fail(key, "material \"" + sw.materials[i] + "\" listed twice");
  }
  if (sw.output.empty()) c.fail("sweep.output", "must not be empty");
  check_section(scene, "outputs", scene.outputs, kOutputsKeys);
  if (scene.outputs.directory.empty()) c.fail("outputs.directory", "must not be empty");
  const FieldRun& f = scene.field;
  check_section(scene, "field", f, kFieldKeys);
  if (!f.material.empty() && scene.find_material(f.material) == nullptr) {
    c.fail("field.material", "no material named \"" + f.material + "\"");
  }
  if (!f.track.empty() && f.boundary.empty()) c.fail("field.track", "a track is driven in a field: give field.boundary too");
}

}  // namespace

Scene parse_scene(const std::string& toml_text, const std::string& source_name,
                  const std::vector<std::string>& overrides) {
  Scene scene;
  scene.source_name = source_name;
  scene.text = toml_text;
  scene.overrides = overrides;
  const TomlDocument doc(toml_text, source_name, overrides);
  doc.check_top_level_keys(
      {"machine", "inlet", "products", "materials", "simulate", "air", "effects", "numerics", "sweep", "outputs", "field"});
  read_section(doc, "machine", scene.machine, kMachineKeys);
  read_section(doc, "inlet", scene.inlet, kInletKeys);
  read_section(doc, "products", scene.products, kProductsKeys);
  read_materials(doc, scene);
  read_section(doc, "simulate", scene, kSimulateKeys);
  read_section(doc, "air", scene.air, kAirKeys);
  read_effects(doc, scene);
  read_section(doc, "numerics", scene.numerics, kNumericsKeys);
  read_section(doc, "sweep", scene.sweep, kSweepKeys);
  check_sweep_source_keys(doc, scene);
  read_section(doc, "outputs", scene.outputs, kOutputsKeys);
  read_section(doc, "field", scene.field, kFieldKeys);
  validate(scene);
  return scene;
}

Scene load_scene_file(const std::string& path, const std::vector<std::string>& overrides) {
  Scene scene = parse_scene(read_scene_text(path), path, overrides);
  // A disc STL named relative to the scene travels with it: resolve against the scene file's directory.
  std::string& stl = scene.machine.stl_path;
  if (!stl.empty() && std::filesystem::path(stl).is_relative())
    stl = (std::filesystem::path(path).parent_path() / stl).lexically_normal().string();
  // The field's files travel with the scene as the disc's does; their content is checked where it is read.
  for (std::string* field_file : {&scene.field.boundary, &scene.field.track}) {
    if (!field_file->empty() && std::filesystem::path(*field_file).is_relative()) {
      *field_file = (std::filesystem::path(path).parent_path() / *field_file).lexically_normal().string();
    }
  }
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
