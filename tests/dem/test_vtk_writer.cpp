// VTK snapshots: particle points (active only) and walls placed where they are at time t.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "libspread/physics/dem/vtk_writer.hpp"

namespace spread::dem {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("spread_vtk_" + std::to_string(::getpid()) + "_" + name)).string();
}

// The numbers after `keyword` on its line and the following `rows` lines, as one list.
std::vector<double> section(const std::string& path, const std::string& keyword, int rows) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && line.rfind(keyword, 0) != 0) {
  }
  std::vector<double> values;
  for (int r = 0; r < rows && std::getline(in, line); ++r) {
    std::istringstream fields(line);
    double v = 0.0;
    while (fields >> v) values.push_back(v);
  }
  return values;
}

std::string header_line(const std::string& path, const std::string& keyword) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(keyword, 0) == 0) return line;
  }
  return "";
}

TEST(VtkWriter, ParticlesFileHoldsTheActiveParticlesOnly) {
  ParticleArrays p;
  p.push_back(Vec3(0.1, 0.2, 0.3), Vec3(1, 2, 3), Vec3::Zero(), 0.002, 1e-5, 1e-11, 0, 1, 0.0);
  p.push_back(Vec3(9, 9, 9), Vec3::Zero(), Vec3::Zero(), 0.003, 1e-5, 1e-11, 0, 2, 0.0);
  p.push_back(Vec3(-0.1, 0.0, 0.05), Vec3(0, 0, -1), Vec3::Zero(), 0.0015, 1e-5, 1e-11, 0, 3, 0.0);
  p.active[1] = 0;
  const std::string path = temp_path("particles.vtk");
  write_particles_vtk(p, path);
  EXPECT_EQ(header_line(path, "POINTS"), "POINTS 2 double");
  EXPECT_EQ(section(path, "POINTS", 2), (std::vector<double>{0.1, 0.2, 0.3, -0.1, 0.0, 0.05}));
  EXPECT_EQ(section(path, "LOOKUP_TABLE", 2), (std::vector<double>{0.002, 0.0015}));
  std::filesystem::remove(path);
}

TEST(VtkWriter, WallsAreDrawnTurnedToTheirAngleAtTimeT) {
  WallSet walls;
  WallGroup disc;
  disc.name = "disc";
  disc.pieces.push_back(make_cone_disc(0.3, 0.0, 0.0));  // flat disc: a fan of `segments` triangles
  // A vane along +x in the group frame, 0.1–0.3 m out, 0.05 m high.
  disc.pieces.push_back(make_rectangle(Vec3(0.1, 0.0, 0.0), Vec3::UnitX(), 0.2, Vec3::UnitZ(), 0.05));
  disc.angular_velocity_rad_s = 2.0;  // counter-clockwise seen from above
  walls.groups.push_back(disc);
  const double t_s = M_PI / 4.0;  // θ = ω t = 90°: the vane now points along +y
  const std::string path = temp_path("walls.vtk");
  const int segments = 12;
  write_walls_vtk(walls, t_s, path, segments);

  const int triangles = segments + 2;  // the apex half of each sector is empty
  EXPECT_EQ(header_line(path, "POLYGONS"), "POLYGONS " + std::to_string(triangles) + " " + std::to_string(4 * triangles));
  const std::vector<double> points = section(path, "POINTS", 3 * triangles);
  ASSERT_EQ(points.size(), static_cast<std::size_t>(9 * triangles));
  // Every disc vertex lies on the plane z = 0 within the radius; the vane's vertices lie on x = 0,
  // y in [0.1, 0.3], z in [0, 0.05].
  for (int k = 0; k < 3 * segments; ++k) {
    EXPECT_NEAR(points[3 * k + 2], 0.0, 1e-12);
    EXPECT_LE(std::hypot(points[3 * k], points[3 * k + 1]), 0.3 + 1e-12);
  }
  for (int k = 3 * segments; k < 3 * triangles; ++k) {
    EXPECT_NEAR(points[3 * k], 0.0, 1e-12) << "vertex " << k;
    EXPECT_GE(points[3 * k + 1], 0.1 - 1e-12);
    EXPECT_LE(points[3 * k + 1], 0.3 + 1e-12);
  }
  std::filesystem::remove(path);
}

TEST(VtkWriter, UnwritablePathIsNamed) {
  WallSet walls;
  try {
    write_walls_vtk(walls, 0.0, "/nonexistent-dir/walls.vtk");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/walls.vtk"), std::string::npos);
  }
}

}  // namespace
}  // namespace spread::dem
