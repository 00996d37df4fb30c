// The mesh walls' near lists (mesh_near_list.hpp): the contacts through a particle's list are the grid
// query's to the bit, however the list's skin is chosen and whenever it is rebuilt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "libspread/physics/dem/disc_generator.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/mesh_near_list.hpp"
#include "libspread/physics/dem/wall_set.hpp"

using namespace spread;
using namespace spread::dem;

namespace {

// The seed's Case-1 disc (cone 0.157 rad, R 0.29 m, two radial vanes 0.036 m high) as a mesh of size ξ.
DiscGeometry case1_disc(double radius_m, double xi_m) {
  DiscGeometry g;
  g.radius_m = radius_m;
  g.cone_angle_rad = 0.157;
  g.vane_count = 2;
  g.vane_start_radius_m = 0.2 * radius_m;
  g.vane_height_m = 0.036;
  g.mesh_size_m = xi_m;
  return g;
}

void expect_same_contacts(const WallContact* a, int na, const WallContact* b, int nb, int step) {
  ASSERT_EQ(na, nb) << "step " << step;
  for (int c = 0; c < na; ++c) {
    EXPECT_EQ(a[c].key, b[c].key) << "step " << step;
    EXPECT_EQ(a[c].distance_m, b[c].distance_m) << "step " << step;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(a[c].point_m[k], b[c].point_m[k]) << "step " << step;
      EXPECT_EQ(a[c].normal[k], b[c].normal[k]) << "step " << step;
    }
  }
}

}  // namespace

TEST(DemMeshNearList, ListedContactsAreTheGridQuerysBits) {
  WallSet walls;
  walls.groups.push_back(make_disc(case1_disc(0.29, 0.005), 500.0, 0, 1.6e-3));
  MeshNearLists lists;
  lists.configure(walls.mesh_count(), 0.8e-3);
  lists.resize(1);
  // A granule wandering over the turning disc, across faces, edges, vertices and the vanes' feet and tops,
  // in steps of up to 0.3 mm so that its list is both kept and rebuilt.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> step(-0.3e-3, 0.3e-3);
  const double r = 1.6e-3;
  int touching = 0, multiple = 0;
  for (int track = 0; track < 40; ++track) {
    const double phi = 0.05 * track, rho = 0.06 + 0.005 * track;
    Vec3 at(rho * std::cos(phi), rho * std::sin(phi), std::tan(0.157) * rho + 0.8 * r);
    for (int s = 0; s < 400; ++s) {
      walls.set_time(1e-5 * s);
      at += Vec3(step(rng), step(rng), step(rng));
      at.z() = std::clamp(at.z(), std::tan(0.157) * std::hypot(at.x(), at.y()) - 0.5 * r, std::tan(0.157) * std::hypot(at.x(), at.y()) + 0.04);
      WallContact grid[8], listed[8];
      const int ng = walls.collect(at, r, grid, 8);
      const int nl = walls.collect(at, r, listed, 8, ~0ull, lists.of(0, 1));
      expect_same_contacts(grid, ng, listed, nl, track * 400 + s);
      touching += ng > 0;
      multiple += ng > 1;
    }
  }
  EXPECT_GT(touching, 4000);
  EXPECT_GT(multiple, 50);  // edges, folds and vane feet were met, not only faces
}

TEST(DemMeshNearList, RunOnAMeshDiscIsTheSameForAnySkin) {
  // Granules rain on a small turning mesh disc and leave it at the collector, so the engine compacts its
  // arrays (and the lists with them) while lists are kept: a skin of 1 µm rebuilds a list nearly every step,
  // one of 2 mm rarely. The same bits either way.
  auto run = [](double mesh_skin_m) {
    WallSet walls;
    walls.groups.push_back(make_disc(case1_disc(0.06, 0.004), 700.0, 1, 1e-3));
    EngineParams ep;
    ep.min_particle_radius_m = ep.max_particle_radius_m = 1e-3;
    ep.mesh_skin_m = mesh_skin_m;
    Material granule;
    granule.name = "granule";
    Material disc = granule;
    disc.rigid = true;
    DemEngine e({granule, disc}, {}, walls, ep);
    Collector c;
    c.enabled = true;
    c.radius_m = 0.045;
    e.set_collector(c);
    for (int k = 0; k < 24; ++k) {
      const double phi = 0.7 * k, rho = 0.012 + 0.0008 * k;
      e.add_particle(Vec3(rho * std::cos(phi), rho * std::sin(phi), std::tan(0.157) * rho + 1.2e-3 + 2.5e-3 * (k % 4)),
                     Vec3(0.0, 0.0, -0.3), 1e-3, 0);
    }
    e.steps(6000);
    return e;
  };
  const DemEngine fine = run(1e-6), coarse = run(2e-3);
  EXPECT_GT(fine.launches().size(), 2u);
  ASSERT_EQ(fine.launches().size(), coarse.launches().size());
  for (std::size_t k = 0; k < fine.launches().size(); ++k) {
    EXPECT_EQ(fine.launches()[k].id, coarse.launches()[k].id);
    EXPECT_EQ(fine.launches()[k].time_s, coarse.launches()[k].time_s);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(fine.launches()[k].velocity_m_s[d], coarse.launches()[k].velocity_m_s[d]);
  }
  const auto& a = fine.particles();
  const auto& b = coarse.particles();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (const auto field : {&ParticleArrays::x, &ParticleArrays::y, &ParticleArrays::z, &ParticleArrays::vx, &ParticleArrays::vy,
                             &ParticleArrays::vz})
      ASSERT_EQ((a.*field)[i], (b.*field)[i]) << "particle " << i;
}
