// The product library (scenes/products.toml): every product makes a valid material, a scene takes one by
// name and its own keys replace the product's, the provenance records what the product gave, and the
// mistakes are errors naming the key.
#include <gtest/gtest.h>

#include <cmath>

#include "libspread/core/sieve_analysis.hpp"
#include "libspread/io/scene/product_library.hpp"
#include "libspread/io/scene/scene.hpp"

namespace spread::scene {
namespace {

const std::string kLibrary = std::string(SPREAD_SOURCE_DIR) + "/scenes/products.toml";

std::string scene_with(const std::string& materials) {
  return "[products]\nfile = \"" + kLibrary + "\"\n" + materials;
}

// Each product as a scene's material passes the scene's checks (ranges, sizes), and the library holds
// the seed paper's nine Table 2 materials with their densities.
TEST(ProductLibrary, EveryProductIsAValidMaterial) {
  const std::vector<Material> products = read_product_library(kLibrary);
  std::string text;
  for (const Material& p : products) text += "[[materials]]\nproduct = \"" + p.name + "\"\n";
  const Scene s = parse_scene(scene_with(text), "scene.toml");
  ASSERT_EQ(s.materials.size(), products.size());
  const std::pair<const char*, double> table2[] = {{"AMS standard", 1819}, {"Kmag", 2542}, {"Coarse potash", 1910},
                                                   {"Limestone filler", 2604}, {"Triple 0-46-0", 1834},
                                                   {"Muriate of potash", 1937}, {"Urea", 1257}, {"DAP", 1606},
                                                   {"Pell lime", 2105}};
  for (const auto& [name, density] : table2) {
    const Material* m = s.find_material(name);
    ASSERT_NE(m, nullptr) << name;
    EXPECT_EQ(m->density_kg_m3, density) << name;
  }
  // The figures docs/products.md gives for the granular urea at its specification's limits.
  const Material* urea = s.find_material("Urea, granular");
  ASSERT_NE(urea, nullptr);
  EXPECT_EQ(std::lround(size_guide_number(urea->sieve)), 303);
  EXPECT_EQ(std::lround(uniformity_index(urea->sieve)), 52);
}

TEST(ProductLibrary, TheEntrysOwnKeysReplaceTheProducts) {
  const Scene s = parse_scene(scene_with(R"toml(
[[materials]]
product = "Urea, granular"
name = "my urea"
friction_wall = 0.3
[[materials]]
product = "Urea, granular"
name = "urea as a lognormal"
diameter_mean_m = 3e-3
)toml"),
                              "scene.toml");
  const Material& own = s.materials[0];
  EXPECT_EQ(own.name, "my urea");
  EXPECT_EQ(own.friction_wall, 0.3);
  EXPECT_EQ(own.friction_particle, 0.4);  // the product's
  EXPECT_EQ(own.density_kg_m3, 1257);
  EXPECT_FALSE(own.sieve.empty());
  // A size key replaces the product's sizes as a whole: no sieve, the schema's sd.
  const Material& lognormal = s.materials[1];
  EXPECT_TRUE(lognormal.sieve.empty());
  EXPECT_EQ(lognormal.diameter_mean_m, 3e-3);
  EXPECT_EQ(lognormal.diameter_sd_m, 0.6e-3);
  // The provenance says what each product gave, after the scene's text.
  ASSERT_EQ(s.product_notes.size(), 2u);
  EXPECT_EQ(s.product_notes[0].rfind("# materials[0] = product \"Urea, granular\" of " + kLibrary + ": density_kg_m3 = 1257;", 0), 0u)
      << s.product_notes[0];
  EXPECT_NE(s.provenance_text().find("sieve_retained_pct = [3, 37, 53, 7];"), std::string::npos);
}

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "scene.toml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(ProductLibrary, MistakesNameTheKey) {
  EXPECT_NE(error_of(scene_with("[[materials]]\nproduct = \"Urea, pearl\"\n"))
                .find("scene.toml: materials[0].product: no product \"Urea, pearl\" in " + kLibrary + " (products: \"AMS standard\""),
            std::string::npos);
  EXPECT_NE(error_of("[[materials]]\nproduct = \"Urea\"\n").find("materials[0].product: names a product, but the scene names no library"),
            std::string::npos);
  EXPECT_NE(error_of("[products]\nfile = \"no-such-library.toml\"\n[[materials]]\nproduct = \"Urea\"\n").find("scene.toml: products.file: no such library file: no-such-library.toml"),
            std::string::npos);
  // A product's lognormal size key beside the entry's sieve: the entry's sizes stand alone, so a sieve
  // with a lognormal key in the same entry is still refused.
  EXPECT_NE(error_of(scene_with("[[materials]]\nproduct = \"Urea\"\nsieve_mm = [1, 2]\nsieve_retained_pct = [100]\ndiameter_sd_m = 1e-3\n"))
                .find("materials[0].diameter_sd_m: is a lognormal size"),
            std::string::npos);
}

}  // namespace
}  // namespace spread::scene
