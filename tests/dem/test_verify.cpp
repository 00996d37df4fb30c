#include <gtest/gtest.h>

#include "libspread/physics/dem/verify.hpp"

using namespace spread::dem;

TEST(DemVerify, PattersonReeceVaneFast) {
  for (double mu : {0.0, 0.4}) {
    VaneCase c;
    c.rpm = 500;
    c.friction = mu;
    const VaneResult r = run_vane(c);
    EXPECT_LT(std::abs(r.rel_error_radial), 0.02) << mu;
    EXPECT_LT(std::abs(r.rel_error_tangential), 0.02) << mu;
  }
}

TEST(DemVerify, ConeReferenceIsConverged) {
  ConeCase c;
  const ConeState a = cone_reference(c, 1e-12), b = cone_reference(c, 1e-9);
  EXPECT_NEAR(a.speed, b.speed, 1e-9);
  EXPECT_NEAR(a.t_exit, b.t_exit, 1e-7);
}

TEST(DemVerify, AnalyticConeWithinOnePercent) {
  ConeCase c;
  c.mu = 0.3;
  c.particles = 1;
  const ConeResult r = run_cone(c);
  EXPECT_LT(std::abs(r.rel_error_speed), 0.01);
  EXPECT_LT(std::abs(r.rel_error_elevation), 0.01);
  EXPECT_LT(std::abs(r.rel_error_angle), 0.01);
  EXPECT_LT(std::abs(r.rel_error_t_exit), 0.01);
}

// Full sweeps (label long): every case of `spread verify vane` and the mesh convergence of the cone.
TEST(DemVerifyLong, VaneAllCases) {
  for (double rpm : {500.0, 900.0})
    for (double mu : {0.0, 0.3, 0.4}) {
      VaneCase c;
      c.rpm = rpm;
      c.friction = mu;
      const VaneResult r = run_vane(c);
      EXPECT_LT(std::abs(r.rel_error_radial), 0.02);
      EXPECT_LT(std::abs(r.rel_error_tangential), 0.02);
    }
}

// The seed's apparent-friction effect: the mesh error grows as the mesh coarsens, for each μ of Fig. 2.
// (Its sign is the opposite of the seed's: coarse facets make the particles faster, docs/dem.md.)
TEST(DemVerifyLong, ConeMeshErrorGrowsAsMeshCoarsens) {
  for (double mu : {0.25, 0.2625, 0.275, 0.2875, 0.3}) {
    ConeCase c;
    c.mu = mu;
    double previous = 0.0;
    for (double xi : {0.01, 0.02, 0.05}) {
      c.mesh_size = xi;
      const ConeResult r = run_cone(c);
      const double err = std::abs(r.rel_error_speed) + std::abs(r.rel_error_elevation) + std::abs(r.rel_error_angle);
      if (xi == 0.01) {
        EXPECT_LT(std::abs(r.rel_error_speed), 0.01) << "mu " << mu;
        EXPECT_LT(std::abs(r.rel_error_elevation), 0.01) << "mu " << mu;
        EXPECT_LT(std::abs(r.rel_error_angle), 0.01) << "mu " << mu;
      }
      EXPECT_GT(err, previous) << "mu " << mu << " xi " << xi;
      previous = err;
    }
  }
}
