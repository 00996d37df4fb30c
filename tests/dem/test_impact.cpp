#include <gtest/gtest.h>

#include <cstdio>

#include "libspread/dem/verify.hpp"

using namespace spread::dem;

TEST(DemImpact, SpherePlaneRestitutionAndContactTime) {
  for (double e : {0.1, 0.3, 0.5, 0.7, 0.9}) {
    ImpactCase c;
    c.restitution = e;
    const ImpactResult r = run_impact(c);
    std::printf("plane e %.2f measured %.5f t %.4e hertz %.4e\n", e, r.e_measured, r.t_contact_s, r.t_contact_hertz_s);
    EXPECT_NEAR(r.e_measured, e, 0.01 * e);
  }
}

TEST(DemImpact, SphereSphereRestitutionMomentum) {
  for (double e : {0.1, 0.3, 0.5, 0.7, 0.9}) {
    ImpactCase c;
    c.sphere_sphere = true;
    c.restitution = e;
    const ImpactResult r = run_impact(c);
    std::printf("sphere e %.2f measured %.5f t %.4e hertz %.4e mom %.2e\n", e, r.e_measured, r.t_contact_s, r.t_contact_hertz_s, r.momentum_rel_error);
    EXPECT_NEAR(r.e_measured, e, 0.01 * e);
    EXPECT_LT(r.momentum_rel_error, 1e-12);
  }
}

TEST(DemImpact, ElasticFrictionlessKeepsEnergyAndHertzTime) {
  for (bool ss : {false, true}) {
    ImpactCase c;
    c.sphere_sphere = ss;
    c.restitution = 1.0;
    const ImpactResult r = run_impact(c);
    std::printf("elastic ss=%d energy %.6f t %.4e hertz %.4e\n", ss, r.energy_ratio, r.t_contact_s, r.t_contact_hertz_s);
    EXPECT_NEAR(r.energy_ratio, 1.0, 1e-3);
    EXPECT_NEAR(r.t_contact_s, r.t_contact_hertz_s, 0.02 * r.t_contact_hertz_s);
    EXPECT_LT(r.momentum_rel_error, 1e-12);
  }
}
