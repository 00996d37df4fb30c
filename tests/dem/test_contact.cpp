#include <gtest/gtest.h>

#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/restitution.hpp"
#include "libspread/physics/dem/time_step.hpp"

using namespace spread;
using namespace spread::dem;

TEST(DemRestitution, HertzFitReproducesRequestedRestitution) {
  // The corrected fit (docs/design.md §2) against the non-dimensional clipped impact: measured within 0.2 %
  // over [0.1, 0.95] (0.95 is the worst, −0.20 %).
  for (double e : {0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 0.95}) {
    const double measured = simulated_restitution_hertz(hertz_damping_ratio(e));
    EXPECT_NEAR(measured, e, 0.0025 * e) << "e = " << e;
  }
  EXPECT_EQ(hertz_damping_ratio(1.0), 0.0);
}

TEST(DemRestitution, LinearBisectionMatches) {
  for (double e : {0.1, 0.5, 0.9}) EXPECT_NEAR(simulated_restitution_linear(linear_damping_ratio(e)), e, 1e-6);
}

TEST(DemContact, HertzNormalForceIsMinusEnergyGradient) {
  // HOOMD-style check: the elastic force equals −dU/dδ with U = 8/15 sqrt(R*) E* δ^{5/2}.
  PairParams p;
  p.e_star_pa = 1e8;
  p.g_star_pa = 4e7;
  p.friction = 0.0;
  ContactInput in;
  in.r_eff_m = 1e-3;
  in.m_eff_kg = 1e-5;
  in.dt_s = 1e-7;
  const double d = 2e-6, h = 1e-10;
  auto energy = [&](double delta) { return 8.0 / 15.0 * std::sqrt(in.r_eff_m) * p.e_star_pa * std::pow(delta, 2.5); };
  in.overlap_m = d;
  double hist[4] = {0, 0, 0, 0};
  const ContactForce f = HertzThornton::eval(p, in, hist);
  EXPECT_NEAR(f.normal_force_n, (energy(d + h) - energy(d - h)) / (2 * h), 1e-6 * f.normal_force_n);
}

TEST(DemContact, NormalForceNeverAttracts) {
  PairParams p;
  p.e_star_pa = 1e8;
  p.g_star_pa = 4e7;
  p.damping_ratio = hertz_damping_ratio(0.1);
  ContactInput in;
  in.overlap_m = 1e-7;
  in.slip_m_s = Vec3(0, 0, 50.0);  // separating fast: damping would pull
  in.r_eff_m = 1e-3;
  in.m_eff_kg = 1e-5;
  in.dt_s = 1e-7;
  double hist[4] = {0, 0, 0, 0};
  EXPECT_EQ(HertzThornton::eval(p, in, hist).normal_force_n, 0.0);
}

TEST(DemContact, CoulombCapAndShortenedSpring) {
  PairParams p;
  p.e_star_pa = 1e8;
  p.g_star_pa = 4e7;
  p.friction = 0.3;
  ContactInput in;
  in.overlap_m = 1e-6;
  in.r_eff_m = 1e-3;
  in.m_eff_kg = 1e-5;
  in.dt_s = 1e-6;
  in.slip_m_s = Vec3(5.0, 0, 0);  // strong sliding
  double hist[4] = {0, 0, 0, 0};
  ContactForce f;
  for (int k = 0; k < 50; ++k) f = HertzThornton::eval(p, in, hist);
  EXPECT_LE(f.tangential_force_n.norm(), 0.3 * f.normal_force_n * (1 + 1e-12));
  EXPECT_LT(f.tangential_force_n.x(), 0.0);  // opposes the slip
  EXPECT_LE(std::hypot(hist[0], hist[1]), 0.3 * f.normal_force_n * (1 + 1e-12));  // spring shortened
}

TEST(DemContact, UnloadingScalesTangentialSpring) {
  PairParams p;
  p.e_star_pa = 1e8;
  p.g_star_pa = 4e7;
  p.friction = 10.0;  // never slides
  ContactInput in;
  in.r_eff_m = 1e-3;
  in.m_eff_kg = 1e-5;
  in.dt_s = 1e-6;
  in.overlap_m = 4e-6;
  in.slip_m_s = Vec3(0.01, 0, 0);
  double hist[4] = {0, 0, 0, 0};
  HertzThornton::eval(p, in, hist);
  const double before = hist[0];
  in.overlap_m = 1e-6;  // a = sqrt(Rδ) halves
  in.slip_m_s = Vec3::Zero();
  HertzThornton::eval(p, in, hist);
  EXPECT_NEAR(hist[0], 0.5 * before, 1e-12 * std::abs(before));
}

TEST(DemTimeStep, HertzContactTimeAndBound) {
  PairParams p;
  p.e_star_pa = 5e7;
  p.g_star_pa = 2e7;
  const double tc = hertz_contact_time_s(1e-5, 1e-3, 5e7, 1.0);
  EXPECT_GT(tc, 0.0);
  // Scaling t_c ∝ v^{-1/5}.
  EXPECT_NEAR(hertz_contact_time_s(1e-5, 1e-3, 5e7, 32.0), tc / 2.0, 1e-12);
  const double bound = stable_step_bound_s(kHertzThorntonLaw, p, 1e-5, 1e-3, 1.0, false);
  EXPECT_GT(bound, tc / 10.0);
  EXPECT_LT(bound, tc);
}
