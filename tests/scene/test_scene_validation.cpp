// Every class of bad scene is an error naming the key.
#include <gtest/gtest.h>

#include "libspread/io/scene/scene.hpp"

namespace spread::scene {
namespace {

const char* kBase = R"toml(
[machine]
disc_radius_m = 0.3
[inlet]
radius_m = 0.01
offset_m = 0.1
[[materials]]
name = "m"
density_kg_m3 = 1500
friction_wall = 0.4
)toml";

// Parses kBase plus `extra` lines (or with overrides) and returns the error message ("" = accepted).
std::string error_of(const std::vector<std::string>& overrides, const std::string& extra = "") {
  try {
    parse_scene(std::string(kBase) + extra, "scene.toml", overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const std::vector<std::string>& overrides, const std::string& expected_part,
                  const std::string& extra = "") {
  const std::string message = error_of(overrides, extra);
  EXPECT_NE(message.find(expected_part), std::string::npos)
      << "message \"" << message << "\" lacks \"" << expected_part << "\"";
  EXPECT_EQ(message.rfind("scene.toml", 0), 0u) << message;
}

TEST(SceneValidation, BaseSceneIsValid) { EXPECT_EQ(error_of({}), ""); }

TEST(SceneValidation, UnknownKeysAreNamed) {
  expect_error({}, "scene.toml: air.humidity: unknown key", "[air]\nhumidity = 0.5\n");
  expect_error({"machine.disc_raduis_m=0.3"}, "machine.disc_raduis_m: unknown key");
  expect_error({"materials.0.colour=\"red\""}, "materials[0].colour: unknown key");
  expect_error({"tractor.speed=3"}, "tractor: unknown key");
}

TEST(SceneValidation, ImpossibleNumbers) {
  expect_error({"machine.disc_radius_m=-1"}, "machine.disc_radius_m: must be > 0, got -1");
  expect_error({"machine.disc_radius_m=nan"}, "machine.disc_radius_m: must be a finite number");
  expect_error({"inlet.mass_flow_kg_s=inf"}, "inlet.mass_flow_kg_s: must be a finite number");
  expect_error({"materials.0.friction_wall=-0.1"}, "materials[0].friction_wall: must be in [0, 10], got -0.1");
  expect_error({"materials.0.poisson_ratio=0.7"}, "materials[0].poisson_ratio: must be in [0, 0.499]");
  expect_error({"machine.disc_count=3"}, "machine.disc_count: must be in [1, 2], got 3");
  expect_error({"machine.rotation_sense=0"}, "machine.rotation_sense: must be +1 or -1");
  expect_error({"machine.disc_spacing_m=0.5"}, "machine.disc_spacing_m: must be >= 2 x disc_radius_m");
  expect_error({"sweep.rpm=[500, -3]"}, "sweep.rpm[1]: must be > 0, got -3");
  expect_error({"sweep.samples_per_run=0"}, "sweep.samples_per_run");
  expect_error({"numerics.collector_radius_m=0.1"}, "numerics.collector_radius_m: must be >= disc_radius_m");
  expect_error({"machine.vane_end_radius_m=0.4"}, "machine.vane_end_radius_m: must be <= disc_radius_m");
}

TEST(SceneValidation, InletOutsideTheDisc) {
  expect_error({"inlet.offset_m=0.295"}, "inlet.offset_m: inlet circle reaches beyond the disc rim");
}

TEST(SceneValidation, UnknownEffectAndEnumValues) {
  expect_error({"effects.enabled=[\"drag\", \"gravity_waves\"]"}, "effects.enabled[1]: unknown effect \"gravity_waves\"");
  expect_error({"effects.enabled=[\"drag\", \"drag\"]"}, "listed twice");
  expect_error({"numerics.integrator=\"leapfrog\""}, "numerics.integrator: unknown value \"leapfrog\"");
  expect_error({"sweep.source=\"cfd\""}, "sweep.source: unknown value \"cfd\"");
  expect_error({"machine.disc_model=\"cad\""}, "machine.disc_model: unknown value");
}

// A value whose effect or launch source is off would be recorded as provenance and never act: an error
// naming the key and what is off.
TEST(SceneValidation, ValuesForWhatIsOffAreRefused) {
  expect_error({"materials.0.rolling_friction=0.05"}, "materials[0].rolling_friction: is 0.05 but the `rolling` effect is off");
  EXPECT_EQ(error_of({"materials.0.rolling_friction=0.05",
                      "effects.enabled=[\"particle_contact\", \"wall_contact\", \"rotation\", \"rolling\"]"}),
            "");
  expect_error({"air.wind_m_s=[2.0, 0.0]", "effects.enabled=[\"drag\"]"}, "air.wind_m_s: is [2, 0] but the `wind` effect is off");
  EXPECT_EQ(error_of({"air.wind_m_s=[2.0, 0.0]", "effects.enabled=[\"drag\", \"wind\"]"}), "");
  expect_error({"sweep.source=\"dem\"", "sweep.spin_model=\"sliding\""},
               "sweep.spin_model: applies to the analytic source only");
  EXPECT_EQ(error_of({"sweep.source=\"analytic\"", "sweep.spin_model=\"sliding\""}), "");
  for (const char* key : {"sweep.batch_s=0.1", "sweep.convergence_tolerance=0.01", "sweep.particle_budget=100",
                          "sweep.working_width_ci_m=0.3"}) {
    expect_error({"sweep.source=\"analytic\"", key}, "applies to the DEM source only");
    EXPECT_EQ(error_of({"sweep.source=\"dem\"", key}), "") << key;
  }
  expect_error({"sweep.source=\"dem\"", "sweep.working_width_ci_m=-1"}, "sweep.working_width_ci_m: must be in [0, 100], got -1");
}

// disc_model = "stl" (the file itself is checked where it is read: tests/dem DemSceneStl).
TEST(SceneValidation, StlDiscKeys) {
  expect_error({"machine.disc_model=\"stl\""}, "machine.stl_path: required when disc_model = \"stl\"");
  expect_error({"machine.stl_path=\"disc.stl\""}, "machine.stl_path: is only used with disc_model = \"stl\"");
  expect_error({"machine.disc_model=\"stl\"", "machine.stl_path=\"disc.stl\"", "machine.stl_scale=0"},
               "machine.stl_scale: must be > 0");
  EXPECT_EQ(error_of({"machine.disc_model=\"stl\"", "machine.stl_path=\"disc.stl\"", "machine.stl_scale=0.001"}), "");
}

TEST(SceneValidation, WrongTypes) {
  expect_error({"machine.disc_radius_m=\"big\""}, "machine.disc_radius_m: expected a number, got a string");
  expect_error({"machine.vane_count=2.5"}, "machine.vane_count: expected an integer");
  expect_error({"air.wind_m_s=[1, 2, 3]"}, "air.wind_m_s: expected [vx, vy]");
  expect_error({"outputs.launch_csv=1"}, "outputs.launch_csv: expected true or false");
}

TEST(SceneValidation, MaterialReferencesAndNames) {
  expect_error({"simulate.material=\"Gold\""}, "simulate.material: no material named \"Gold\"");
  expect_error({"sweep.materials=[\"Gold\"]"}, "sweep.materials[0]: no material named \"Gold\"");
  expect_error({}, "materials[1].name: duplicate material name \"m\"",
               "[[materials]]\nname = \"m\"\ndensity_kg_m3 = 1500\n");
  try {
    parse_scene("[machine]\ndisc_radius_m = 0.3\n", "nomat.toml");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("materials: at least one"), std::string::npos) << e.what();
  }
}

TEST(SceneValidation, TomlSyntaxErrorNamesTheLine) {
  try {
    parse_scene("[machine]\ndisc_radius_m = = 3\n", "broken.toml");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("broken.toml:2:", 0), 0u) << e.what();
  }
  EXPECT_THROW(load_scene_file("/nonexistent/scene.toml"), SceneError);
}

}  // namespace
}  // namespace spread::scene
