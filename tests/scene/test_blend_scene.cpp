// A blend in a scene: a [[materials]] entry with components, each a library product or a material of its
// own, with mass fractions summing to 1 and optional nutrient contents; every mistake an error naming the
// key; the components' values and fractions are the run's inputs, their nutrients are not.
#include <gtest/gtest.h>

#include <string>

#include "libspread/io/scene/scene.hpp"

namespace spread::scene {
namespace {

const std::string kLibrary = std::string(SPREAD_SOURCE_DIR) + "/scenes/products.toml";

std::string blend_scene(const std::string& components) {
  return "[products]\nfile = \"" + kLibrary + "\"\n[[materials]]\nname = \"NPK blend\"\n" + components;
}

const std::string kThree = R"toml(
[[materials.components]]
product = "Urea, granular"
mass_fraction = 0.3
n_pct = 46
[[materials.components]]
product = "DAP, granular"
mass_fraction = 0.35
n_pct = 18
p2o5_pct = 46
[[materials.components]]
name = "potash of my own"
density_kg_m3 = 1937
friction_wall = 0.6
mass_fraction = 0.35
k2o_pct = 60
)toml";

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "scene.toml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

TEST(BlendScene, ComponentsFromProductsAndOwnDefinitions) {
  const Scene s = parse_scene(blend_scene(kThree), "scene.toml");
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& blend = s.materials[0];
  ASSERT_TRUE(blend.is_blend());
  ASSERT_EQ(blend.components.size(), 3u);
  EXPECT_EQ(blend.components[0].material.name, "Urea, granular");
  EXPECT_EQ(blend.components[0].material.density_kg_m3, 1257);
  EXPECT_FALSE(blend.components[0].material.sieve.empty());  // the product's sieve analysis
  EXPECT_EQ(blend.components[1].material.density_kg_m3, 1606);
  EXPECT_EQ(blend.components[1].p2o5_pct, 46);
  EXPECT_EQ(blend.components[2].material.name, "potash of my own");
  EXPECT_EQ(blend.components[2].material.diameter_mean_m, 3.2e-3);  // the schema's default
  EXPECT_EQ(blend.components[2].k2o_pct, 60);
  EXPECT_EQ(blend.components[2].n_pct, 0);
  EXPECT_EQ(s.product_notes.size(), 2u);
  EXPECT_EQ(s.product_notes[1].rfind("# materials[0].components[1] = product \"DAP, granular\"", 0), 0u) << s.product_notes[1];
}

TEST(BlendScene, MistakesNameTheKey) {
  std::string bad = kThree;
  bad.replace(bad.find("mass_fraction = 0.3\n"), 20, "mass_fraction = 0.2\n");
  EXPECT_NE(error_of(blend_scene(bad)).find("materials[0].components: the mass fractions must sum to 1"), std::string::npos)
      << error_of(blend_scene(bad));
  bad = kThree;
  bad.replace(bad.find("mass_fraction = 0.3\n"), 20, "mass_fraction = -0.3\n");
  EXPECT_NE(error_of(blend_scene(bad)).find("materials[0].components[0].mass_fraction: must be in (0, 1]"), std::string::npos)
      << error_of(blend_scene(bad));
  bad = kThree;
  bad.replace(bad.find("k2o_pct = 60"), 12, "k2o_pct = 160");
  EXPECT_NE(error_of(blend_scene(bad)).find("materials[0].components[2].k2o_pct: must be in [0, 100]"), std::string::npos)
      << error_of(blend_scene(bad));
  bad = kThree;
  bad.replace(bad.find("mass_fraction = 0.35\nk2o"), 21, "k2o");
  EXPECT_NE(error_of(blend_scene(bad)).find("materials[0].components[2].mass_fraction: missing"), std::string::npos)
      << error_of(blend_scene(bad));
  bad = kThree;
  bad.replace(bad.find("density_kg_m3 = 1937"), 20, "density_kg_m3 = -1");
  EXPECT_NE(error_of(blend_scene(bad)).find("materials[0].components[2].density_kg_m3"), std::string::npos)
      << error_of(blend_scene(bad));
  EXPECT_NE(error_of(blend_scene("density_kg_m3 = 1500\n" + kThree)).find("materials[0].density_kg_m3: a blend's quantities are its components'"),
            std::string::npos);
  EXPECT_NE(error_of(blend_scene("components = []\n")).find("materials[0].components: a blend needs at least one component"),
            std::string::npos);
  bad = kThree;
  bad.replace(bad.find("product = \"DAP, granular\""), 25, "product = \"Urea, granular\"");
  EXPECT_NE(error_of(blend_scene(bad)).find("components[1].name: component \"Urea, granular\" listed twice"), std::string::npos)
      << error_of(blend_scene(bad));
  bad = kThree;
  bad.replace(bad.find("n_pct = 46\n"), 11, "n_pct = 46\ncolour = 1\n");
  EXPECT_NE(error_of(blend_scene(bad)).find("materials[0].components[0].colour: unknown key"), std::string::npos)
      << error_of(blend_scene(bad));
}

// A component's values and fraction change the run's inputs; its nutrients do not (they change no launch).
TEST(BlendScene, RunInputsAreTheComponentsAndFractions) {
  const Scene s = parse_scene(blend_scene(kThree), "scene.toml");
  const std::string text = s.run_inputs_text(s.materials[0], 600);
  EXPECT_NE(text.find("material.components[1].density_kg_m3 = 1606\n"), std::string::npos) << text;
  EXPECT_NE(text.find("material.components[2].mass_fraction = 0.34999999999999998\n"), std::string::npos) << text;
  std::string nutrients = kThree;
  nutrients.replace(nutrients.find("n_pct = 46"), 10, "n_pct = 45");
  const Scene other_nutrients = parse_scene(blend_scene(nutrients), "scene.toml");
  EXPECT_EQ(other_nutrients.run_inputs_hash(other_nutrients.materials[0], 600), s.run_inputs_hash(s.materials[0], 600));
  std::string fractions = kThree;
  fractions.replace(fractions.find("mass_fraction = 0.3\n"), 20, "mass_fraction = 0.29\n");
  fractions.replace(fractions.find("mass_fraction = 0.35\nn_pct"), 20, "mass_fraction = 0.36");
  const Scene other_fractions = parse_scene(blend_scene(fractions), "scene.toml");
  EXPECT_NE(other_fractions.run_inputs_hash(other_fractions.materials[0], 600), s.run_inputs_hash(s.materials[0], 600));
}

}  // namespace
}  // namespace spread::scene
