// A table run's inputs (Scene::run_inputs_text) are what the key rows say they are: each key changed on its
// own changes the text exactly when its row makes it an input of that run's source, and a key of any type
// the rows hold can be one.
#include <gtest/gtest.h>

#include <string>
#include <type_traits>
#include <variant>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/scene/scene_keys.hpp"

namespace spread::scene {
namespace {

// The owner's value of `key` changed to another one of its type (ranges do not matter to the text).
template <typename Owner>
void change(Owner& owner, const Key<Owner>& key) {
  std::visit(
      [&](const auto& field) {
        using F = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<F, Choice<Owner>>) {
          const int now = field.get(owner);
          for (const ChoiceName& n : field.names) {
            if (n.value != now) {
              field.set(owner, n.value);
              return;
            }
          }
          ADD_FAILURE() << key.name << ": a choice of one value";
        } else if constexpr (std::is_same_v<F, std::array<double, 2> Owner::*>) {
          (owner.*field)[1] += 0.25;
        } else if constexpr (std::is_same_v<F, std::vector<double> Owner::*> ||
                             std::is_same_v<F, std::vector<std::string> Owner::*>) {
          (owner.*field).emplace_back();
        } else if constexpr (std::is_same_v<F, bool Owner::*>) {
          owner.*field = !(owner.*field);
        } else if constexpr (std::is_same_v<F, std::string Owner::*>) {
          owner.*field += "x";
        } else {
          owner.*field += 1;
        }
      },
      key.field);
}

// For every row of `keys`: change the key alone in `scene` (its member `owner`) and compare the texts.
template <typename Owner, std::size_t kCount>
void expect_inputs_follow_rows(const Scene& base, Owner Scene::* owner, const std::array<Key<Owner>, kCount>& keys,
                               const char* section) {
  for (const LaunchSource source : {LaunchSource::kDem, LaunchSource::kAnalytic}) {
    Scene scene = base;
    scene.sweep.source = source;
    const Material& material = scene.materials.at(0);
    const std::string before = scene.run_inputs_text(material, 600.0);
    for (const Key<Owner>& key : keys) {
      Scene changed = scene;
      change(changed.*owner, key);
      if (std::string(section) == "sweep" && key.name == "source") continue;  // the source is the loop's
      const RunInput own = source == LaunchSource::kDem ? RunInput::kDem : RunInput::kAnalytic;
      const bool input = (key.run_input == RunInput::kAlways || key.run_input == own) &&
                         (key.input_when == nullptr || key.input_when(scene.*owner));
      const std::string after = changed.run_inputs_text(changed.materials.at(0), 600.0);
      EXPECT_EQ(after != before, input) << section << "." << key.name << " ("
                                        << (source == LaunchSource::kDem ? "dem" : "analytic") << " run)";
      if (input) {
        EXPECT_NE(after.find(std::string(section) + "." + std::string(key.name)), std::string::npos) << key.name;
      }
    }
  }
}

TEST(SceneInputs, EachKeyIsAnInputExactlyWhenItsRowSays) {
  const Scene scene = load_scene_file(std::string(SPREAD_SOURCE_DIR) + "/scenes/default.toml");
  expect_inputs_follow_rows(scene, &Scene::machine, kMachineKeys, "machine");
  expect_inputs_follow_rows(scene, &Scene::inlet, kInletKeys, "inlet");
  expect_inputs_follow_rows(scene, &Scene::air, kAirKeys, "air");
  expect_inputs_follow_rows(scene, &Scene::numerics, kNumericsKeys, "numerics");
  expect_inputs_follow_rows(scene, &Scene::sweep, kSweepKeys, "sweep");
  expect_inputs_follow_rows(scene, &Scene::outputs, kOutputsKeys, "outputs");
  // A key with a condition: the mesh size is an input of a meshed disc only.
  Scene meshed = scene;
  meshed.machine.disc_model = DiscModel::kMesh;
  expect_inputs_follow_rows(meshed, &Scene::machine, kMachineKeys, "machine");
  EXPECT_NE(meshed.run_inputs_text(meshed.materials.at(0), 600.0).find("machine.mesh_size_m"), std::string::npos);
  EXPECT_EQ(scene.run_inputs_text(scene.materials.at(0), 600.0).find("machine.mesh_size_m"), std::string::npos);
}

// The canonical text of the bundled scene, line for line: it is hashed into every table's runs, and a
// change here makes lookup_builder rebuild tables rather than extend them (docs/table-format.md).
TEST(SceneInputs, TheCanonicalTextKeepsItsForm) {
  Scene scene = load_scene_file(std::string(SPREAD_SOURCE_DIR) + "/scenes/default.toml");
  const std::string text = scene.run_inputs_text(scene.materials.at(0), 555.5);
  EXPECT_EQ(text.substr(0, text.find('\n') + 1), "machine.name = \"case1-twin\"\n");
  EXPECT_NE(text.find("\nmachine.disc_radius_m = 0.28999999999999998\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\ninlet.mass_flow_kg_s = 0.11\nmaterial.name = \"AMS standard\"\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nrpm = 555.5\nair.density_kg_m3 = "), std::string::npos) << text;
  EXPECT_NE(text.find("\nair.wind_m_s[0] = 0\nair.wind_m_s[1] = 0\neffects = "), std::string::npos) << text;
  EXPECT_NE(text.find("\nnumerics.seed = "), std::string::npos) << text;
  EXPECT_NE(text.find("\nsweep.source = \"dem\"\nsweep.samples_per_run = "), std::string::npos) << text;
  EXPECT_NE(text.find("\nnumerics.contact_model = \"hertz_thornton\"\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("threads"), std::string::npos) << text;
  EXPECT_EQ(text.find("outputs."), std::string::npos) << text;
  EXPECT_EQ(scene.run_inputs_hash(scene.materials.at(0), 555.5).size(), 16u);
}

}  // namespace
}  // namespace spread::scene
