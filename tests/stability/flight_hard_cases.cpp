// Flight hard cases: ω = 0, v = 0 relative to the air, Re → 0, launch straight down, wind
// stronger than the launch, extreme diameters and densities, a step far above the drag relaxation time.
// Invariants asserted for every case and both integrators: no NaN/Inf in the result (a refusal is an
// exception naming the cause, never a silent NaN), the landing on the ground plane, speed bounded by
// energy (drag only removes energy, Magnus does no work), and bit-identical repeats.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/physics/flight/flight.hpp"

namespace spread::flight {
namespace {

constexpr double kG = kStandardGravity_m_s2;

Settings settings_for(Scheme scheme) {
  Settings s;
  s.scheme = scheme;
  s.dt_s = 1e-3;
  return s;
}

bool finite(const Vec3& v) { return v.allFinite(); }

void expect_finite_landing(const Landing& landing) {
  EXPECT_TRUE(finite(landing.state.position_m)) << landing.state.position_m.transpose();
  EXPECT_TRUE(finite(landing.state.velocity_m_s)) << landing.state.velocity_m_s.transpose();
  EXPECT_TRUE(finite(landing.state.spin_rad_s)) << landing.state.spin_rad_s.transpose();
  EXPECT_TRUE(std::isfinite(landing.flight_time_s));
  EXPECT_GE(landing.flight_time_s, 0.0);
}

// Still air (no wind): the landing speed can never exceed the speed of a drag-free fall from the
// launch, v² ≤ v0² + 2 g h — drag takes energy out and the Magnus force is perpendicular to v.
void expect_energy_bounded(const State& launch, double ground_z_m, const Landing& landing) {
  const double v0_sq = launch.velocity_m_s.squaredNorm();
  const double bound_sq = v0_sq + 2.0 * kG * (launch.position_m.z() - ground_z_m);
  EXPECT_LE(landing.state.velocity_m_s.squaredNorm(), bound_sq * (1.0 + 1e-6) + 1e-12);
}

class FlightHardCases : public ::testing::TestWithParam<Scheme> {};

TEST_P(FlightHardCases, ZeroSpinWithMagnusOnEqualsMagnusOff) {
  const Granule granule;
  State launch;
  launch.position_m = Vec3(0.0, 0.0, 0.8);
  launch.velocity_m_s = Vec3(20.0, 5.0, 2.0);
  launch.spin_rad_s = Vec3::Zero();
  const Settings s = settings_for(GetParam());
  const Landing with = fly_to_ground(granule, launch, 0.0, Air{}, kDrag | kMagnus | kSpinDecay, s);
  const Landing without = fly_to_ground(granule, launch, 0.0, Air{}, kDrag, s);
  expect_finite_landing(with);
  ASSERT_TRUE(with.landed);
  // The lift direction ω×v/|ω| has the limit 0 as ω → 0 and spin decay keeps ω = 0: a zero-spin launch
  // is flown by the drag-only instantiation, so the same path exactly.
  EXPECT_EQ(with.state.position_m, without.state.position_m);
  EXPECT_EQ(with.state.spin_rad_s, Vec3::Zero());
  expect_energy_bounded(launch, 0.0, with);
}

TEST_P(FlightHardCases, TinySpinIsContinuousWithZeroSpin) {
  const Granule granule;
  State launch;
  launch.position_m = Vec3(0.0, 0.0, 0.8);
  launch.velocity_m_s = Vec3(20.0, 5.0, 2.0);
  const Settings s = settings_for(GetParam());
  const Landing zero = fly_to_ground(granule, launch, 0.0, Air{}, kAllEffects, s);
  launch.spin_rad_s = Vec3(1e-300, -1e-300, 1e-300);  // denormal-scale spin: no 0/0 in the lift direction
  const Landing tiny = fly_to_ground(granule, launch, 0.0, Air{}, kAllEffects, s);
  expect_finite_landing(tiny);
  // A zero-spin launch flies without lift and spin decay (they act as zeros). RK4 takes the same fixed
  // steps either way; Dormand–Prince picks other steps once the spin equations leave its error norm, so
  // the paths agree to within its tolerance (rel 1e-6 of ~20 m), as in ZeroSpinWithMagnus above.
  const double tolerance_m = GetParam() == Scheme::kRk4 ? 1e-9 : 1e-4;
  EXPECT_NEAR((tiny.state.position_m - zero.state.position_m).norm(), 0.0, tolerance_m);
}

TEST_P(FlightHardCases, ZeroVelocityRelativeToAirWithSpin) {
  const Granule granule;
  const Settings s = settings_for(GetParam());
  // At rest in still air, spinning fast: v_rel = 0 at t = 0, so drag, C_D(Re = 0) and the Magnus
  // direction must all have finite limits.
  State at_rest;
  at_rest.position_m = Vec3(0.0, 0.0, 1.0);
  at_rest.spin_rad_s = Vec3(300.0, -200.0, 100.0);
  const Landing a = fly_to_ground(granule, at_rest, 0.0, Air{}, kAllEffects, s);
  expect_finite_landing(a);
  ASSERT_TRUE(a.landed);
  EXPECT_NEAR(a.state.position_m.z(), 0.0, 1e-9);
  EXPECT_GE(a.flight_time_s, std::sqrt(2.0 * 1.0 / kG) * (1.0 - 1e-9));  // drag only slows the fall
  expect_energy_bounded(at_rest, 0.0, a);

  // Carried by the wind at exactly the wind speed: v_rel = 0 with wind on.
  Air windy;
  windy.wind_m_s = Vec3(7.0, -3.0, 0.0);
  State drifting = at_rest;
  drifting.velocity_m_s = windy.wind_m_s;
  const Landing b = fly_to_ground(granule, drifting, 0.0, windy, kAllEffects, s);
  expect_finite_landing(b);
  ASSERT_TRUE(b.landed);
  EXPECT_GT(b.state.position_m.x(), 0.0);
}

TEST_P(FlightHardCases, ApexOfAVerticalThrowPassesThroughZeroVelocity) {
  const Granule granule;
  State up;
  up.position_m = Vec3(0.0, 0.0, 0.5);
  up.velocity_m_s = Vec3(0.0, 0.0, 10.0);
  up.spin_rad_s = Vec3(0.0, 0.0, 500.0);  // spin parallel to v: ω×v = 0 all the way
  const Landing l = fly_to_ground(granule, up, 0.0, Air{}, kAllEffects, settings_for(GetParam()));
  expect_finite_landing(l);
  ASSERT_TRUE(l.landed);
  EXPECT_NEAR(l.state.position_m.head<2>().norm(), 0.0, 1e-9);
  expect_energy_bounded(up, 0.0, l);
}

TEST_P(FlightHardCases, LaunchStraightDown) {
  const Granule granule;
  State down;
  down.position_m = Vec3(0.3, -0.2, 1.0);
  down.velocity_m_s = Vec3(0.0, 0.0, -25.0);
  const Landing l = fly_to_ground(granule, down, 0.0, Air{}, kAllEffects, settings_for(GetParam()));
  expect_finite_landing(l);
  ASSERT_TRUE(l.landed);
  EXPECT_DOUBLE_EQ(l.state.position_m.x(), 0.3);
  EXPECT_DOUBLE_EQ(l.state.position_m.y(), -0.2);
  EXPECT_NEAR(l.state.position_m.z(), 0.0, 1e-9);
  // Never faster than a drag-free throw (t >= h / sqrt(v0² + 2gh)); drag brakes it towards the terminal
  // speed (~10 m/s here) but never below it while falling, so it lands well before 1 m / 10 m/s.
  EXPECT_GE(l.flight_time_s, 1.0 / std::sqrt(25.0 * 25.0 + 2.0 * kG * 1.0) * (1.0 - 1e-9));
  EXPECT_LT(l.flight_time_s, 0.1);
  expect_energy_bounded(down, 0.0, l);

  // Launched downward from exactly the ground: landed at t = 0 (documented precondition).
  down.position_m.z() = 0.0;
  const Landing at_ground = fly_to_ground(granule, down, 0.0, Air{}, kAllEffects, settings_for(GetParam()));
  EXPECT_TRUE(at_ground.landed);
  EXPECT_EQ(at_ground.flight_time_s, 0.0);
}

TEST_P(FlightHardCases, WindStrongerThanTheLaunch) {
  const Granule granule{1e-3, 1000.0};  // light granule: the wind wins
  State launch;
  launch.position_m = Vec3(0.0, 0.0, 1.0);
  launch.velocity_m_s = Vec3(5.0, 0.0, 0.0);
  for (double wind_x : {40.0, -40.0}) {
    Air air;
    air.wind_m_s = Vec3(wind_x, 0.0, 0.0);
    const Landing l = fly_to_ground(granule, launch, 0.0, air, kDrag | kWind, settings_for(GetParam()));
    expect_finite_landing(l);
    ASSERT_TRUE(l.landed) << "wind " << wind_x;
    // Without spin the drag only pulls v_x towards the wind speed: never past it.
    if (wind_x > 0.0) {
      EXPECT_GT(l.state.velocity_m_s.x(), 5.0);
      EXPECT_LE(l.state.velocity_m_s.x(), wind_x * (1.0 + 1e-9));
    } else {
      EXPECT_LT(l.state.velocity_m_s.x(), 5.0);
      EXPECT_GE(l.state.velocity_m_s.x(), wind_x * (1.0 + 1e-9));
      EXPECT_LT(l.state.position_m.x(), 0.0);  // blown back behind the launch point
    }
  }
}

// Fixed-step RK4 is refused exactly when the step is above its explicit stability bound
// (rk4_stable_step_bound_s: 2.78 × the stiffest drag/spin-decay relaxation time), and the message says so;
// every flight that is not refused — all of Dormand–Prince's — is finite and energy-bounded.
TEST_P(FlightHardCases, ExtremeDiametersAndDensitiesStayFiniteAndBounded) {
  State launch;
  launch.position_m = Vec3(0.0, 0.0, 0.8);
  launch.velocity_m_s = Vec3(30.0, 10.0, 3.0);
  launch.spin_rad_s = Vec3(50.0, -80.0, 400.0);
  Settings s = settings_for(GetParam());
  s.max_steps = 200'000;  // the dust cases may not land in time: they must stop, not run away
  int refused = 0;
  for (double d : {1e-5, 1e-4, 3e-3, 2e-2, 1e-1}) {
    for (double rho : {10.0, 300.0, 1500.0, 8000.0, 2e4}) {
      SCOPED_TRACE(::testing::Message() << "d = " << d << " m, rho = " << rho << " kg/m3");
      const Granule granule{d, rho};
      const bool above_bound =
          GetParam() == Scheme::kRk4 && s.dt_s > rk4_stable_step_bound_s(granule, launch, 0.0, Air{}, kAllEffects, s);
      if (d >= 3e-3) {
        EXPECT_FALSE(above_bound) << "a fertiliser-sized granule is within RK4's bound at 1 ms";
      }
      try {
        const Landing l = fly_to_ground(granule, launch, 0.0, Air{}, kAllEffects, s);
        EXPECT_FALSE(above_bound) << "a step above RK4's stable bound was taken";
        expect_finite_landing(l);
        if (l.landed) {
          EXPECT_NEAR(l.state.position_m.z(), 0.0, 1e-9);
          expect_energy_bounded(launch, 0.0, l);
        }
      } catch (const std::invalid_argument& e) {
        ++refused;
        EXPECT_TRUE(above_bound) << "a valid granule was refused: " << e.what();
        EXPECT_NE(std::string(e.what()).find("stable bound"), std::string::npos) << e.what();
      }
    }
  }
  // At dt = 1 ms only dust (d <= 0.1 mm) is beyond RK4, and only RK4 refuses.
  if (GetParam() == Scheme::kRk4) {
    EXPECT_GT(refused, 0);
  } else {
    EXPECT_EQ(refused, 0);
  }
}

// The bound: for a granule at rest in still air with only drag on it is 2.78 × the Stokes relaxation time
// ρ d²/(18 μ); with spin decay on it is never larger; it shrinks as the flight can reach higher speeds.
TEST(FlightRk4Bound, MatchesTheStokesRelaxationTimeAndOrdersCorrectly) {
  const Air air;
  const Granule dust{1e-4, 1000.0};
  State at_rest;  // on the ground, at rest: relative speed 0 for the whole "flight"
  Settings s;
  const double tau_stokes = dust.density_kg_m3 * dust.diameter_m * dust.diameter_m / (18.0 * air.viscosity_pa_s);
  EXPECT_NEAR(rk4_stable_step_bound_s(dust, at_rest, 0.0, air, kDrag, s), kRk4StabilityLimit * tau_stokes,
              1e-12 * tau_stokes);
  EXPECT_LE(rk4_stable_step_bound_s(dust, at_rest, 0.0, air, kAllEffects, s),
            rk4_stable_step_bound_s(dust, at_rest, 0.0, air, kDrag, s));
  State thrown = at_rest;
  thrown.position_m = Vec3(0.0, 0.0, 1.0);
  thrown.velocity_m_s = Vec3(30.0, 0.0, 0.0);
  EXPECT_LT(rk4_stable_step_bound_s(dust, thrown, 0.0, air, kDrag, s), rk4_stable_step_bound_s(dust, at_rest, 0.0, air, kDrag, s));
  EXPECT_EQ(rk4_stable_step_bound_s(dust, thrown, 0.0, air, kMagnus, s), HUGE_VAL);  // no stiff term
  // A 3 mm fertiliser granule at 30 m/s: the bound is far above any step in use (about 0.5 s).
  EXPECT_GT(rk4_stable_step_bound_s(Granule{3e-3, 1800.0}, thrown, 0.0, air, kAllEffects, s), 0.1);
}

// Just below the bound RK4 is stable: the dust that is refused at 1 ms flies finite and energy-bounded
// at 0.9 × its bound, with and without spin decay.
TEST(FlightRk4Bound, JustBelowTheBoundTheDustStaysFiniteAndBounded) {
  State launch;
  launch.position_m = Vec3(0.0, 0.0, 0.8);
  launch.velocity_m_s = Vec3(30.0, 10.0, 3.0);
  launch.spin_rad_s = Vec3(50.0, -80.0, 400.0);
  for (EffectSet effects : {EffectSet{kDrag}, kAllEffects}) {
    for (double d : {1e-5, 1e-4}) {
      for (double rho : {10.0, 1500.0}) {
        SCOPED_TRACE(::testing::Message() << "effects " << effects << ", d = " << d << " m, rho = " << rho);
        const Granule granule{d, rho};
        Settings s;
        s.scheme = Scheme::kRk4;
        s.max_time_s = 2.0;
        s.max_steps = 2'000'000;
        s.dt_s = 0.9 * rk4_stable_step_bound_s(granule, launch, 0.0, Air{}, effects, s);
        const Landing l = fly_to_ground(granule, launch, 0.0, Air{}, effects, s);
        expect_finite_landing(l);
        expect_energy_bounded(launch, 0.0, l);
        EXPECT_GE(l.state.position_m.z(), 0.0);
        s.dt_s *= 1.2;  // 1.08 × the bound: refused
        EXPECT_THROW(fly_to_ground(granule, launch, 0.0, Air{}, effects, s), std::invalid_argument);
      }
    }
  }
}

// Re → 0: a 1 µm particle in air 1000× more viscous. The drag relaxation time ρd²/(18μ) ≈ 3e-12 s is
// nine orders below the step. RK4 refuses the step naming its stable bound (before, it diverged to
// |v| ≈ 1e25 m/s); Dormand–Prince adapts its step and stops finite, hovering, at max_time_s.
TEST_P(FlightHardCases, StokesLimitWithAStepFarAboveTheRelaxationTime) {
  State launch;
  launch.position_m = Vec3(0.0, 0.0, 1.0);
  launch.velocity_m_s = Vec3(10.0, 0.0, 0.0);
  Air viscous;
  viscous.viscosity_pa_s = 1.81e-2;
  Settings s = settings_for(GetParam());
  s.max_steps = 20'000;
  s.max_time_s = 1.0;
  if (GetParam() == Scheme::kRk4) {
    try {
      (void)fly_to_ground(Granule{1e-6, 1000.0}, launch, 0.0, viscous, kAllEffects, s);
      ADD_FAILURE() << "RK4 took a step 1e8 x its relaxation time";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("stable bound"), std::string::npos) << e.what();
    }
    // fly_batch refuses it too, before any thread starts, naming the element.
    const std::vector<Granule> granules{Granule{3e-3, 1800.0}, Granule{1e-6, 1000.0}};
    const std::vector<State> launches{launch, launch};
    std::vector<Landing> out(2);
    try {
      fly_batch(granules, launches, 0.0, viscous, kAllEffects, s, out, 1);
      ADD_FAILURE() << "fly_batch took the unstable step";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("element 1"), std::string::npos) << e.what();
    }
    return;
  }
  const Landing l = fly_to_ground(Granule{1e-6, 1000.0}, launch, 0.0, viscous, kAllEffects, s);
  expect_finite_landing(l);
  EXPECT_FALSE(l.landed);  // terminal speed ≈ 3e-8 m/s: it cannot fall 1 m in 1 s
  EXPECT_GT(l.state.position_m.z(), 0.0);
  EXPECT_LE(l.state.velocity_m_s.norm(), 10.0 * (1.0 + 1e-9));
}

