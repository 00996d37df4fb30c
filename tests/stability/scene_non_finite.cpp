// NaN and Inf in any scene value: every numeric key of every shipped scene (scenes/*.toml, the drum's
// too: it reads through the same TOML document), found by walking the TOML tree — so a key added to a
// scene later is covered without editing this test — set to nan, inf and -inf, both in the file text and
// as a --set override. Each must be refused with a SceneError that names the key (for arrays: the
// array's key).
#include <gtest/gtest.h>

#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "libspread/physics/drum/drum_scene.hpp"
#include "libspread/io/scene/scene.hpp"

namespace spread::scene {
namespace {

struct NumericKey {
  std::string override_key;  // dotted, array indices as segments: "materials.0.density_kg_m3"
  std::string message_key;   // as the parser names it: "materials[0].density_kg_m3", "air.wind_m_s"
  std::vector<std::string> path;  // segments, for editing the tree
};

void collect(const toml::node& node, const std::string& override_key, const std::string& message_key,
             std::vector<std::string>& path, std::vector<NumericKey>& out) {
  if (const toml::table* table = node.as_table()) {
    for (auto&& [key, child] : *table) {
      const std::string k(key.str());
      path.push_back(k);
      collect(child, override_key.empty() ? k : override_key + "." + k, message_key.empty() ? k : message_key + "." + k,
              path, out);
      path.pop_back();
    }
  } else if (const toml::array* array = node.as_array()) {
    for (std::size_t i = 0; i < array->size(); ++i) {
      const toml::node& element = *array->get(i);
      path.push_back(std::to_string(i));
      // Tables in arrays are named with brackets; numbers in arrays by the array's key alone.
      const std::string element_message = element.is_table() ? message_key + "[" + std::to_string(i) + "]" : message_key;
      collect(element, override_key + "." + std::to_string(i), element_message, path, out);
      path.pop_back();
    }
  } else if (node.is_number()) {
    out.push_back({override_key, message_key, path});
  }
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Reads a scene the way its program does: a scene with a [drum] table is the drum's.
using Reader = void (*)(const std::string& text, const std::string& source, const std::vector<std::string>& overrides);
void read_spreader_scene(const std::string& text, const std::string& source, const std::vector<std::string>& overrides) {
  (void)parse_scene(text, source, overrides);
}
void read_drum_scene(const std::string& text, const std::string& source, const std::vector<std::string>& overrides) {
  (void)drum::parse_drum_scene(text, source, overrides);
}

struct ShippedScene {
  std::filesystem::path path;
  Reader read;
  bool operator<(const ShippedScene& other) const { return path < other.path; }
};

std::vector<ShippedScene> shipped_scenes() {
  std::vector<ShippedScene> scenes;
  for (const auto& entry : std::filesystem::directory_iterator(SPREAD_SOURCE_DIR "/scenes")) {
    if (entry.path().extension() != ".toml") continue;
    const toml::table root = toml::parse_file(entry.path().string());
    // A product library (scenes/products.toml) is not a scene: a scene takes its entries as materials,
    // and tests/scene/test_product_library.cpp checks each makes a valid one.
    if (root.contains("products") && !root.contains("machine")) continue;
    const bool drum = root.contains("drum");
    scenes.push_back({entry.path(), drum ? read_drum_scene : read_spreader_scene});
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

// The tree with the value at `path` replaced by `bad`.
toml::table with_value(toml::table root, const std::vector<std::string>& path, double bad) {
  toml::node* node = &root;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    if (toml::table* t = node->as_table()) {
      node = t->get(path[i]);
    } else {
      node = node->as_array()->get(std::stoul(path[i]));
    }
  }
  if (toml::table* t = node->as_table()) {
    t->insert_or_assign(path.back(), bad);
  } else {
    toml::array& a = *node->as_array();
    a.replace(a.cbegin() + static_cast<std::ptrdiff_t>(std::stoul(path.back())), bad);
  }
  return root;
}

// `name`: the scene file's path, so that the files it names (a product library) are found beside it.
void expect_refused(Reader read, const std::string& text, const std::string& name,
                    const std::vector<std::string>& overrides, const NumericKey& key, const std::string& how) {
  try {
    read(text, name, overrides);
    ADD_FAILURE() << key.override_key << " = " << how << " was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(key.message_key), std::string::npos)
        << how << ": the message does not name " << key.message_key << ": " << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << key.override_key << " = " << how << ": not a SceneError: " << e.what();
  }
}

TEST(SceneNonFinite, EveryNumericKeyOfEveryShippedSceneRefusesNanAndInf) {
  const std::vector<ShippedScene> scenes = shipped_scenes();
  ASSERT_FALSE(scenes.empty());
  std::size_t checked = 0;
  for (const auto& [file, read] : scenes) {
    SCOPED_TRACE(file.string());
    const std::string text = read_file(file);
    ASSERT_NO_THROW(read(text, file.string(), {})) << "the shipped scene itself must parse";
    const toml::table root = toml::parse(text);
    std::vector<NumericKey> keys;
    std::vector<std::string> path;
    collect(root, "", "", path, keys);
    ASSERT_GT(keys.size(), 15u) << "the walk found too few numeric keys";
    for (const NumericKey& key : keys) {
      for (const char* literal : {"nan", "inf", "-inf", "+inf", "-nan"}) {
        expect_refused(read, text, file.string(), {key.override_key + "=" + literal}, key, std::string("--set ") + literal);
        ++checked;
      }
      for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity()}) {
        std::ostringstream edited;
        edited << with_value(root, key.path, bad);
        expect_refused(read, edited.str(), file.string(), {}, key, "in the file: " + std::to_string(bad));
        ++checked;
      }
    }
  }
  RecordProperty("cases", static_cast<int>(checked));
}

// Values that are finite but overflow to Inf once derived (rpm → ω, huge diameters → volumes) and
// numbers TOML cannot hold exactly: refused or accepted, never a crash or a NaN in the scene.
TEST(SceneNonFinite, HugeFiniteValuesNeverBecomeNonFinite) {
  const std::string text = read_file(SPREAD_SOURCE_DIR "/scenes/default.toml");
  for (const char* assignment : {"machine.rpm=1e308", "materials.0.diameter_mean_m=1e300", "inlet.mass_flow_kg_s=1e308",
                                 "numerics.duration_s=1e308", "air.wind_m_s=[1e308, -1e308]", "machine.rpm=5e-324",
                                 "numerics.seed=9223372036854775807", "sweep.rpm=[1e308]"}) {
    SCOPED_TRACE(assignment);
    try {
      const Scene s = parse_scene(text, "scene.toml", {assignment});
      EXPECT_TRUE(std::isfinite(s.machine.rpm));
      EXPECT_TRUE(std::isfinite(s.materials.at(0).diameter_mean_m));
      EXPECT_TRUE(std::isfinite(s.air.wind_m_s[0]));
    } catch (const SceneError&) {
    }
  }
}

}  // namespace
}  // namespace spread::scene
