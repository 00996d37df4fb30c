// Shipped scenes parse; overrides; provenance.
#include <gtest/gtest.h>

#include "libspread/io/scene/scene.hpp"

namespace spread::scene {
namespace {

std::string scene_path(const std::string& name) { return std::string(SPREAD_SOURCE_DIR) + "/scenes/" + name; }

TEST(ScenesShipped, DefaultIsTheCase1MachineWithThreeMaterials) {
  const Scene s = load_scene_file(scene_path("default.toml"));
  EXPECT_EQ(s.machine.disc_radius_m, 0.29);
  EXPECT_EQ(s.machine.disc_count, 2);
  EXPECT_EQ(s.machine.cone_angle_rad, 0.157);
  EXPECT_EQ(s.materials.size(), 3u);
  // The main job's table is a DEM table (granule scatter), with enough launches per row for a working
  // width within ±0.5 m (docs/metrics.md "Uncertainty").
  EXPECT_EQ(s.sweep.source, LaunchSource::kDem);
  EXPECT_GE(s.sweep.rpm.size(), 3u);
  EXPECT_LE(s.sweep.rpm.size(), 5u);
  EXPECT_GE(s.sweep.samples_per_run, 2000);
  EXPECT_EQ(s.sweep_materials().size(), 3u);
  EXPECT_TRUE(s.has(effect::kDrag));
  EXPECT_FALSE(s.has(effect::kWind));
  EXPECT_EQ(s.numerics.collector_radius_m, 0.29);  // 0 resolved to the disc radius
}

TEST(ScenesShipped, Case1MatchesSeedTable1) {
  const Scene s = load_scene_file(scene_path("case1.toml"));
  EXPECT_EQ(s.machine.disc_radius_m, 0.29);
  EXPECT_EQ(s.machine.disc_height_m, 0.28);
  EXPECT_EQ(s.machine.cone_angle_rad, 0.157);
  EXPECT_EQ(s.machine.vane_count, 2);
  EXPECT_EQ(s.machine.vane_height_m, 0.036);
  EXPECT_EQ(s.inlet.radius_m, 0.0145);
  EXPECT_EQ(s.inlet.offset_m, 0.1);
  EXPECT_EQ(s.inlet.mass_flow_kg_s, 0.11);
  EXPECT_EQ(s.machine.rpm, 500.0);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].friction_wall, 0.35);
  EXPECT_EQ(s.machine.disc_model, DiscModel::kMesh);
}

TEST(ScenesShipped, Case2MatchesSeedTables1And2) {
  const Scene s = load_scene_file(scene_path("case2.toml"));
  EXPECT_EQ(s.machine.disc_radius_m, 0.1524);
  EXPECT_EQ(s.machine.disc_height_m, 1.0);
  EXPECT_EQ(s.machine.cone_angle_rad, 0.0);
  EXPECT_EQ(s.machine.vane_count, 4);
  EXPECT_EQ(s.machine.vane_height_m, 0.025);
  EXPECT_EQ(s.inlet.radius_m, 0.0065);
  EXPECT_EQ(s.inlet.offset_m, 0.05);
  EXPECT_EQ(s.sweep.rpm, (std::vector<double>{540.0, 810.0}));
  ASSERT_EQ(s.materials.size(), 9u);
  const Material* kmag = s.find_material("Kmag");
  ASSERT_NE(kmag, nullptr);
  EXPECT_EQ(kmag->density_kg_m3, 2542.0);
  EXPECT_EQ(kmag->friction_wall, 0.5);
  const Material* pell = s.find_material("Pell lime");
  ASSERT_NE(pell, nullptr);
  EXPECT_EQ(pell->density_kg_m3, 2105.0);
  EXPECT_EQ(s.find_material("Muriate of potash")->friction_wall, 0.6);
}

