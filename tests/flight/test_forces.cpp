// The right-hand side: Magnus direction, the ω → 0 and v → 0 limits, drag at rest, and that switched-off
// effects are not in the state at all.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

#include "libspread/physics/flight/right_hand_side.hpp"
#include "tests/flight/flight_test_support.hpp"

namespace spread::flight {
namespace {

using detail::FlightParameters;
using detail::StateVector;

FlightParameters parameters(const State& launch, LiftModel lift = LiftModel::kSmoothSaturating) {
  Settings settings;
  settings.lift = lift;
  settings.gravity_m_s2 = 0.0;  // look at the air forces alone (validation forbids 0 only at the API)
  return detail::make_flight_parameters(test::typical_granule(), launch, Air{}, settings);
}

// Acceleration from Magnus alone (constant spin, no spin decay: spin comes from the parameters).
Vec3 magnus_acceleration(const Vec3& velocity, const Vec3& spin, LiftModel lift) {
  State s;
  s.velocity_m_s = velocity;
  s.spin_rad_s = spin;
  const FlightParameters p = parameters(s, lift);
  StateVector<kMagnus> y = {0, 0, 0, velocity.x(), velocity.y(), velocity.z()};
  StateVector<kMagnus> dy{};
  detail::flight_rhs<kMagnus>(p, y, dy);
  return Vec3(dy[3], dy[4], dy[5]);
}

static_assert(detail::kStateSize<kDrag | kMagnus> == 6, "no spin state without spin decay");
static_assert(detail::kStateSize<kMagnus | kSpinDecay> == 9, "spin integrated with spin decay");

TEST(Magnus, DirectionIsOmegaCrossV) {
  for (LiftModel lift : {LiftModel::kSmoothSaturating, LiftModel::kOesterleBuiDinh,
                         LiftModel::kOesterleBuiDinhAsPrinted}) {
    const Vec3 a = magnus_acceleration(Vec3(20.0, 0.0, 0.0), Vec3(0.0, 0.0, 300.0), lift);
    EXPECT_GT(a.y(), 0.0);  // ω = +z, v = +x → ω × v = +y
    EXPECT_EQ(a.x(), 0.0);
    EXPECT_EQ(a.z(), 0.0);
    const Vec3 b = magnus_acceleration(Vec3(20.0, 0.0, 0.0), Vec3(0.0, 0.0, -300.0), lift);
    EXPECT_NEAR(b.y(), -a.y(), 1e-12 * a.y());
  }
}

TEST(Magnus, MagnitudeMatchesEquation28) {
  const Granule g = test::typical_granule();
  const Air air;
  const Vec3 v(20.0, 5.0, -3.0);
  const Vec3 w(10.0, -40.0, 250.0);
  const double speed = v.norm();
  const double re = air.density_kg_m3 * g.diameter_m * speed / air.viscosity_pa_s;
  const double spin_ratio = g.diameter_m * w.norm() / (2.0 * speed);
  for (LiftModel lift : {LiftModel::kSmoothSaturating, LiftModel::kOesterleBuiDinh}) {
    const double cl = lift_coefficient(lift, spin_ratio, re);
    const double area = kPi * g.diameter_m * g.diameter_m / 4.0;
    const double mass = g.density_kg_m3 * kPi * std::pow(g.diameter_m, 3) / 6.0;
    const Vec3 expected = 0.5 * air.density_kg_m3 * cl * area * speed * w.cross(v) / w.norm() / mass;
    const Vec3 a = magnus_acceleration(v, w, lift);
    EXPECT_NEAR((a - expected).norm(), 0.0, 1e-12 * expected.norm());
    EXPECT_NEAR(a.dot(v), 0.0, 1e-12 * a.norm() * speed);  // lift does no work
  }
}

TEST(Magnus, FiniteAndVanishingAsSpinGoesToZero) {
  for (LiftModel lift : {LiftModel::kSmoothSaturating, LiftModel::kOesterleBuiDinh,
                         LiftModel::kOesterleBuiDinhAsPrinted}) {
    double previous = INFINITY;
    for (double spin : {1e2, 1.0, 1e-3, 1e-8, 1e-20, 1e-300, 0.0}) {
      const Vec3 a = magnus_acceleration(Vec3(25.0, 10.0, 2.0), Vec3(0.0, spin, spin), lift);
      ASSERT_TRUE(a.allFinite()) << "spin " << spin;
      EXPECT_LE(a.norm(), previous) << "spin " << spin;
      previous = a.norm();
    }
    EXPECT_EQ(previous, 0.0);
  }
}

TEST(Magnus, FiniteAndVanishingAsVelocityGoesToZero) {
  for (LiftModel lift : {LiftModel::kSmoothSaturating, LiftModel::kOesterleBuiDinh,
                         LiftModel::kOesterleBuiDinhAsPrinted}) {
    double previous = INFINITY;
    for (double speed : {30.0, 1.0, 1e-3, 1e-8, 1e-20, 1e-300, 0.0}) {
      const Vec3 a = magnus_acceleration(Vec3(speed, 0.0, 0.0), Vec3(0.0, 0.0, 400.0), lift);
      ASSERT_TRUE(a.allFinite()) << "speed " << speed;
      EXPECT_LE(a.norm(), previous) << "speed " << speed;
      previous = a.norm();
    }
    EXPECT_EQ(previous, 0.0);
    EXPECT_TRUE(magnus_acceleration(Vec3::Zero(), Vec3::Zero(), lift).isZero(0.0));
  }
}

TEST(Drag, ZeroAtRestAndOpposesRelativeVelocity) {
  State s;
  const FlightParameters p = parameters(s);
  StateVector<kDrag> y{};
  StateVector<kDrag> dy{};
  detail::flight_rhs<kDrag>(p, y, dy);
  for (double d : dy) EXPECT_EQ(d, 0.0);

  // With wind the drag pushes towards the wind velocity.
  FlightParameters windy = p;
  windy.wind_m_s[0] = 5.0;
  StateVector<kDrag | kWind> y2{};
  StateVector<kDrag | kWind> dy2{};
  detail::flight_rhs<kDrag | kWind>(windy, y2, dy2);
  EXPECT_GT(dy2[3], 0.0);
  EXPECT_EQ(dy2[4], 0.0);
}

TEST(SpinDecayRhs, MatchesEquation34) {
  const Granule g = test::typical_granule();
  const Air air;
  State s;
  s.spin_rad_s = Vec3(100.0, -200.0, 300.0);
  const FlightParameters p = parameters(s);
  StateVector<kSpinDecay> y = {0, 0, 0, 0, 0, 0, 100.0, -200.0, 300.0};
  StateVector<kSpinDecay> dy{};
  detail::flight_rhs<kSpinDecay>(p, y, dy);
  const double mass = g.density_kg_m3 * kPi * std::pow(g.diameter_m, 3) / 6.0;
  const double inertia = mass * g.diameter_m * g.diameter_m / 10.0;
  const double re_spin = air.density_kg_m3 * s.spin_rad_s.norm() * g.diameter_m * g.diameter_m / (4 * air.viscosity_pa_s);
  const Vec3 expected = -spin_decay_alpha(re_spin) * air.viscosity_pa_s * std::pow(g.diameter_m, 3) * s.spin_rad_s / inertia;
  EXPECT_NEAR(dy[6], expected.x(), 1e-12 * expected.norm());
  EXPECT_NEAR(dy[7], expected.y(), 1e-12 * expected.norm());
  EXPECT_NEAR(dy[8], expected.z(), 1e-12 * expected.norm());
}

}  // namespace
}  // namespace spread::flight
