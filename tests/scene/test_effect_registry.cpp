// The effect registry is the one list of effects: the scene reader, the docs, the C header and the flight
// use it.
#include <gtest/gtest.h>

#include <cctype>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "libspread/core/effect_registry.hpp"
#include "libspread/io/scene/scene.hpp"
#include "tests/support/source_file.hpp"

namespace spread::effect {
namespace {

// The row of docs/scene-format.md's effects table that documents `e`, built from the registry.
std::string doc_row(const Effect& e) {
  std::string needs;
  for (const Effect& other : kRegistry) {
    if ((e.requires_effects & other.bit) == 0) continue;
    needs += (needs.empty() ? "`" : ", `") + std::string(other.name) + "`";
  }
  return "| `" + std::string(e.name) + "` | " + (e.domain == Domain::kDem ? "on the disc" : "in flight") + " | " +
         (e.on_by_default ? "yes" : "no") + " | " + (needs.empty() ? "–" : needs) + " | " + std::string(e.model) +
         " |";
}

TEST(EffectRegistry, DocsListEveryRow) {
  const std::string doc = spread::testing::read_source_file("docs/scene-format.md");
  ASSERT_FALSE(doc.empty());
  for (const Effect& e : kRegistry) EXPECT_NE(doc.find(doc_row(e) + "\n"), std::string::npos) << doc_row(e);
}

// The C API passes its SPREAD_EFFECT_* bits through unchanged: each flight row has its
// `#define SPREAD_EFFECT_<NAME> 0x<bit>u`, and the header has no other (capi/src/predict.cpp checks at compile
// time that SPREAD_EFFECT_ALL, the OR of them, is every flight bit).
TEST(EffectRegistry, CHeaderDefinesEveryFlightBit) {
  const std::string header = spread::testing::read_source_file("capi/include/spread/spread.h");
  const std::regex define(R"(#define SPREAD_EFFECT_([A-Z0-9_]+) 0x([0-9A-Fa-f]+)u\b)");
  std::set<std::string> defined;
  for (auto it = std::sregex_iterator(header.begin(), header.end(), define); it != std::sregex_iterator(); ++it) {
    const std::string macro = (*it)[1];
    defined.insert(macro);
    std::string name = macro;
    for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const Effect* e = find(name);
    ASSERT_NE(e, nullptr) << "SPREAD_EFFECT_" << macro << " has no effect registry row";
    EXPECT_EQ(e->domain, Domain::kFlight) << "SPREAD_EFFECT_" << macro << " is not a flight effect";
    EXPECT_EQ(std::stoul((*it)[2], nullptr, 16), e->bit) << "SPREAD_EFFECT_" << macro;
  }
  for (const Effect& e : kRegistry) {
    if (e.domain != Domain::kFlight) continue;
    std::string macro(e.name);
    for (char& c : macro) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    EXPECT_EQ(defined.count(macro), 1u) << "spread.h lacks #define SPREAD_EFFECT_" << macro << " 0x" << std::hex
                                        << e.bit << "u";
  }
}

TEST(EffectRegistry, SceneDefaultIsTheRegistryDefault) {
  const scene::Scene s = scene::parse_scene("[[materials]]\nname = \"u\"\ndensity_kg_m3 = 1000\n", "t");
  EXPECT_EQ(s.effects, kDefault);
  EXPECT_EQ(to_string(kDefault), "particle_contact,wall_contact,rotation,drag,magnus,spin_decay");
}

TEST(EffectRegistry, RequirementsComeFromTheRows) {
  EXPECT_EQ(unmet_requirements(kRolling), kRotation);
  EXPECT_EQ(unmet_requirements(kRolling | kRotation), 0u);
  try {
    scene::parse_scene("[[materials]]\nname = \"u\"\ndensity_kg_m3 = 1000\n[effects]\nenabled = [\"wall_contact\", "
                       "\"rolling\"]\n",
                       "t");
    FAIL() << "rolling without rotation accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("t: effects.enabled: effect \"rolling\" needs rotation"), std::string::npos)
        << e.what();
  }
}

TEST(EffectRegistry, ListsRoundTripInCanonicalOrder) {
  for (EffectSet set = 0; set <= 0xFFFu; ++set) {
    if ((set & ~kAll) != 0) continue;
    std::string enabled = "[";
    const std::string names = to_string(set);
    std::stringstream parts(names);
    for (std::string name; std::getline(parts, name, ',');) enabled += "\"" + name + "\",";
    enabled += "]";
    if (unmet_requirements(set) != 0) continue;
    const scene::Scene s = scene::parse_scene(
        "[[materials]]\nname = \"u\"\ndensity_kg_m3 = 1000\n[effects]\nenabled = " + enabled + "\n", "t");
    EXPECT_EQ(s.effects, set) << enabled;
  }
}

}  // namespace
}  // namespace spread::effect
