// A sphere dropped from high up reaches the speed where m g = ½ ρ C_D A v² (Eqs. 27, 32); the root is
// found here independently by bisection.
#include <gtest/gtest.h>

#include <cmath>

#include "libspread/physics/flight/flight.hpp"
#include "tests/flight/flight_test_support.hpp"

namespace spread::flight {
namespace {

double terminal_speed_by_bisection(const Granule& g, const Air& air, double gravity) {
  const double mass = g.density_kg_m3 * kPi * std::pow(g.diameter_m, 3) / 6.0;
  const double area = kPi * g.diameter_m * g.diameter_m / 4.0;
  const auto excess_drag = [&](double v) {
    const double re = air.density_kg_m3 * g.diameter_m * v / air.viscosity_pa_s;
    const double cd = 24.0 / re * (1.0 + 0.1806 * std::pow(re, 0.6459)) + 0.4251 / (1.0 + 6880.95 / re);
    return 0.5 * air.density_kg_m3 * cd * area * v * v - mass * gravity;
  };
  double lo = 1e-6;
  double hi = 1e3;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (excess_drag(mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(TerminalVelocity, LongDropMatchesRootSolve) {
  const Air air;
  for (const Granule& g : {Granule{3.2e-3, 1500.0}, Granule{1e-3, 1000.0}, Granule{6e-3, 2500.0}}) {
    const double expected = terminal_speed_by_bisection(g, air, kStandardGravity_m_s2);
    State launch;
    launch.position_m = Vec3(0.0, 0.0, 2000.0);
    for (Scheme scheme : {Scheme::kDormandPrince45, Scheme::kRk4}) {
      Settings settings;
      settings.scheme = scheme;
      settings.dt_s = 1e-2;
      settings.max_time_s = 1000.0;
      // The physics is under test, not the tolerance: at rtol 1e-6 DP's 2 s steps in the steady fall leave
      // ~2e-6 relative velocity error.
      settings.rel_tol = 1e-10;
      settings.abs_tol = 1e-10;
      const Landing landing = fly_to_ground(g, launch, 0.0, air, kDrag, settings);
      ASSERT_TRUE(landing.landed);
      EXPECT_NEAR(-landing.state.velocity_m_s.z(), expected, 1e-6 * expected) << "D=" << g.diameter_m << " scheme " << static_cast<int>(scheme) << " steps " << landing.steps << " rejected " << landing.rejected_steps;
      EXPECT_NEAR(landing.state.velocity_m_s.x(), 0.0, 1e-12);
    }
  }
}

}  // namespace
}  // namespace spread::flight
