// DEM hard cases, against the engine's public API (libspread/physics/dem): stiff and small granules
// (the automatic step must follow), soft and large, a step above the stable bound, Thornton unloading as
// δ → 0, grazing impacts on a vane edge, a particle exactly on a shared edge or vertex, coplanar
// triangles split differently, a disc at 1500 rpm, degenerate STL input, and repeatability.
// Invariants: no NaN/Inf, penetration bounded by the Hertz maximum of the impact (a few % of the radius
// for stiff granules), mechanical energy never rising in a dissipative contact, the same result twice.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/physics/dem/analytic_wall.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/triangle_mesh.hpp"

namespace spread::dem {
namespace {

constexpr double kG = kStandardGravity_m_s2;

Material granule(double young_pa, double density = 1500.0) {
  Material m;
  m.name = "granule";
  m.youngs_modulus_pa = young_pa;
  m.density_kg_m3 = density;
  m.restitution = 0.5;
  m.friction_particle = m.friction_wall = 0.4;
  return m;
}

Material rigid_wall() {
  Material w = granule(2e11, 7800.0);
  w.name = "steel";
  w.rigid = true;
  return w;
}

WallSet plane_floor() {
  WallGroup g;
  g.name = "floor";
  g.pieces.push_back(make_plane(Vec3::Zero(), Vec3::UnitZ()));
  g.material = 1;
  WallSet walls;
  walls.groups.push_back(g);
  return walls;
}

WallSet mesh_floor(const TriangleMesh& mesh, double radius_m) {
  WallGroup g;
  g.name = "mesh floor";
  g.meshes.emplace_back(mesh, radius_m);
  g.material = 1;
  WallSet walls;
  walls.groups.push_back(g);
  return walls;
}

EngineParams params_for(double radius_m, double impact_speed_m_s) {
  EngineParams p;
  p.min_particle_radius_m = radius_m;
  p.max_particle_radius_m = radius_m;
  p.impact_speed_m_s = impact_speed_m_s;
  p.effects &= ~spread::effect::kParticleContact;
  return p;
}

// Hertz maximum indentation of a sphere hitting a rigid plane at v: δ = (15 m v² / (16 E* √R))^(2/5).
double hertz_max_indentation_m(const Material& m, double radius_m, double speed_m_s) {
  const double mass = m.density_kg_m3 * 4.0 / 3.0 * kPi * std::pow(radius_m, 3);
  const double e_star = m.youngs_modulus_pa / (1.0 - m.poisson_ratio * m.poisson_ratio);
  return std::pow(15.0 * mass * speed_m_s * speed_m_s / (16.0 * e_star * std::sqrt(radius_m)), 0.4);
}

struct DropResult {
  double max_penetration_m = 0.0;
  double max_energy_rise_j = 0.0;  // largest rise of KE + PE above its start
  double initial_energy_j = 0.0;
  double rebound_speed_m_s = 0.0;
  bool finite = true;
  std::vector<double> z_history;
};

// One granule dropped on `walls` from just above contact at `speed`, followed for `duration_s`.
DropResult drop(const Material& m, double radius_m, double speed_m_s, WallSet walls, double duration_s,
                const Vec3& start_xy = Vec3::Zero(), EngineParams params = {}) {
  if (params.min_particle_radius_m == 0.0) params = params_for(radius_m, speed_m_s);
  DemEngine engine({m, rigid_wall()}, {}, std::move(walls), params);
  const double z0 = radius_m * 1.001;
  engine.add_particle(Vec3(start_xy.x(), start_xy.y(), z0), Vec3(0.0, 0.0, -speed_m_s), radius_m, 0);
  const ParticleArrays& p = engine.particles();
  const double mass = p.mass_kg[0];
  DropResult r;
  r.initial_energy_j = engine.kinetic_energy_j() + mass * kG * z0;
  while (engine.time_s() < duration_s && engine.active_count() == 1) {
    engine.step();
    const double z = p.z[0];
    const double energy = engine.kinetic_energy_j() + mass * kG * z;
    if (!std::isfinite(z) || !std::isfinite(energy) || !engine.particles().velocity(0).allFinite()) {
      r.finite = false;
      break;
    }
    r.max_penetration_m = std::max(r.max_penetration_m, radius_m - z);
    r.max_energy_rise_j = std::max(r.max_energy_rise_j, energy - r.initial_energy_j);
    r.rebound_speed_m_s = std::max(r.rebound_speed_m_s, p.vz[0]);
    r.z_history.push_back(z);
  }
  return r;
}

TEST(DemHardCases, StiffAndSmallGranuleAutomaticStepFollows) {
  const double radius = 0.25e-3;  // 0.5 mm granule
  const Material stiff = granule(1e10);
  const Material soft = granule(5e7);
  const EngineParams p = params_for(radius, 5.0);
  const DemEngine stiff_engine({stiff, rigid_wall()}, {}, plane_floor(), p);
  const DemEngine soft_engine({soft, rigid_wall()}, {}, plane_floor(), p);
  // t_c ∝ E*^(-2/5): 200× stiffer → about 8× shorter contact, and the step follows it.
  EXPECT_LT(stiff_engine.dt_s(), soft_engine.dt_s() / 5.0);
  EXPECT_LE(stiff_engine.dt_s(), stiff_engine.contact_time_s() / p.contact_steps * (1.0 + 1e-12));
  EXPECT_LE(stiff_engine.dt_s(), stiff_engine.stable_step_bound_s());

  const DropResult r = drop(stiff, radius, 5.0, plane_floor(), 2e-4);
  ASSERT_TRUE(r.finite);
  const double hertz = hertz_max_indentation_m(stiff, radius, 5.0);
  EXPECT_LE(r.max_penetration_m, 1.05 * hertz) << "Hertz maximum " << hertz;
  EXPECT_LE(r.max_penetration_m, 0.03 * radius);  // a few % of the radius
  EXPECT_LE(r.max_energy_rise_j, 1e-9 * r.initial_energy_j);
  EXPECT_GT(r.rebound_speed_m_s, 0.3 * 5.0);  // it bounced (e = 0.5), not stuck or tunnelled
  EXPECT_LT(r.rebound_speed_m_s, 0.7 * 5.0);
}

TEST(DemHardCases, SoftAndLargeGranulePenetrationStaysHertzian) {
  const double radius = 10e-3;
  const Material soft = granule(1e6);
  const DropResult r = drop(soft, radius, 3.0, plane_floor(), 0.03);
  ASSERT_TRUE(r.finite);
  const double hertz = hertz_max_indentation_m(soft, radius, 3.0);
  EXPECT_LE(r.max_penetration_m, 1.05 * hertz) << "Hertz maximum " << hertz;
  EXPECT_GT(r.max_penetration_m, 0.5 * hertz);  // it did hit (damping with e = 0.5 keeps it below the elastic value)
  EXPECT_LE(r.max_energy_rise_j, 1e-9 * r.initial_energy_j);
}

TEST(DemHardCases, StepAboveTheStableBoundIsRefusedWithTheBound) {
  const double radius = 0.25e-3;
  EngineParams p = params_for(radius, 5.0);
  const DemEngine automatic({granule(1e10), rigid_wall()}, {}, plane_floor(), p);
  p.dt_s = 10.0 * automatic.stable_step_bound_s();
  try {
    DemEngine refused({granule(1e10), rigid_wall()}, {}, plane_floor(), p);
    FAIL() << "a step 10x above the stable bound was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("stable bound"), std::string::npos) << e.what();
  }
  // Just below the bound: accepted, and the impact stays finite and dissipative.
  p.dt_s = 0.9 * automatic.stable_step_bound_s();
  const DropResult r = drop(granule(1e10), radius, 5.0, plane_floor(), 2e-4, Vec3::Zero(), p);
  ASSERT_TRUE(r.finite);
  EXPECT_LE(r.max_energy_rise_j, 1e-6 * r.initial_energy_j);
}

TEST(DemHardCases, NonFiniteStepOrStateIsRefused) {
  const double radius = 1e-3;
  EngineParams p = params_for(radius, 2.0);
  DemEngine engine({granule(5e7), rigid_wall()}, {}, plane_floor(), p);
  const double nan = std::nan("");
  EXPECT_THROW(engine.add_particle(Vec3(0, 0, nan), Vec3::Zero(), radius, 0), std::invalid_argument);
  EXPECT_THROW(engine.add_particle(Vec3(0, 0, 1), Vec3(HUGE_VAL, 0, 0), radius, 0), std::invalid_argument);
  EXPECT_THROW(engine.add_particle(Vec3(0, 0, 1), Vec3::Zero(), nan, 0), std::invalid_argument);
  // A NaN, infinite or negative step is refused naming the key; it never quietly becomes the automatic
  // step (only 0 means automatic).
  for (double bad : {nan, -nan, HUGE_VAL, -HUGE_VAL, -1e-6}) {
    SCOPED_TRACE(bad);
    EngineParams q = p;
    q.dt_s = bad;
    try {
      const DemEngine e({granule(5e7), rigid_wall()}, {}, plane_floor(), q);
      ADD_FAILURE() << "dt_s = " << bad << " was accepted; the engine took " << e.dt_s() << " s";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("dt_s"), std::string::npos) << error.what();
    }
  }
  EngineParams automatic = p;
  automatic.dt_s = 0.0;
  const DemEngine e({granule(5e7), rigid_wall()}, {}, plane_floor(), automatic);
  EXPECT_TRUE(std::isfinite(e.dt_s()) && e.dt_s() > 0.0 && e.dt_s() <= e.stable_step_bound_s()) << e.dt_s();
  Material bad_material = granule(nan);
  EXPECT_THROW(DemEngine({bad_material, rigid_wall()}, {}, plane_floor(), p), std::invalid_argument);
}

// Thornton's unloading correction scales the tangential force by sqrt(δ/δ_old): as δ → 0 that ratio
// must not become 0/0. A granule released exactly touching, at rest, and one arriving at 1 nm/s with a
// sideways velocity (so the tangential spring is loaded) both stay finite and settle.
TEST(DemHardCases, ThorntonUnloadingAsIndentationGoesToZero) {
  const double radius = 1e-3;
  for (double approach : {0.0, 1e-9}) {
    SCOPED_TRACE(approach);
    EngineParams p = params_for(radius, 1.0);
    DemEngine engine({granule(5e7), rigid_wall()}, {}, plane_floor(), p);
    engine.add_particle(Vec3(0, 0, radius), Vec3(1e-6, 0, -approach), radius, 0, Vec3(0, 1e-3, 0));
    for (int i = 0; i < 20000; ++i) {
      engine.step();
      ASSERT_TRUE(engine.particles().position(0).allFinite()) << "step " << i;
      ASSERT_TRUE(engine.particles().velocity(0).allFinite()) << "step " << i;
    }
    const double static_indentation = std::pow(
        3.0 * engine.particles().mass_kg[0] * kG * (1.0 - 0.25 * 0.25) / (4.0 * 5e7 * std::sqrt(radius)), 2.0 / 3.0);
    EXPECT_NEAR(radius - engine.particles().z[0], static_indentation, 0.2 * static_indentation);
    EXPECT_LT(engine.particles().velocity(0).norm(), 1e-3);
  }
}

// Friction at the stick/slip boundary: a granule pressed on the floor by gravity with μ chosen so the
// Coulomb limit is crossed back and forth by the tangential spring. The kinetic energy must not grow.
TEST(DemHardCases, SlipStickSwitchingStaysDissipative) {
  const double radius = 1e-3;
  Material m = granule(5e7);
  m.friction_particle = m.friction_wall = 0.01;  // small μ: the spring reaches the limit within a step or two, every oscillation
  EngineParams p = params_for(radius, 1.0);
  DemEngine engine({m, rigid_wall()}, {}, plane_floor(), p);
  engine.add_particle(Vec3(0, 0, radius * 0.9999), Vec3(0.05, 0.02, 0), radius, 0, Vec3(0, 30.0, -10.0));
  const auto energy = [&] { return engine.kinetic_energy_j() + engine.particles().mass_kg[0] * kG * engine.particles().z[0]; };
  const double start = energy();
  // The start overlap of 1e-7 m stores U = 8/15 E* √R δ^(5/2) ≈ 3e-12 J: the only energy that may appear.
  const double allowed = start * (1.0 + 1e-6) + 1e-11;
  double peak = start;
  for (int i = 0; i < 30000; ++i) {
    engine.step();
    const double e = energy();
    ASSERT_TRUE(std::isfinite(e)) << "step " << i;
    peak = std::max(peak, e);
  }
  EXPECT_LE(peak, allowed) << "start " << start;
  EXPECT_LT(energy(), start);  // sliding friction took energy out
}

// A granule sliding along a vane (two-sided rectangle) at a distance just under its radius, into the
// vane's free edge and past it: grazing face → edge → no contact. Finite, dissipative.
TEST(DemHardCases, GrazingImpactAlongAVaneEdge) {
  const double radius = 1.6e-3;
  for (double overlap : {1e-9, 1e-6, 1e-4}) {
    SCOPED_TRACE(overlap);
    WallGroup vane;
    vane.name = "vane";
    vane.pieces.push_back(make_rectangle(Vec3(0, 0, 0), Vec3::UnitX(), 0.05, Vec3::UnitZ(), 0.036));
    vane.material = 1;
    WallSet walls;
    walls.groups.push_back(vane);
    EngineParams p = params_for(radius, 20.0);
    p.gravity_m_s2 = Vec3::Zero();
    DemEngine engine({granule(5e7), rigid_wall()}, {}, walls, p);
    // Moving along +x, at y = r − overlap from the vane plane, at the top edge height (z = 0.036).
    engine.add_particle(Vec3(0.01, radius - overlap, 0.036), Vec3(15.0, 0.0, 0.0), radius, 0, Vec3::Zero());
    const double e0 = engine.kinetic_energy_j();
    while (engine.time_s() < 0.005) {
      engine.step();
      ASSERT_TRUE(engine.particles().position(0).allFinite());
      ASSERT_LE(engine.kinetic_energy_j(), e0 * (1.0 + 1e-9));
    }
    EXPECT_GT(engine.particles().x[0], 0.06);  // passed the vane's end
  }
}

// Two triangulations of the same unit square: split along either diagonal, and a fan around the centre.
TriangleMesh square(int split) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0), o(0.5, 0.5, 0);
  std::vector<std::array<Vec3, 3>> soup;
  if (split == 0) soup = {{a, b, c}, {a, c, d}};
  if (split == 1) soup = {{a, b, d}, {b, c, d}};
  if (split == 2) soup = {{a, b, o}, {b, c, o}, {c, d, o}, {d, a, o}};
  return weld_triangle_soup(soup, 1e-12);
}

