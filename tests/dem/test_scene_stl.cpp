// A machine's own disc from STL (scene keys machine.disc_model = "stl", machine.stl_path,
// machine.stl_scale): the generated Case-1 disc written to STL and simulated from the STL scene gives
// the generated-mesh result, and every bad file is an error naming machine.stl_path.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/physics/dem/simulate.hpp"
#include <unistd.h>

namespace spread::dem {
namespace {

const std::string kCase1 = std::string(SPREAD_SOURCE_DIR) + "/scenes/case1.toml";

// A scratch folder holding a copy of case1.toml, so relative STL paths resolve against it.
struct SceneDir {
  std::filesystem::path dir;
  std::string scene;
  SceneDir() {
    static int counter = 0;
    dir = std::filesystem::temp_directory_path() /
          ("spread_test_stl_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(dir);
    scene = (dir / "case1_stl.toml").string();
    std::filesystem::copy_file(kCase1, scene, std::filesystem::copy_options::overwrite_existing);
  }
  ~SceneDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  std::string file(const std::string& name) const { return (dir / name).string(); }
};

// Short Case-1 run that launches granules: inlet near the rim and dropped from 5 mm, so a vane sweeps
// ~55 of them off within 0.035 s; ξ 5 mm (bench_dem's) to keep the test short.
std::vector<std::string> short_run(std::vector<std::string> extra = {}) {
  std::vector<std::string> o = {"numerics.duration_s=0.035", "inlet.offset_m=0.25", "inlet.drop_height_m=0.005",
                                "machine.mesh_size_m=0.005", "numerics.threads=1"};
  o.insert(o.end(), extra.begin(), extra.end());
  return o;
}

std::string config_error(const std::string& scene_path, const std::vector<std::string>& overrides) {
  try {
    config_from_scene(scene::load_scene_file(scene_path, overrides));
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(DemSceneStl, GeneratedCase1DiscFromStlGivesTheSameRun) {
  const SceneDir d;
  const SimulationConfig generated = config_from_scene(scene::load_scene_file(kCase1, short_run()));
  ASSERT_GT(generated.disc.mesh_size_m, 0.0);  // case1.toml uses the generated mesh
  const TriangleMesh mesh = mesh_disc_with_vanes(generated.disc);
  write_stl_ascii(mesh, d.file("disc.stl"));       // 17 digits: the coordinates come back exactly
  write_stl_binary(mesh, d.file("disc_bin.stl"));  // 32-bit floats: coordinates rounded (~1e-8 m)

  const SimulationConfig from_ascii = config_from_scene(scene::load_scene_file(
      d.scene, short_run({"machine.disc_model=\"stl\"", "machine.stl_path=\"disc.stl\""})));
  ASSERT_TRUE(from_ascii.disc.mesh);
  ASSERT_EQ(from_ascii.disc.mesh->triangles, mesh.triangles);
  ASSERT_EQ(from_ascii.disc.mesh->vertices, mesh.vertices);

  const SimulationResult a = simulate(generated);
  const SimulationResult b = simulate(from_ascii);
  ASSERT_GT(a.launches.size(), 10u);
  // Same walls, same everything else: the same run, to the bit.
  EXPECT_EQ(a.released, b.released);
  EXPECT_EQ(a.launches.size(), b.launches.size());
  EXPECT_EQ(a.particle_steps, b.particle_steps);
  EXPECT_EQ(a.launch.speed_mean, b.launch.speed_mean);
  EXPECT_EQ(a.mean_radius_m, b.mean_radius_m);
  EXPECT_EQ(a.sector_mass_fraction, b.sector_mass_fraction);

  // Binary STL: vertices rounded to float, so contacts differ in the last digits and the granular flow
  // drifts apart; the run stays close (launch speed within 2 %, same released count).
  const SimulationConfig from_binary = config_from_scene(scene::load_scene_file(
      d.scene, short_run({"machine.disc_model=\"stl\"", "machine.stl_path=\"disc_bin.stl\""})));
  ASSERT_TRUE(from_binary.disc.mesh);
  ASSERT_EQ(from_binary.disc.mesh->triangles.size(), mesh.triangles.size());
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k)
    ASSERT_LT((from_binary.disc.mesh->vertices[k] - mesh.vertices[k]).norm(), 1e-7) << "vertex " << k;
  const SimulationResult c = simulate(from_binary);
  EXPECT_EQ(a.released, c.released);
  ASSERT_GT(c.launches.size(), 0u);
  EXPECT_NEAR(c.launch.speed_mean, a.launch.speed_mean, 0.02 * a.launch.speed_mean);
  std::printf("generated: %zu launched, %llu steps, speed %.6f; binary STL: %zu launched, %llu steps, speed %.6f, R %.6f vs %.6f\n",
              a.launches.size(), static_cast<unsigned long long>(a.particle_steps), a.launch.speed_mean,
              c.launches.size(), static_cast<unsigned long long>(c.particle_steps), c.launch.speed_mean,
              c.mean_radius_m, a.mean_radius_m);
}

TEST(DemSceneStl, MillimetreFileWithScale) {
  const SceneDir d;
  const SimulationConfig generated = config_from_scene(scene::load_scene_file(kCase1, {"machine.mesh_size_m=0.01"}));
  TriangleMesh mm = mesh_disc_with_vanes(generated.disc);
  for (Vec3& v : mm.vertices) v *= 1000.0;
  write_stl_ascii(mm, d.file("disc_mm.stl"));
  const SimulationConfig c = config_from_scene(scene::load_scene_file(
      d.scene, {"machine.disc_model=\"stl\"", "machine.stl_path=\"disc_mm.stl\"", "machine.stl_scale=0.001"}));
  ASSERT_TRUE(c.disc.mesh);
  ASSERT_EQ(c.disc.mesh->vertices.size(), mm.vertices.size());
  for (std::size_t k = 0; k < mm.vertices.size(); ++k)
    ASSERT_LT((c.disc.mesh->vertices[k] - 1e-3 * mm.vertices[k]).norm(), 1e-12);
  // Forgetting the scale: the disc would reach 290 m — caught, with the hint.
  const std::string e = config_error(d.scene, {"machine.disc_model=\"stl\"", "machine.stl_path=\"disc_mm.stl\""});
  EXPECT_NE(e.find("machine.stl_path: the mesh reaches"), std::string::npos) << e;
  EXPECT_NE(e.find("stl_scale = 0.001"), std::string::npos) << e;
}

TEST(DemSceneStl, BadFilesNameTheKey) {
  const SceneDir d;
  auto error_for = [&](const std::string& file) {
    return config_error(d.scene, {"machine.disc_model=\"stl\"", "machine.stl_path=\"" + file + "\""});
  };
  std::string e = error_for("missing.stl");
  EXPECT_NE(e.find("case1_stl.toml: machine.stl_path: no such file"), std::string::npos) << e;
  EXPECT_NE(e.find("missing.stl"), std::string::npos) << e;

  std::ofstream(d.file("notes.stl")) << "this is not a mesh\n";
  e = error_for("notes.stl");
  EXPECT_NE(e.find("machine.stl_path: STL file"), std::string::npos) << e;
  EXPECT_NE(e.find("neither binary"), std::string::npos) << e;

  std::ofstream(d.file("empty.stl")) << "solid empty\nendsolid empty\n";
  e = error_for("empty.stl");
  EXPECT_NE(e.find("machine.stl_path: STL file"), std::string::npos) << e;
  EXPECT_NE(e.find("no valid triangle"), std::string::npos) << e;
}

}  // namespace
}  // namespace spread::dem
