#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "libspread/physics/dem/restitution.hpp"
#include "libspread/physics/dem/verify.hpp"

using namespace spread::dem;

// Contact time within 2 % of Hertz — for a damped contact the reference is the damped Hertz
// model itself (its overlap ODE solved to 1e-12, contact_reference), not the elastic Hertz time.
TEST(DemImpact, SpherePlaneRestitutionAndContactTime) {
  for (double e : {0.1, 0.3, 0.5, 0.7, 0.9}) {
    ImpactCase c;
    c.restitution = e;
    const ImpactResult r = run_impact(c);
    std::printf("plane e %.2f measured %.5f t %.4e ref %.4e hertz %.4e\n", e, r.e_measured, r.t_contact_s,
                r.t_contact_ref_s, r.t_contact_hertz_s);
    EXPECT_NEAR(r.e_measured, e, 0.01 * e);
    EXPECT_NEAR(r.t_contact_s, r.t_contact_ref_s, 0.02 * r.t_contact_ref_s) << "e " << e;
  }
}

TEST(DemImpact, SphereSphereRestitutionMomentum) {
  for (double e : {0.1, 0.3, 0.5, 0.7, 0.9}) {
    ImpactCase c;
    c.sphere_sphere = true;
    c.restitution = e;
    const ImpactResult r = run_impact(c);
    std::printf("sphere e %.2f measured %.5f t %.4e ref %.4e hertz %.4e mom %.2e\n", e, r.e_measured, r.t_contact_s,
                r.t_contact_ref_s, r.t_contact_hertz_s, r.momentum_rel_error);
    EXPECT_NEAR(r.e_measured, e, 0.01 * e);
    EXPECT_NEAR(r.t_contact_s, r.t_contact_ref_s, 0.02 * r.t_contact_ref_s) << "e " << e;
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
    EXPECT_NEAR(r.t_contact_ref_s, r.t_contact_hertz_s, 0.005 * r.t_contact_hertz_s);  // 2.87 is rounded
    EXPECT_LT(r.momentum_rel_error, 1e-12);
  }
}

// The reference itself: converged (1e-9 vs 1e-12), and the damped ODE gives back the restitution the
// γ(e) fit was made for (the fit is within 0.2 %, docs/dem.md), while its duration falls as e falls.
TEST(DemImpact, ContactReferenceConvergedAndConsistent) {
  double previous = 0.0;
  for (double e : {0.1, 0.3, 0.5, 0.7, 0.9, 1.0}) {
    const double gamma = hertz_damping_ratio(e);
    const ContactReference fine = contact_reference(kHertzThorntonLaw, gamma, 1e-12);
    const ContactReference coarse = contact_reference(kHertzThorntonLaw, gamma, 1e-9);
    EXPECT_NEAR(coarse.duration, fine.duration, 1e-7 * fine.duration) << "e " << e;
    EXPECT_NEAR(fine.restitution, e, 0.003 * e) << "e " << e;
    EXPECT_GT(fine.duration, previous) << "e " << e;
    previous = fine.duration;
    const ContactReference lin = contact_reference(kLinearSpringDashpotLaw, linear_damping_ratio(e));
    // linear_damping_ratio bisects on an RK4 impact ending at a step end (h = 2e-4): e within ~1e-5.
    EXPECT_NEAR(lin.restitution, e, 2e-5) << "linear e " << e;
  }
  // Elastic Hertz: τ = 2 ∫0^{x_m} dx / sqrt(1 − 0.8 x^{5/2}) = 3.21807, i.e. 2.86827 × (M*²/(R* E*² v))^{1/5}
  // with t0 of verify.hpp (the "2.87" of hertz_contact_time_s rounded).
  EXPECT_NEAR(contact_reference(kHertzThorntonLaw, 0.0).duration * std::pow(0.75, 0.4), 2.86827, 1e-4);
  EXPECT_NEAR(contact_reference(kLinearSpringDashpotLaw, 0.0).duration, spread::kPi, 1e-9);
}
