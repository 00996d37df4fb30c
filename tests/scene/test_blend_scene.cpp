// A blend in a scene: a [[materials]] entry with components, each a library product or a material of its
// own, with mass fractions summing to 1 and optional nutrient contents; every mistake an error naming the
// key; the components' values and fractions are the run's inputs, their nutrients are not.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <utility>

#include "libspread/io/scene/scene.hpp"
#include "tests/support/error_message.hpp"

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

// The error parsing the three-component blend with `from` replaced by `to` (once) gives ("" when none).
std::string error_with(const std::string& from, const std::string& to, const std::string& before = "") {
  std::string text = kThree;
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return spread::testing::error_of([&] { parse_scene(blend_scene(before + text), "scene.toml"); });
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
  const std::pair<std::array<std::string, 2>, std::string> cases[] = {
      {{"mass_fraction = 0.3\n", "mass_fraction = 0.2\n"}, "materials[0].components: the mass fractions must sum to 1"},
      {{"mass_fraction = 0.3\n", "mass_fraction = -0.3\n"}, "materials[0].components[0].mass_fraction: must be in (0, 1]"},
      {{"k2o_pct = 60", "k2o_pct = 160"}, "materials[0].components[2].k2o_pct: must be in [0, 100]"},
      {{"mass_fraction = 0.35\nk2o", "k2o"}, "materials[0].components[2].mass_fraction: missing"},
      {{"density_kg_m3 = 1937", "density_kg_m3 = -1"}, "materials[0].components[2].density_kg_m3"},
      {{"product = \"DAP, granular\"", "product = \"Urea, granular\""}, "components[1].name: component \"Urea, granular\" listed twice"},
      {{"n_pct = 46\n", "n_pct = 46\ncolour = 1\n"}, "materials[0].components[0].colour: unknown key"},
  };
  for (const auto& [edit, expected] : cases) {
    const std::string message = error_with(edit[0], edit[1]);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
  EXPECT_NE(error_with("", "", "density_kg_m3 = 1500\n").find("materials[0].density_kg_m3: a blend's quantities are its components'"),
            std::string::npos);
  const std::string empty = spread::testing::error_of([] { parse_scene(blend_scene("components = []\n"), "scene.toml"); });
  EXPECT_NE(empty.find("materials[0].components: a blend needs at least one component"), std::string::npos) << empty;
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