TEST(DemHardCases, CoplanarTrianglesSplitDifferentlyGiveOneIdenticalContact) {
  const double radius = 0.01;
  // Points on faces, on the shared diagonals, on the fan's centre vertex and its spokes.
  const std::vector<Vec3> centres = {{0.5, 0.5, 0.009}, {0.25, 0.25, 0.009}, {0.75, 0.25, 0.009},
                                     {0.5, 0.25, 0.0095}, {0.3, 0.6, 0.005}, {0.5, 0.5, 1e-12}};
  for (const Vec3& centre : centres) {
    SCOPED_TRACE(::testing::Message() << centre.transpose());
    std::vector<MeshContact> first;
    for (int split = 0; split < 3; ++split) {
      const MeshCollider collider(square(split), radius);
      MeshContact out[8];
      const int n = collider.query(centre, radius, out, 8);
      ASSERT_EQ(n, 1) << "split " << split << ": one surface patch, one contact";
      EXPECT_NEAR(out[0].distance_m, centre.z(), 1e-15);
      EXPECT_NEAR((out[0].normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
      EXPECT_NEAR((out[0].point - Vec3(centre.x(), centre.y(), 0)).norm(), 0.0, 1e-15);
    }
  }
}

TEST(DemHardCases, GranuleOnASharedEdgeOrVertexFeelsTheSameForceAsOnAFace) {
  const double radius = 1e-3;
  // Through the engine: the rebound off the diagonal of split 0 equals the rebound off split 1 (where
  // that point is inside a face) and off the centre vertex of the fan.
  std::vector<std::vector<double>> histories;
  for (int split = 0; split < 3; ++split) {
    const DropResult r = drop(granule(5e7), radius, 2.0, mesh_floor(square(split), radius), 2e-3, Vec3(0.5, 0.5, 0));
    ASSERT_TRUE(r.finite);
    histories.push_back(r.z_history);
  }
  for (int split = 1; split < 3; ++split) {
    ASSERT_EQ(histories[static_cast<std::size_t>(split)].size(), histories[0].size());
    for (std::size_t i = 0; i < histories[0].size(); ++i) {
      ASSERT_NEAR(histories[static_cast<std::size_t>(split)][i], histories[0][i], 1e-12) << "split " << split << " step " << i;
    }
  }
  // And equal to the exact plane.
  const DropResult plane = drop(granule(5e7), radius, 2.0, plane_floor(), 2e-3, Vec3(0.5, 0.5, 0));
  ASSERT_EQ(plane.z_history.size(), histories[0].size());
  for (std::size_t i = 0; i < plane.z_history.size(); ++i) ASSERT_NEAR(plane.z_history[i], histories[0][i], 1e-12) << i;
}

// A radial vane on a flat disc at 1500 rpm (rim speed 45 m/s at R = 0.29 m): the granule is thrown
// off finite, and no faster than the frictionless bound √2·ωR of a radial vane (Patterson & Reece).
TEST(DemHardCases, DiscAt1500Rpm) {
  const double radius = 1.6e-3;
  const double disc_radius = 0.29;
  const double omega = 1500.0 * 2.0 * kPi / 60.0;
  WallGroup disc;
  disc.name = "disc";
  disc.pieces.push_back(make_cone_disc(disc_radius, 0.0, 0.0));
  // Vane in the x–z plane, the granule pushed by its +y face (the disc turns counter-clockwise).
  disc.pieces.push_back(make_rectangle(Vec3(0.05, 0, 0), Vec3::UnitX(), disc_radius - 0.05, Vec3::UnitZ(), 0.036));
  disc.angular_velocity_rad_s = omega;
  disc.material = 1;
  WallSet walls;
  walls.groups.push_back(disc);
  EngineParams p = params_for(radius, 0.0);
  DemEngine engine({granule(5e7), rigid_wall()}, {}, walls, p);
  Collector collector;
  collector.enabled = true;
  collector.radius_m = disc_radius + 0.01;
  collector.lost_below_z_m = -0.1;
  engine.set_collector(collector);
  // Start in front of the vane, resting on the disc, turning with it.
  const Vec3 start(0.1, radius * 1.01, radius);
  engine.add_particle(start, Vec3(-omega * start.y(), omega * start.x(), 0.0), radius, 0);
  while (engine.time_s() < 0.1 && engine.launches().empty() && engine.active_count() == 1) {
    engine.step();
    ASSERT_TRUE(engine.particles().position(0).allFinite()) << "t = " << engine.time_s();
  }
  ASSERT_EQ(engine.launches().size(), 1u) << "the granule was not thrown off within 0.1 s";
  const LaunchRecord& launch = engine.launches().front();
  EXPECT_TRUE(launch.velocity_m_s.allFinite());
  const double speed = launch.velocity_m_s.norm();
  EXPECT_GT(speed, 0.7 * omega * disc_radius);
  EXPECT_LT(speed, std::sqrt(2.0) * omega * (disc_radius + 0.01) * 1.02);
}

std::filesystem::path temp_file(const std::string& name) { return std::filesystem::temp_directory_path() / name; }

void write(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// Degenerate STL input: refused with a message naming the file, or loaded with the bad parts reported
// and only finite, non-degenerate triangles kept.
TEST(DemHardCases, DegenerateStlInputIsRefusedOrCleaned) {
  const std::string good = "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n"
                           "      vertex 0 1 0\n    endloop\n  endfacet\n";
  const auto facet = [](const std::string& a, const std::string& b, const std::string& c) {
    return "  facet normal 0 0 1\n    outer loop\n      vertex " + a + "\n      vertex " + b + "\n      vertex " + c +
           "\n    endloop\n  endfacet\n";
  };
  struct Case {
    std::string name, text;
  };
  const std::vector<Case> cases = {
      {"empty", ""},
      {"only_zero_area", "solid s\n" + facet("0 0 0", "1 0 0", "2 0 0") + "endsolid s\n"},
      {"zero_area_and_good", "solid s\n" + facet("0 0 0", "1 0 0", "2 0 0") + good + "endsolid s\n"},
      {"duplicate_vertex", "solid s\n" + facet("0 0 0", "0 0 0", "1 1 0") + good + "endsolid s\n"},
      {"duplicate_triangle", "solid s\n" + good + good + "endsolid s\n"},
      {"nan_vertex", "solid s\n" + facet("nan 0 0", "1 0 0", "0 1 0") + good + "endsolid s\n"},
      {"inf_vertex", "solid s\n" + facet("inf 0 0", "1 0 0", "0 1 0") + good + "endsolid s\n"},
      {"huge_vertex", "solid s\n" + facet("1e308 0 0", "-1e308 0 0", "0 1e308 0") + good + "endsolid s\n"},
      {"non_manifold", "solid s\n" + good + facet("0 0 0", "1 0 0", "0 0 1") + facet("0 0 0", "1 0 0", "0 -1 0") +
                           facet("0 0 0", "1 0 0", "0 0 -1") + "endsolid s\n"},
      {"truncated", "solid s\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0"},
      {"binary_header_lies", std::string(80, 'x') + std::string("\xff\xff\xff\x0f", 4) + std::string(50, '\0')},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const auto path = temp_file("spread_stability_" + c.name + ".stl");
    write(path, c.text);
    MeshLoadReport report;
    try {
      const TriangleMesh mesh = read_stl(path.string(), 1.0, &report);
      ASSERT_FALSE(mesh.triangles.empty());
      for (const Vec3& v : mesh.vertices) EXPECT_TRUE(v.allFinite()) << v.transpose();
      // Usable: a query near the mesh is finite.
      const MeshCollider collider(mesh, 1e-3);
      MeshContact out[8];
      const int n = collider.query(Vec3(0.2, 0.2, 5e-4), 1e-3, out, 8);
      for (int k = 0; k < n; ++k) {
        EXPECT_TRUE(out[k].normal.allFinite());
        EXPECT_TRUE(std::isfinite(out[k].distance_m));
      }
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << "message must name the file: " << e.what();
    }
    std::filesystem::remove(path);
  }
}

TEST(DemHardCases, SameSetupSameResult) {
  const auto run = [] {
    const DropResult r = drop(granule(5e7), 1e-3, 2.0, mesh_floor(square(2), 1e-3), 3e-3, Vec3(0.5, 0.5, 0));
    return r.z_history;
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace spread::dem
