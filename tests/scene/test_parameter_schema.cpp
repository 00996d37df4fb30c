// The material schema is the one list of material quantities: the docs, the scene reader and the
// table file's columns follow it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/scene/scene_keys.hpp"
#include "libspread/io/tables/material_schema.hpp"
#include "libspread/io/tables/table_schema.hpp"
#include "tests/support/source_file.hpp"

namespace spread::tables {
namespace {

// The cells of the doc row whose first cell is `key` (empty when there is none).
std::vector<std::string> doc_row(const std::string& doc, const std::string& key) {
  const std::string start = "\n| `" + key + "` |";
  const std::size_t at = doc.find(start);
  if (at == std::string::npos) return {};
  const std::string line = doc.substr(at + 2, doc.find('\n', at + 1) - at - 2);
  std::vector<std::string> cells;
  std::stringstream parts(line);
  for (std::string cell; std::getline(parts, cell, '|');) {
    const std::size_t b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
    if (b != std::string::npos) cells.push_back(cell.substr(b, e - b + 1));
  }
  return cells;
}

TEST(ParameterSchema, DocsListEveryMaterialQuantity) {
  const std::string doc = spread::testing::read_source_file("docs/scene-format.md");
  ASSERT_FALSE(doc.empty());
  std::size_t previous = 0;
  for (const MaterialQuantity& q : kMaterialQuantities) {
    const std::string key(q.name);
    const std::vector<std::string> cells = doc_row(doc, key);
    ASSERT_EQ(cells.size(), 4u) << key << ": no row | `key` | unit | default | meaning | in docs/scene-format.md";
    EXPECT_EQ(cells[1], q.unit) << key;
    if (std::isnan(q.scene_default)) {
      EXPECT_EQ(cells[2], "(required)") << key;
    } else {
      EXPECT_EQ(std::strtod(cells[2].c_str(), nullptr), q.scene_default) << key << ": the doc says " << cells[2];
    }
    EXPECT_EQ(cells[3].rfind(std::string(q.meaning), 0), 0u) << key << ": the doc's meaning should start with \"" << q.meaning << "\"";
    const std::size_t at = doc.find("\n| `" + key + "` |");
    EXPECT_GT(at, previous) << key << ": rows out of the schema's order";
    previous = at;
  }
}

// The sieve lists follow the quantities in the same table: unit, no default (given together or not at
// all), meaning.
TEST(ParameterSchema, DocsListTheSieveLists) {
  const std::string doc = spread::testing::read_source_file("docs/scene-format.md");
  std::size_t previous = doc.find("\n| `" + std::string(kMaterialQuantities.back().name) + "` |");
  ASSERT_NE(previous, std::string::npos);
  for (const MaterialList& list : kMaterialSieveLists) {
    const std::string key(list.name);
    const std::vector<std::string> cells = doc_row(doc, key);
    ASSERT_EQ(cells.size(), 4u) << key << ": no row | `key` | unit | default | meaning | in docs/scene-format.md";
    EXPECT_EQ(cells[1], list.unit) << key;
    EXPECT_EQ(cells[2], "(none)") << key;
    EXPECT_EQ(cells[3].rfind(std::string(list.meaning), 0), 0u) << key << ": the doc's meaning should start with \"" << list.meaning << "\"";
    const std::size_t at = doc.find("\n| `" + key + "` |");
    EXPECT_GT(at, previous) << key << ": rows out of the schema's order";
    previous = at;
  }
}

// The text of the section headed `heading` (up to the next "## " heading); empty when there is none.
std::string doc_section(const std::string& doc, const std::string& heading) {
  const std::size_t at = doc.find("\n## " + heading);
  if (at == std::string::npos) return {};
  const std::size_t end = doc.find("\n## ", at + 1);
  return doc.substr(at, end == std::string::npos ? std::string::npos : end - at) + "\n";
}

std::string without_backticks(std::string text) {
  std::erase(text, '`');
  return text;
}

// Each key row of `keys` appears in the section, in the rows' order, with its unit, its default (the
// owner's default-constructed value) and a meaning that starts with the row's.
template <typename Owner, std::size_t N>
void expect_doc_rows(const std::string& doc, const std::string& heading, const std::array<scene::Key<Owner>, N>& keys) {
  const std::string section = doc_section(doc, heading);
  ASSERT_FALSE(section.empty()) << "no section " << heading << " in docs/scene-format.md";
  std::size_t previous = 0;
  for (const scene::Key<Owner>& k : keys) {
    const std::string key(k.name);
    const std::vector<std::string> cells = doc_row(section, key);
    ASSERT_EQ(cells.size(), 4u) << heading << " " << key << ": no row | `key` | unit | default | meaning |";
    EXPECT_EQ(cells[1], k.unit) << heading << " " << key;
    const std::string documented = without_backticks(cells[2]);
    const std::string actual = scene::default_text(k);
    const bool numeric = std::holds_alternative<double Owner::*>(k.field) ||
                         std::holds_alternative<int Owner::*>(k.field) ||
                         std::holds_alternative<std::uint64_t Owner::*>(k.field);
    if (numeric) {
      EXPECT_EQ(std::strtod(documented.c_str(), nullptr), std::strtod(actual.c_str(), nullptr))
          << heading << " " << key << ": the doc says " << cells[2] << ", the reader " << actual;
    } else {
      EXPECT_EQ(documented.rfind(actual, 0), 0u) << heading << " " << key << ": the doc says " << cells[2]
                                                  << ", the reader " << actual;
    }
    EXPECT_EQ(cells[3].rfind(std::string(k.meaning), 0), 0u)
        << heading << " " << key << ": the doc's meaning should start with \"" << k.meaning << "\"";
    const std::size_t at = section.find("\n| `" + key + "` |");
    EXPECT_GT(at, previous) << heading << " " << key << ": rows out of the reader's order";
    previous = at;
  }
}

TEST(ParameterSchema, DocsListEverySectionKey) {
  const std::string doc = spread::testing::read_source_file("docs/scene-format.md");
  ASSERT_FALSE(doc.empty());
  expect_doc_rows(doc, "`[machine]`", scene::kMachineKeys);
  expect_doc_rows(doc, "`[inlet]`", scene::kInletKeys);
  expect_doc_rows(doc, "`[products]`", scene::kProductsKeys);
  expect_doc_rows(doc, "`[simulate]`", scene::kSimulateKeys);
  expect_doc_rows(doc, "`[air]`", scene::kAirKeys);
  expect_doc_rows(doc, "`[numerics]`", scene::kNumericsKeys);
  expect_doc_rows(doc, "`[sweep]`", scene::kSweepKeys);
  expect_doc_rows(doc, "`[outputs]`", scene::kOutputsKeys);
  expect_doc_rows(doc, "`[field]`", scene::kFieldKeys);
}

// Each section key's range reaches the reader: a value just outside its bounds is refused naming the key.
template <typename Owner, std::size_t N>
void expect_bounds_enforced(const std::string& section, const std::array<scene::Key<Owner>, N>& keys) {
  for (const scene::Key<Owner>& k : keys) {
    const bool is_double = std::holds_alternative<double Owner::*>(k.field);
    const bool is_int = std::holds_alternative<int Owner::*>(k.field);
    if (!is_double && !is_int) continue;
    const scene::Bounds& b = k.bounds;
    const double step = is_int ? 1.0 : 1e-3;
    for (const double outside : {b.low_open ? b.low : b.low - step, b.high_open ? b.high : b.high + step}) {
      if (!std::isfinite(outside)) continue;
      std::ostringstream set;
      set.precision(17);
      set << section << "." << k.name << "=" << outside;
      try {
        scene::parse_scene("[[materials]]\nname = \"u\"\ndensity_kg_m3 = 1000\n", "t", {set.str()});
        ADD_FAILURE() << set.str() << " accepted";
      } catch (const scene::SceneError& e) {
        EXPECT_NE(std::string(e.what()).find(section + "." + std::string(k.name) + ": must be"), std::string::npos)
            << set.str() << ": " << e.what();
      }
    }
  }
}

TEST(ParameterSchema, SceneRefusesSectionValuesOutsideTheBounds) {
  expect_bounds_enforced("machine", scene::kMachineKeys);
  expect_bounds_enforced("inlet", scene::kInletKeys);
  expect_bounds_enforced("air", scene::kAirKeys);
  expect_bounds_enforced("numerics", scene::kNumericsKeys);
  expect_bounds_enforced("outputs", scene::kOutputsKeys);
  expect_bounds_enforced("field", scene::kFieldKeys);
}

// A key that acts with any of several effects names them all when every one is off.
TEST(ParameterSchema, KeyOfSeveralEffectsNamesThemWhenAllAreOff) {
  try {
    scene::fail_effect_off("t", "air.x", "2", effect::kDrag | effect::kMagnus);
    ADD_FAILURE() << "no error";
  } catch (const scene::SceneError& e) {
    EXPECT_EQ(std::string(e.what()), "t: air.x: is 2 but none of the effects `drag, magnus` is on: add \"drag\" to "
                                     "effects.enabled or remove the key");
  }
}

// The scene reader's defaults are the schema's.
TEST(ParameterSchema, SceneDefaultsAreTheSchemas) {
  const scene::Scene s = scene::parse_scene("[[materials]]\nname = \"u\"\ndensity_kg_m3 = 1000\n", "t");
  for (const MaterialQuantity& q : kMaterialQuantities) {
    if (std::isnan(q.scene_default)) continue;
    EXPECT_EQ(s.materials.front().*q.member, q.scene_default) << q.name;
  }
}

// Each quantity's bounds reach the scene reader: a value just outside is refused naming the key.
TEST(ParameterSchema, SceneRefusesValuesOutsideTheBounds) {
  for (const MaterialQuantity& q : kMaterialQuantities) {
    const double outside = q.scene_bounds.low_open ? q.scene_bounds.low : q.scene_bounds.low - 1e-3;
    std::ostringstream text;
    text.precision(17);
    text << "[[materials]]\nname = \"u\"\n";
    if (q.name != "density_kg_m3") text << "density_kg_m3 = 1000\n";
    text << q.name << " = " << outside << "\n";
    try {
      scene::parse_scene(text.str(), "t");
      ADD_FAILURE() << q.name << " = " << outside << " accepted";
    } catch (const scene::SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("materials[0]." + std::string(q.name) + ": must be"), std::string::npos)
          << e.what();
    }
  }
}

// The table file's materials columns are the schema's, in its order (the checksum's order too).
TEST(ParameterSchema, TableColumnsAreTheSchemas) {
  const std::string sql = detail::kSchemaSql;
  const std::size_t begin = sql.find("CREATE TABLE materials (");
  ASSERT_NE(begin, std::string::npos);
  const std::string body = sql.substr(begin, sql.find(");", begin) - begin);
  std::size_t previous = body.find("name TEXT");
  ASSERT_NE(previous, std::string::npos);
  for (const MaterialQuantity& q : kMaterialQuantities) {
    const std::size_t at = body.find("\n  " + std::string(q.name) + " REAL NOT NULL");
    ASSERT_NE(at, std::string::npos) << q.name;
    EXPECT_GT(at, previous) << q.name;
    previous = at;
  }
  EXPECT_GT(body.find("checksum TEXT"), previous);
}

}  // namespace
}  // namespace spread::tables

// The [field] section's keys that name something else: a material of the scene, a boundary for a track.
TEST(ParameterSchema, FieldSectionNamesWhatItCannotRun) {
  const std::string text = "[[materials]]\nname = \"u\"\ndensity_kg_m3 = 1000\n";
  const auto message = [&](const std::string& set) {
    try {
      spread::scene::parse_scene(text, "t", {set});
    } catch (const spread::scene::SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message("field.material=\"v\""), "t: field.material: no material named \"v\"");
  EXPECT_EQ(message("field.track=\"t.csv\""), "t: field.track: a track is driven in a field: give field.boundary too");
  EXPECT_EQ(message("field.material=\"u\""), "");
}