TEST_P(FlightHardCases, SameInputSameResultAndAnyThreadCount) {
  std::vector<State> launches(64);
  for (std::size_t i = 0; i < launches.size(); ++i) {
    const double a = 0.1 * static_cast<double>(i);
    launches[i].position_m = Vec3(0.29 * std::cos(a), 0.29 * std::sin(a), 0.8);
    launches[i].velocity_m_s = Vec3(-25.0 * std::sin(a), 25.0 * std::cos(a), 1.0);
    launches[i].spin_rad_s = Vec3(0.0, 0.0, static_cast<double>(i) * 10.0);
  }
  const std::vector<Granule> granule{Granule{}};
  Air air;
  air.wind_m_s = Vec3(3.0, -1.0, 0.0);
  const Settings s = settings_for(GetParam());
  std::vector<Landing> one(launches.size()), two(launches.size()), again(launches.size());
  fly_batch(granule, launches, 0.0, air, kAllEffects, s, one, 1);
  fly_batch(granule, launches, 0.0, air, kAllEffects, s, two, 2);
  fly_batch(granule, launches, 0.0, air, kAllEffects, s, again, 1);
  for (std::size_t i = 0; i < launches.size(); ++i) {
    expect_finite_landing(one[i]);
    EXPECT_EQ(one[i].state.position_m, two[i].state.position_m) << i;
    EXPECT_EQ(one[i].state.position_m, again[i].state.position_m) << i;
    EXPECT_EQ(one[i].steps, again[i].steps) << i;
  }
}

