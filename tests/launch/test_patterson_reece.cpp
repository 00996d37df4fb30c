// The closed-form vane motion against an independent numerical integration of the ODE, and its limits.
#include <gtest/gtest.h>

#include <cmath>

#include "libspread/core/vec3.hpp"
#include "libspread/physics/launch/patterson_reece.hpp"

namespace spread::launch {
namespace {

// The equation of motion written out independently of the closed form (see patterson_reece.hpp):
// s̈ = ω² cos²α s − g sin α − μ (g cos α + ω² cos α sin α s + 2 ω cos α ṡ), integrated with classic
// RK4 at a tiny step until ρ = s cos α reaches the exit radius (final step interpolated linearly).
struct NumericExit {
  double time_s, s_dot_m_s;
};
NumericExit integrate_to_exit(const VaneMotion& m, double r0_m, double r_exit_m) {
  const double ca = std::cos(m.cone_angle_rad), sa = std::sin(m.cone_angle_rad), w = m.omega_rad_s;
  auto accel = [&](double s, double v) {
    return w * w * ca * ca * s - m.gravity_m_s2 * sa - m.friction * (m.gravity_m_s2 * ca + w * w * ca * sa * s + 2.0 * w * ca * v);
  };
  double s = r0_m / ca, v = 0.0, t = 0.0;
  const double s_exit = r_exit_m / ca;
  const double h = 1e-6;
  while (true) {
    const double k1s = v, k1v = accel(s, v);
    const double k2s = v + 0.5 * h * k1v, k2v = accel(s + 0.5 * h * k1s, v + 0.5 * h * k1v);
    const double k3s = v + 0.5 * h * k2v, k3v = accel(s + 0.5 * h * k2s, v + 0.5 * h * k2v);
    const double k4s = v + h * k3v, k4v = accel(s + h * k3s, v + h * k3v);
    const double s_next = s + h / 6.0 * (k1s + 2 * k2s + 2 * k3s + k4s);
    const double v_next = v + h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (s_next >= s_exit) {
      const double f = (s_exit - s) / (s_next - s);
      return {t + f * h, v + f * (v_next - v)};
    }
    s = s_next;
    v = v_next;
    t += h;
  }
}

double omega_of(double rpm) { return rpm * 2.0 * kPi / 60.0; }

TEST(PattersonReece, ClosedFormMatchesNumericalIntegrationFlatDisc) {
  for (double mu : {0.0, 0.3, 0.6}) {
    for (double rpm : {300.0, 900.0}) {
      const VaneMotion motion{omega_of(rpm), mu, 0.0, kStandardGravity_m_s2};
      const VaneExit exit = vane_exit(motion, 0.1, 0.4);
      const NumericExit ref = integrate_to_exit(motion, 0.1, 0.4);
      EXPECT_NEAR(exit.time_s, ref.time_s, 1e-6 * ref.time_s + 2e-7) << "mu " << mu << " rpm " << rpm;
      EXPECT_NEAR(exit.radial_speed_m_s, ref.s_dot_m_s, 1e-6 * ref.s_dot_m_s) << "mu " << mu << " rpm " << rpm;
      EXPECT_DOUBLE_EQ(exit.tangential_speed_m_s, omega_of(rpm) * 0.4);
      EXPECT_EQ(exit.vertical_speed_m_s, 0.0);
    }
  }
}

TEST(PattersonReece, ClosedFormMatchesNumericalIntegrationCone) {
  const double alpha = 0.157;
  const VaneMotion motion{omega_of(500.0), 0.35, alpha, kStandardGravity_m_s2};
  const VaneExit exit = vane_exit(motion, 0.1, 0.29);
  const NumericExit ref = integrate_to_exit(motion, 0.1, 0.29);
  EXPECT_NEAR(exit.time_s, ref.time_s, 1e-6 * ref.time_s + 2e-7);
  EXPECT_NEAR(exit.speed_along_vane_m_s, ref.s_dot_m_s, 1e-6 * ref.s_dot_m_s);
  // The relative velocity leaves along the generatrix: elevation = cone angle.
  EXPECT_NEAR(std::atan2(exit.vertical_speed_m_s, exit.radial_speed_m_s), alpha, 1e-12);
}

TEST(PattersonReece, FrictionlessFlatDiscGivesOmegaSqrtRSquaredMinusR0Squared) {
  // μ = 0: r = r0 cosh ωt, ṙ = ω sqrt(r² − r0²) — also checks that gravity drops out on a flat disc.
  const double omega = omega_of(540.0);
  const VaneMotion motion{omega, 0.0, 0.0, kStandardGravity_m_s2};
  const VaneExit exit = vane_exit(motion, 0.05, 0.3);
  EXPECT_NEAR(exit.radial_speed_m_s, omega * std::sqrt(0.3 * 0.3 - 0.05 * 0.05), 1e-12 * omega);
  EXPECT_NEAR(exit.time_s, std::acosh(0.3 / 0.05) / omega, 1e-13);
  EXPECT_NEAR(exit.turned_angle_rad, std::acosh(6.0), 1e-12);
}

TEST(PattersonReece, ExitAngleFromTangentTendsToTheLimitForSmallR0) {
  for (double mu : {0.0, 0.35, 0.6}) {
    const double limit = exit_angle_from_tangent_limit_rad(mu);
    EXPECT_NEAR(limit, std::atan(std::sqrt(1.0 + mu * mu) - mu), 1e-15);
    // r0/R = 1e-4 and a fast, large disc (ω²R ≫ μg): angle = atan(ṙ / ωR) approaches the limit.
    const VaneMotion motion{omega_of(3000.0), mu, 0.0, kStandardGravity_m_s2};
    const VaneExit exit = vane_exit(motion, 2e-4, 2.0);
    const double angle = std::atan2(exit.radial_speed_m_s, exit.tangential_speed_m_s);
    EXPECT_NEAR(angle, limit, 1e-4) << "mu " << mu;
    // ... and a larger r0 is measurably further from it (the check can fail).
    const VaneExit near_rim = vane_exit(motion, 1.0, 2.0);
    EXPECT_GT(std::abs(std::atan2(near_rim.radial_speed_m_s, near_rim.tangential_speed_m_s) - limit), 1e-2);
  }
}

TEST(PattersonReece, RefusesAGranuleHeldByFriction) {
  // r0 ≤ μ g / ω²: the vane cannot push it outward.
  const double omega = omega_of(30.0);
  const VaneMotion motion{omega, 0.6, 0.0, kStandardGravity_m_s2};
  const double held_radius = 0.5 * 0.6 * kStandardGravity_m_s2 / (omega * omega);
  EXPECT_THROW(vane_exit(motion, held_radius, held_radius * 10.0), std::invalid_argument);
  const VaneMotion steep{omega_of(500.0), 0.6, 1.1, kStandardGravity_m_s2};  // tan α > 1/μ
  EXPECT_THROW(vane_exit(steep, 0.1, 0.3), std::invalid_argument);
}

}  // namespace
}  // namespace spread::launch
