#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "libspread/physics/dem/disc_generator.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/triangle_mesh.hpp"

using namespace spread;
using namespace spread::dem;

namespace {
// A flat square [−L, L]² at z = 0 split into a fan around the origin plus a regular grid: many shared
// edges and vertices.
TriangleMesh flat_mesh() {
  std::vector<std::array<Vec3, 3>> soup;
  const int n = 4;
  const double h = 0.01;
  for (int i = -n; i < n; ++i)
    for (int j = -n; j < n; ++j) {
      const Vec3 a(i * h, j * h, 0), b((i + 1) * h, j * h, 0), c((i + 1) * h, (j + 1) * h, 0), d(i * h, (j + 1) * h, 0);
      const Vec3 m = 0.25 * (a + b + c + d);  // 4-triangle fan per square: vertex of valence 4 and 8
      soup.push_back({a, b, m});
      soup.push_back({b, c, m});
      soup.push_back({c, d, m});
      soup.push_back({d, a, m});
    }
  return weld_triangle_soup(soup, 1e-9);
}

// A particle material (μ 0.5 with particles and walls) and a rigid wall material like it: materials 0 and 1.
std::vector<Material> particle_and_rigid_wall(const char* name, double restitution) {
  Material p;
  p.name = name;
  p.friction_particle = p.friction_wall = 0.5;
  p.restitution = restitution;
  Material w = p;
  w.rigid = true;
  return {p, w};
}
}  // namespace

TEST(DemMesh, OneContactPerFlatPatchAnywhere) {
  MeshCollider mesh(flat_mesh(), 2e-3);
  const double r = 2e-3, gap = 1.5e-3;
  // Over a face, an edge, a valence-4 vertex (square centre), a valence-8 vertex (grid node).
  for (const Vec3& xy : {Vec3(0.0031, 0.0022, 0), Vec3(0.005, 0.0, 0), Vec3(0.005, 0.005, 0), Vec3(0.01, 0.01, 0),
                        Vec3(0.0100001, 0.0149, 0)}) {
    MeshContact out[8];
    const int n = mesh.query(xy + Vec3(0, 0, gap), r, out, 8);
    ASSERT_EQ(n, 1) << "at " << xy.transpose();
    EXPECT_NEAR(out[0].distance_m, gap, 1e-12);
    EXPECT_NEAR(out[0].normal.z(), 1.0, 1e-9);
  }
}

TEST(DemMesh, ConvexRidgeAndConcaveFoldContacts) {
  // Two faces meeting at a ridge along y (roof) and a valley (V).
  auto make = [](double sign) {
    std::vector<std::array<Vec3, 3>> soup;
    const Vec3 a(0, -1, 0), b(0, 1, 0), l1(-1, -1, sign * 0.5), l2(-1, 1, sign * 0.5), r1(1, -1, sign * 0.5), r2(1, 1, sign * 0.5);
    soup.push_back({a, b, l2}); soup.push_back({a, l2, l1});
    soup.push_back({a, r1, r2}); soup.push_back({a, r2, b});
    return weld_triangle_soup(soup, 1e-9);
  };
  MeshContact out[8];
  MeshCollider roof(make(-1.0), 0.1);  // ridge at x = 0 on top
  EXPECT_EQ(roof.query(Vec3(0, 0, 0.05), 0.1, out, 8), 1);  // sits on the ridge: one edge contact
  EXPECT_EQ(out[0].feature, Feature::kEdge);
  MeshCollider valley(make(1.0), 0.1);  // valley: a ball in it touches both faces
  EXPECT_EQ(valley.query(Vec3(0, 0, 0.1), 0.1, out, 8), 2);
}

TEST(DemMesh, StlRoundTripAsciiBinaryAndDegenerate) {
  const auto dir = std::filesystem::temp_directory_path();
  TriangleMesh m = mesh_cone_disc(0.1, 0.2, 0.0, 0.02);
  const auto bin = (dir / "dem_test_bin.stl").string(), asc = (dir / "dem_test_ascii.stl").string();
  write_stl_binary(m, bin);
  write_stl_ascii(m, asc);
  MeshLoadReport rb, ra;
  const TriangleMesh b = read_stl(bin, 1.0, &rb);
  const TriangleMesh a = read_stl(asc, 1.0, &ra);
  EXPECT_EQ(b.triangles.size(), m.triangles.size());
  EXPECT_EQ(a.triangles.size(), m.triangles.size());
  EXPECT_EQ(a.vertices.size(), m.vertices.size());
  EXPECT_NE(ra.message.find("ASCII"), std::string::npos);
  // A degenerate facet (three collinear points) is dropped with a count.
  {
    std::ofstream f(asc, std::ios::app);
    f << "solid x\n";
  }
  const auto deg = (dir / "dem_test_degenerate.stl").string();
  {
    std::ofstream f(deg);
    f << "solid d\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
         "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 2 0 0\nendloop\nendfacet\nendsolid d\n";
  }
  MeshLoadReport rd;
  const TriangleMesh d = read_stl(deg, 1.0, &rd);
  EXPECT_EQ(d.triangles.size(), 1u);
  EXPECT_EQ(rd.degenerate_dropped, 1u);
  EXPECT_THROW(read_stl((dir / "does_not_exist.stl").string()), std::runtime_error);
}

