// Integrator accuracy: RK4's observed order, the adaptive tolerance, exact ground crossing, wind drift.
#include <gtest/gtest.h>

#include <cmath>

#include "libspread/physics/flight/flight.hpp"
#include "tests/flight/flight_test_support.hpp"

namespace spread::flight {
namespace {

using test::horizontal_distance_m;

Landing fly(const Settings& settings, EffectSet effects = test::kDiscEffects, const Air& air = Air{}) {
  return fly_to_ground(test::typical_granule(), test::typical_launch(), 0.0, air, effects, settings);
}

TEST(Rk4, ObservedOrderIsFour) {
  const Landing reference = fly(test::tight_dormand_prince());
  ASSERT_TRUE(reference.landed);
  double errors[3];
  const double steps_s[3] = {2e-2, 1e-2, 5e-3};
  for (int i = 0; i < 3; ++i) {
    const Landing l = fly(test::rk4(steps_s[i]));
    ASSERT_TRUE(l.landed);
    errors[i] = horizontal_distance_m(l.state, reference.state);
  }
  for (int i = 0; i < 2; ++i) {
    const double order = std::log2(errors[i] / errors[i + 1]);
    EXPECT_GT(order, 3.7) << "errors " << errors[i] << " → " << errors[i + 1];
    EXPECT_LT(order, 4.3) << "errors " << errors[i] << " → " << errors[i + 1];
  }
}

TEST(DormandPrince, ToleranceHonoured) {
  const Landing reference = fly(test::tight_dormand_prince());
  const double range_m = reference.state.position_m.norm();
  double previous_error = INFINITY;
  int previous_steps = 0;
  for (double tol : {1e-3, 1e-5, 1e-7, 1e-9}) {
    Settings settings;
    settings.rel_tol = tol;
    settings.abs_tol = tol;
    const Landing l = fly(settings);
    ASSERT_TRUE(l.landed);
    const double error = horizontal_distance_m(l.state, reference.state);
    EXPECT_LT(error, previous_error) << "tol " << tol;
    EXPECT_LT(error, 2.0 * tol * range_m) << "tol " << tol;
    EXPECT_GT(l.steps, previous_steps) << "tol " << tol;
    EXPECT_NEAR(l.flight_time_s, reference.flight_time_s, 10.0 * tol * reference.flight_time_s + 1e-12);
    previous_error = error;
    previous_steps = l.steps;
  }
}

TEST(GroundCrossing, ExactInVacuum) {
  // Gravity only: z(t) = z0 + vz t − g t²/2 has the closed-form landing time and point.
  State launch;
  launch.position_m = Vec3(0.3, -0.2, 1.1);
  launch.velocity_m_s = Vec3(17.0, 9.0, 6.5);
  launch.spin_rad_s = Vec3(1.0, 2.0, 3.0);
  const double ground = 0.25;
  const double g = kStandardGravity_m_s2;
  const double vz = launch.velocity_m_s.z();
  const double t = (vz + std::sqrt(vz * vz + 2.0 * g * (launch.position_m.z() - ground))) / g;
  const double x = launch.position_m.x() + launch.velocity_m_s.x() * t;
  const double y = launch.position_m.y() + launch.velocity_m_s.y() * t;
  for (const Settings& settings : {test::rk4(1e-3), test::rk4(7e-2), Settings{}}) {
    const Landing l = fly_to_ground(test::typical_granule(), launch, ground, Air{}, 0, settings);
    ASSERT_TRUE(l.landed);
    EXPECT_NEAR(l.flight_time_s, t, 1e-9 * t);
    EXPECT_NEAR(l.state.position_m.x(), x, 1e-9 * x);
    EXPECT_NEAR(l.state.position_m.y(), y, 1e-9 * y);
    EXPECT_EQ(l.state.position_m.z(), ground);
    EXPECT_NEAR(l.state.velocity_m_s.z(), vz - g * t, 1e-9 * g * t);
    EXPECT_EQ(l.state.spin_rad_s, launch.spin_rad_s);  // no spin decay: ω constant
  }
}

TEST(GroundCrossing, LandingLiesOnTheTrajectory) {
  // With air: the interpolated crossing of a coarse run agrees with a tight run far below 1 mm, and the
  // default DP run's landing (the one the C API relies on) is within 1 mm.
  const Landing reference = fly(test::tight_dormand_prince());
  const Landing coarse_rk4 = fly(test::rk4(1e-3));
  const Landing default_dp = fly(Settings{});
  EXPECT_LT(horizontal_distance_m(coarse_rk4.state, reference.state), 1e-4);
  EXPECT_LT(horizontal_distance_m(default_dp.state, reference.state), 1e-3);
  EXPECT_EQ(default_dp.state.position_m.z(), 0.0);
}

TEST(GroundCrossing, LaunchOnGroundFallingHasLanded) {
  State launch;
  launch.velocity_m_s = Vec3(3.0, 0.0, -1.0);
  const Landing l = fly_to_ground(test::typical_granule(), launch, 0.0, Air{}, kDrag, Settings{});
  EXPECT_TRUE(l.landed);
  EXPECT_EQ(l.flight_time_s, 0.0);
  EXPECT_EQ(l.steps, 0);
}

TEST(GroundCrossing, LaunchOnGroundGoingUpLandsAfterItsHop) {
  // A hop shorter than the first step (v_z = 5 cm/s: 10 ms in the air, 0.13 mm high) lands at the
  // closed-form time and point in vacuum, for every integrator and for fly_many's SIMD lanes.
  State launch;
  launch.position_m = Vec3(0.1, 0.2, 0.0);
  launch.velocity_m_s = Vec3(3.0, -1.0, 0.05);
  const double t = 2.0 * launch.velocity_m_s.z() / kStandardGravity_m_s2;
  Settings coarse;
  coarse.dt_s = 0.05;  // the first trial step: five hops long
  for (const Settings& settings : {test::rk4(0.05), test::rk4(1e-3), coarse, Settings{}}) {
    const Landing l = fly_to_ground(test::typical_granule(), launch, 0.0, Air{}, 0, settings);
    ASSERT_TRUE(l.landed);
    EXPECT_NEAR(l.flight_time_s, t, 1e-9);
    EXPECT_NEAR(l.state.position_m.x(), 0.1 + 3.0 * t, 1e-9);
    EXPECT_NEAR(l.state.position_m.y(), 0.2 - 1.0 * t, 1e-9);
  }
  // With drag, one by one and in lanes: the same landing, after a hop.
  const Granule granules[1] = {test::typical_granule()};
  const State launches[3] = {launch, launch, launch};
  Landing lanes[3];
  fly_many(granules, launches, 0.0, Air{}, kDrag, coarse, lanes);
  const Landing single = fly_to_ground(test::typical_granule(), launch, 0.0, Air{}, kDrag, coarse);
  ASSERT_TRUE(single.landed);
  EXPECT_GT(single.flight_time_s, 0.9 * t);
  EXPECT_LT(single.flight_time_s, t);
  for (const Landing& l : lanes) {
    ASSERT_TRUE(l.landed);
    EXPECT_EQ(l.flight_time_s, single.flight_time_s);
    EXPECT_EQ(l.state.position_m, single.state.position_m);
  }
}

TEST(Limits, MaxTimeStopsWithoutLanding) {
  Settings settings;
  settings.max_time_s = 0.2;
  for (Scheme scheme : {Scheme::kRk4, Scheme::kDormandPrince45}) {
    settings.scheme = scheme;
    const Landing l = fly(settings);
    EXPECT_FALSE(l.landed);
    EXPECT_NEAR(l.flight_time_s, 0.2, 1e-12);
  }
  Settings few_steps = test::rk4(1e-3);
  few_steps.max_steps = 10;
  const Landing l = fly(few_steps);
  EXPECT_FALSE(l.landed);
  EXPECT_EQ(l.steps, 10);
}

TEST(Wind, DriftsDownwind) {
  const Landing still = fly(Settings{}, test::kDiscEffects);
  Air windy;
  windy.wind_m_s = Vec3(4.0, -3.0, 0.0);
  const Landing drifted = fly(Settings{}, test::kDiscEffects | kWind, windy);
  const Vec3 shift = drifted.state.position_m - still.state.position_m;
  EXPECT_GT(shift.x(), 0.05);
  EXPECT_LT(shift.y(), -0.05);
  // Mostly along the wind: the shift makes an angle < 30° with it.
  EXPECT_GT(shift.head<2>().normalized().dot(windy.wind_m_s.head<2>().normalized()), std::cos(kPi / 6));
  // The wind vector is ignored unless the wind effect is on.
  const Landing ignored = fly(Settings{}, test::kDiscEffects, windy);
  EXPECT_EQ(ignored.state.position_m, still.state.position_m);
}

}  // namespace
}  // namespace spread::flight