TEST_P(FlightHardCases, NonFiniteInputsAreRefusedByName) {
  const double bad[] = {std::nan(""), HUGE_VAL, -HUGE_VAL};
  const Settings s = settings_for(GetParam());
  for (double b : bad) {
    State launch;
    launch.position_m = Vec3(0.0, 0.0, 1.0);
    State p = launch;
    p.position_m.x() = b;
    EXPECT_THROW(fly_to_ground(Granule{}, p, 0.0, Air{}, kAllEffects, s), std::invalid_argument);
    State v = launch;
    v.velocity_m_s.y() = b;
    EXPECT_THROW(fly_to_ground(Granule{}, v, 0.0, Air{}, kAllEffects, s), std::invalid_argument);
    State w = launch;
    w.spin_rad_s.z() = b;
    EXPECT_THROW(fly_to_ground(Granule{}, w, 0.0, Air{}, kAllEffects, s), std::invalid_argument);
    EXPECT_THROW(fly_to_ground(Granule{b, 1500.0}, launch, 0.0, Air{}, kAllEffects, s), std::invalid_argument);
    EXPECT_THROW(fly_to_ground(Granule{3e-3, b}, launch, 0.0, Air{}, kAllEffects, s), std::invalid_argument);
    EXPECT_THROW(fly_to_ground(Granule{}, launch, b, Air{}, kAllEffects, s), std::invalid_argument);
    Air air;
    air.wind_m_s.x() = b;
    EXPECT_THROW(fly_to_ground(Granule{}, launch, 0.0, air, kAllEffects, s), std::invalid_argument);
    Air dense;
    dense.density_kg_m3 = b;
    EXPECT_THROW(fly_to_ground(Granule{}, launch, 0.0, dense, kAllEffects, s), std::invalid_argument);
    Settings bad_dt = s;
    bad_dt.dt_s = b;
    EXPECT_THROW(fly_to_ground(Granule{}, launch, 0.0, Air{}, kAllEffects, bad_dt), std::invalid_argument);
  }
}

std::string scheme_name(const ::testing::TestParamInfo<Scheme>& param) {
  return param.param == Scheme::kRk4 ? "Rk4" : "DormandPrince";
}
INSTANTIATE_TEST_SUITE_P(Schemes, FlightHardCases, ::testing::Values(Scheme::kRk4, Scheme::kDormandPrince45),
                         scheme_name);

}  // namespace
}  // namespace spread::flight
