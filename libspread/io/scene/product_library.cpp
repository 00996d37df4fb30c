#include "libspread/io/scene/product_library.hpp"

#include <filesystem>
#include <set>

#include "libspread/io/scene/material_entry.hpp"
#include "libspread/io/scene/scene_key.hpp"
#include "libspread/io/scene/toml_document.hpp"
#include "libspread/io/tables/material_schema.hpp"

namespace spread::scene {

std::string product_library_path(const std::string& scene_source, const std::string& file) {
  const std::filesystem::path p(file);
  if (p.is_absolute()) return file;
  return (std::filesystem::path(scene_source).parent_path() / p).lexically_normal().string();
}

std::vector<Material> read_product_library(const std::string& path) {
  // A regular file only: a FIFO or device named here must not block or fill memory.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw SceneError(path + ": products: no such library file");
  const TomlDocument doc(read_scene_text(path), path, {});
  doc.check_top_level_keys({"products"});
  std::vector<Material> products;
  std::set<std::string> names;
  for (TomlSection& s : doc.array_of_tables("products")) {
    Material m = read_material_entry(s, nullptr);
    s.finish();
    if (m.name.empty()) s.fail("name", "must be given and not empty");
    if (!names.insert(m.name).second) s.fail("name", "duplicate product name \"" + m.name + "\"");
    products.push_back(std::move(m));
  }
  if (products.empty()) throw SceneError(path + ": products: the library holds no [[products]] entry");
  return products;
}

std::string product_note(const std::string& entry, const Material& product, const std::string& file) {
  std::string note = "# " + entry + " = product \"" + product.name + "\" of " + file + ":";
  for (const tables::MaterialQuantity& q : tables::kMaterialQuantities)
    note += " " + std::string(q.name) + " = " + format_number(product.*q.member) + ";";
  for (const tables::MaterialList& list : tables::kMaterialSieveLists) {
    const std::vector<double>& values = product.sieve.*list.member;
    if (values.empty()) continue;
    note += " " + std::string(list.name) + " = [";
    for (std::size_t i = 0; i < values.size(); ++i) note += (i ? ", " : "") + format_number(values[i]);
    note += "];";
  }
  return note;
}

}  // namespace spread::scene