TEST(SceneDefaults, MinimalSceneGetsDocumentedDefaults) {
  const Scene s = parse_scene("[[materials]]\nname = \"m\"\ndensity_kg_m3 = 1500\n", "mini.toml");
  EXPECT_EQ(s.machine.disc_radius_m, 0.29);
  EXPECT_EQ(s.machine.vane_end_radius_m, 0.29);
  EXPECT_EQ(s.simulate_material, "m");
  EXPECT_EQ(s.sweep_rpms(), std::vector<double>{500.0});
  EXPECT_EQ(s.air.viscosity_pa_s, 1.81e-5);
  EXPECT_EQ(s.numerics.integrator, Integrator::kSymplecticEuler);
}

TEST(SceneOverrides, ValuesAreParsedAsToml) {
  const Scene s = load_scene_file(scene_path("default.toml"),
                                  {"machine.rpm=650", "sweep.rpm=[500, 600.5]", "air.wind_m_s=[1.5, -2]",
                                   "effects.enabled=[\"drag\", \"wind\"]", "numerics.integrator=\"velocity_verlet\"",
                                   "outputs.launch_csv=true", "machine.name=bare-word"});
  EXPECT_EQ(s.machine.rpm, 650.0);
  EXPECT_EQ(s.sweep.rpm, (std::vector<double>{500.0, 600.5}));
  EXPECT_EQ(s.air.wind_m_s[0], 1.5);
  EXPECT_EQ(s.air.wind_m_s[1], -2.0);
  EXPECT_TRUE(s.has(effect::kDrag));
  EXPECT_FALSE(s.has(effect::kMagnus));
  EXPECT_EQ(effect::to_string(s.effects), "drag,wind");
  EXPECT_EQ(s.numerics.integrator, Integrator::kVelocityVerlet);
  EXPECT_TRUE(s.outputs.launch_csv);
  EXPECT_EQ(s.machine.name, "bare-word");
}

TEST(SceneOverrides, ArrayElementsByIndexAndNewSections) {
  const Scene s = load_scene_file(scene_path("default.toml"),
                                  {"materials.1.density_kg_m3=1300", "simulate.material=Urea"});
  EXPECT_EQ(s.materials[1].name, "Urea");
  EXPECT_EQ(s.materials[1].density_kg_m3, 1300.0);
  EXPECT_EQ(s.simulate_material, "Urea");
  const Scene fresh = parse_scene("[[materials]]\nname = \"m\"\ndensity_kg_m3 = 1500\n", "mini.toml",
                                  {"inlet.offset_m=0.05"});
  EXPECT_EQ(fresh.inlet.offset_m, 0.05);
}

TEST(SceneOverrides, OverrideIsValidatedLikeTheFile) {
  try {
    load_scene_file(scene_path("default.toml"), {"machine.disc_radius_m=-1"});
    FAIL() << "negative radius accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("machine.disc_radius_m: must be > 0, got -1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_scene_file(scene_path("default.toml"), {"machine.bogus=1"}), SceneError);
  EXPECT_THROW(load_scene_file(scene_path("default.toml"), {"no_equals_sign"}), SceneError);
  EXPECT_THROW(load_scene_file(scene_path("default.toml"), {"materials.7.density_kg_m3=1"}), SceneError);
  // An index too long for size_t is refused like any index out of range (it once escaped as
  // std::out_of_range from stoul: fuzz/regressions/scene_parser/).
  try {
    load_scene_file(scene_path("default.toml"), {"materials.888888888888888888888881.density_kg_m3=1800"});
    FAIL() << "huge index accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("materials.888888888888888888888881: index out of range"), std::string::npos)
        << e.what();
  }
}

TEST(SceneProvenance, HashCoversTextAndOverrides) {
  const Scene a = load_scene_file(scene_path("default.toml"));
  const Scene b = load_scene_file(scene_path("default.toml"));
  const Scene c = load_scene_file(scene_path("default.toml"), {"machine.rpm=510"});
  EXPECT_EQ(a.hash(), b.hash());
  EXPECT_NE(a.hash(), c.hash());
  EXPECT_EQ(a.hash().size(), 16u);
  EXPECT_EQ(a.provenance_text(), a.text);
  EXPECT_NE(c.provenance_text().find("# --set machine.rpm=510"), std::string::npos);
}

}  // namespace
}  // namespace spread::scene