TEST(DemWalls, MeshedPlaneGivesTheAnalyticForce) {
  // A resting particle on a meshed floor and on an analytic floor settles to the same height.
  auto settle = [](bool mesh) {
    Material p;
    p.name = "p";
    p.youngs_modulus_pa = 5e7;
    p.restitution = 0.2;
    Material w = p;
    w.rigid = true;
    WallGroup g;
    if (mesh) g.meshes.emplace_back(flat_mesh(), 2e-3);
    else g.pieces.push_back(make_plane(Vec3::Zero(), Vec3::UnitZ()));
    g.material = 1;
    WallSet ws;
    ws.groups.push_back(g);
    EngineParams ep;
    ep.effects &= ~spread::effect::kParticleContact;
    ep.min_particle_radius_m = 2e-3;
    ep.impact_speed_m_s = 1.0;
    DemEngine e({p, w}, {}, ws, ep);
    e.add_particle(Vec3(0.005, 0.005, 2e-3), Vec3::Zero(), 2e-3, 0);  // right over a fan vertex
    e.run_until(0.05);
    return e.particles().z[0];
  };
  EXPECT_NEAR(settle(true), settle(false), 1e-12);
}

TEST(DemWalls, RotatingDiscCarriesAParticle) {
  // A particle at rest on a spinning flat disc slides: friction μ m g along the relative velocity
  // (+y at +x for counter-clockwise spin) accelerates it at μ g.
  DiscGeometry g;
  g.radius_m = 0.3;
  WallSet ws;
  ws.groups.push_back(make_disc(g, 300.0, 1, 1e-3));
  EngineParams ep;
  ep.effects &= ~spread::effect::kParticleContact;
  ep.effects &= ~spread::effect::kRotation;
  ep.min_particle_radius_m = 1e-3;
  DemEngine e(particle_and_rigid_wall("p", 0.3), {}, ws, ep);
  e.add_particle(Vec3(0.05, 0, 1e-3), Vec3::Zero(), 1e-3, 0);
  e.run_until(0.02);
  const Vec3 v = e.particles().velocity(0);
  EXPECT_NEAR(v.y(), 0.5 * kStandardGravity_m_s2 * 0.02, 0.02 * 0.5 * kStandardGravity_m_s2 * 0.02);
}

TEST(DemWalls, BadGeometryIsRefusedWithItsName) {
  DiscGeometry g;
  g.radius_m = -1.0;
  try {
    make_disc(g, 500, 1, 1e-3);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("radius_m"), std::string::npos);
  }
}

// The wall list (walls fixed in space) looks at a particle only while a wall lies within its radius plus
// half the near list's inner skin at the near list's last build, and then only at the wall groups within it;
// particles raining fast into a cylinder onto its floor (two groups), entering that reach at many different
// steps, must see exactly the contacts of a wall pass that looks at every particle — here forced by a small
// tilted plate far away that turns (not symmetric about its axis, so no wall list), which nothing touches.
TEST(DemWalls, WallListGivesTheBitsOfLookingAtEveryParticle) {
  auto rain = [](bool far_turning_plate) {
    WallGroup mantle, floor;
    mantle.pieces.push_back(make_cylinder_inner(0.02, 0.0, 0.1));
    floor.pieces.push_back(make_plane(Vec3::Zero(), Vec3::UnitZ()));
    mantle.material = floor.material = 1;
    WallSet walls;
    walls.groups.push_back(mantle);
    walls.groups.push_back(floor);
    if (far_turning_plate) {
      WallGroup plate;
      plate.pieces.push_back(make_rectangle(Vec3(1.0, 0.0, 1.0), Vec3(1.0, 0.0, 0.2), 0.01, Vec3::UnitY(), 0.01));
      plate.material = 1;
      plate.angular_velocity_rad_s = 1e-9;  // a surface speed of 1e-9 m/s: the time step is the same
      walls.groups.push_back(plate);
    }
    EngineParams ep;
    ep.contact_law = kLinearSpringDashpotLaw;
    ep.linear.normal_stiffness_n_m = 1000.0;
    ep.integrator = Integrator::kVelocityVerlet;
    ep.min_particle_radius_m = ep.max_particle_radius_m = 1e-3;
    ep.impact_speed_m_s = 4.0;
    DemEngine e(particle_and_rigid_wall("bead", 0.5), {}, walls, ep);
    // A loose column, each bead thrown down and out at its own speed.
    int k = 0;
    for (int iz = 0; iz < 12; ++iz)
      for (int ix = -6; ix <= 6; ++ix)
        for (int iy = -6; iy <= 6; ++iy, ++k) {
          const Vec3 c(ix * 2.6e-3, iy * 2.6e-3, 1.5e-3 + iz * 2.6e-3);
          if (std::hypot(c.x(), c.y()) > 0.017) continue;
          e.add_particle(c, Vec3(0.6 * c.x() / 0.017 * (1 + k % 3), 0.6 * c.y() / 0.017 * (1 + k % 2), -1.5 - 0.15 * (k % 7)), 1e-3, 0);
        }
    return e;
  };
  DemEngine listed = rain(false), every = rain(true);
  ASSERT_EQ(listed.dt_s(), every.dt_s());
  listed.steps(1000);
  every.steps(1000);
  EXPECT_GT(listed.stats().near_list_builds, 5u);
  const auto& a = listed.particles();
  const auto& b = every.particles();
  ASSERT_EQ(a.size(), b.size());
  std::size_t on_walls = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (const auto field : {&ParticleArrays::x, &ParticleArrays::y, &ParticleArrays::z, &ParticleArrays::vx, &ParticleArrays::vy,
                             &ParticleArrays::vz, &ParticleArrays::wx, &ParticleArrays::wy, &ParticleArrays::wz})
      ASSERT_EQ((a.*field)[i], (b.*field)[i]) << "particle " << i;
    on_walls += a.wall_key[i * kWallSlots] != 0 ? 1 : 0;
  }
  EXPECT_GT(on_walls, 100u);
}
