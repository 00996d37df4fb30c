// The particle–particle pass: one thread adds each pair straight into the sums, several threads
// store per-pair results and gather them; both must give bit-identical states. The block is large enough
// (> 4096 particles and pairs) for the threaded path to run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "libspread/physics/dem/engine.hpp"

using namespace spread;
using namespace spread::dem;

namespace {

DemEngine dense_block(int threads) {
  Material p;
  p.name = "bead";
  p.friction_particle = p.friction_wall = 0.5;
  p.restitution = 0.5;
  p.youngs_modulus_pa = 5e7;
  Material w = p;
  w.rigid = true;
  WallGroup floor;
  floor.pieces.push_back(make_plane(Vec3::Zero(), Vec3::UnitZ()));
  floor.material = 1;
  WallSet walls;
  walls.groups.push_back(floor);
  EngineParams ep;
  ep.contact_law = kLinearSpringDashpotLaw;
  ep.linear.normal_stiffness_n_m = 1000.0;
  ep.integrator = Integrator::kVelocityVerlet;
  ep.min_particle_radius_m = 1.8e-3;
  ep.max_particle_radius_m = 2.0e-3;
  ep.impact_speed_m_s = 1.0;
  ep.threads = threads;
  DemEngine e({p, w}, {}, walls, ep);
  // 24 × 24 × 8 grid, neighbours just touching (spacing 3.99 mm for radii up to 2 mm), sizes and
  // velocities varied deterministically so that every pair differs.
  int k = 0;
  for (int ix = 0; ix < 24; ++ix)
    for (int iy = 0; iy < 24; ++iy)
      for (int iz = 0; iz < 8; ++iz, ++k)
        e.add_particle(Vec3(ix * 3.99e-3, iy * 3.99e-3, 2.0e-3 + iz * 3.99e-3),
                       Vec3(0.01 * ((k * 7) % 5 - 2), 0.01 * ((k * 3) % 5 - 2), -0.05), 1.8e-3 + 0.2e-3 * ((k * 11) % 10) / 9.0, 0,
                       Vec3(0.0, 0.0, 0.5 * ((k * 5) % 3 - 1)));
  return e;
}

}  // namespace

TEST(DemPairPass, OneThreadAndTwoThreadsGiveIdenticalStates) {
  DemEngine one = dense_block(1), two = dense_block(2);
  for (int s = 0; s < 60; ++s) {
    one.step();
    two.step();
  }
  ASSERT_GT(one.pair_count(), 4096u);
  const auto& a = one.particles();
  const auto& b = two.particles();
  ASSERT_EQ(a.size(), b.size());
  std::size_t pushed = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.x[i], b.x[i]) << i;
    ASSERT_EQ(a.z[i], b.z[i]) << i;
    ASSERT_EQ(a.vx[i], b.vx[i]) << i;
    ASSERT_EQ(a.vz[i], b.vz[i]) << i;
    ASSERT_EQ(a.wz[i], b.wz[i]) << i;
    ASSERT_EQ(a.fy[i], b.fy[i]) << i;
    pushed += a.fx[i] != 0.0 ? 1 : 0;  // only contacts push sideways
  }
  EXPECT_GT(pushed, 100u);
}

TEST(DemPairPass, NewtonsThirdLawHoldsWithoutWallsOrGravity) {
  // Without walls and gravity the pair forces are the only forces: they sum to zero (to rounding).
  Material p;
  p.name = "bead";
  EngineParams ep;
  ep.contact_law = kLinearSpringDashpotLaw;
  ep.linear.normal_stiffness_n_m = 1000.0;
  ep.integrator = Integrator::kVelocityVerlet;
  ep.min_particle_radius_m = 2e-3;
  ep.gravity_m_s2 = Vec3::Zero();
  DemEngine e({p}, {}, WallSet{}, ep);
  int k = 0;
  for (int ix = 0; ix < 6; ++ix)
    for (int iy = 0; iy < 6; ++iy, ++k)
      e.add_particle(Vec3(ix * 3.9e-3, iy * 3.9e-3, 0.0), Vec3(0.02 * (k % 3 - 1), 0.0, 0.01 * (k % 2)), 2e-3, 0);
  e.step();
  double fx = 0.0, fy = 0.0, fz = 0.0, fmax = 0.0;
  const auto& q = e.particles();
  for (std::size_t i = 0; i < q.size(); ++i) {
    fx += q.fx[i];
    fy += q.fy[i];
    fz += q.fz[i];
    fmax = std::max(fmax, std::abs(q.fx[i]));
  }
  ASSERT_GT(fmax, 0.05);  // overlaps of 0.1 mm at k_n 1000 N/m: 0.1 N
  EXPECT_NEAR(fx, 0.0, 1e-12 * fmax);
  EXPECT_NEAR(fy, 0.0, 1e-12 * fmax);
  EXPECT_NEAR(fz, 0.0, 1e-12 * fmax);
}
