#pragma once
// A product library file: `[[products]]` entries, each with the keys of a `[[materials]]` entry (name,
// density, friction, sizes as a lognormal or a sieve analysis; docs/products.md, scenes/products.toml).
// A scene names it in `[products] file` and a material entry takes a product by `product = "NAME"`.
#include <string>
#include <vector>

#include "libspread/io/scene/scene.hpp"

namespace spread::scene {

// The file's path as the scene names it: relative paths from the scene file's directory (the directory
// of `scene_source`, the scene's file name; the working directory for a scene without one).
std::string product_library_path(const std::string& scene_source, const std::string& file);

// The products of the library, in file order; SceneError "<path>: products[i].<key>: …" for a bad entry,
// "<path>: cannot open the scene file" when missing. Ranges are the scene's (checked where a material
// takes the product).
std::vector<Material> read_product_library(const std::string& path);

// "# ENTRY = product "NAME" of FILE: key = value, …": what the product gave, for the provenance. ENTRY is
// the scene entry that took it: "materials[i]", or "materials[i].components[j]" for a blend's component.
std::string product_note(const std::string& entry, const Material& product, const std::string& file);

}  // namespace spread::scene