namespace spread::flight {
namespace {

// Without spin at launch, Magnus lift and spin decay act as zeros: the flight is the one without them,
// flown by the instantiation without them (same landing, bit for bit, same steps).
TEST(Effects, ZeroSpinLaunchFliesWithoutLiftAndSpinDecay) {
  State launch = test::typical_launch();
  launch.spin_rad_s = Vec3::Zero();
  Air windy;
  windy.wind_m_s = Vec3(2.0, -1.0, 0.0);
  for (const Settings& settings : {Settings{}, test::rk4(1e-3)}) {
    const Landing all = fly_to_ground(test::typical_granule(), launch, 0.0, windy, kAllEffects, settings);
    const Landing drag =
        fly_to_ground(test::typical_granule(), launch, 0.0, windy, kAllEffects & ~(kMagnus | kSpinDecay), settings);
    ASSERT_TRUE(all.landed);
    EXPECT_EQ(all.state.position_m, drag.state.position_m);
    EXPECT_EQ(all.flight_time_s, drag.flight_time_s);
    EXPECT_EQ(all.steps, drag.steps);
  }
  // A spinning launch still feels them.
  const Landing spinning = fly_to_ground(test::typical_granule(), test::typical_launch(), 0.0, Air{}, kAllEffects, Settings{});
  const Landing spinning_drag = fly_to_ground(test::typical_granule(), test::typical_launch(), 0.0, Air{}, kDrag, Settings{});
  EXPECT_GT(horizontal_distance_m(spinning.state, spinning_drag.state), 1e-3);
}

}  // namespace
}  // namespace spread::flight
