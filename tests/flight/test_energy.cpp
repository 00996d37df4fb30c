// With drag on and no wind, ½mv² + ½Iω² + m g z never rises along a trajectory: drag dissipates, Magnus
// is perpendicular to v (no work), spin decay only removes rotational energy. Checked after every step
// through the StepObserver hook, for both integrators and all lift models.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "libspread/physics/flight/flight.hpp"
#include "tests/flight/flight_test_support.hpp"

namespace spread::flight {
namespace {

struct EnergyTrack {
  double mass_kg = 0.0;
  double inertia_kg_m2 = 0.0;
  double gravity_m_s2 = kStandardGravity_m_s2;
  double previous_j = INFINITY;
  double worst_rise_j = -INFINITY;  // max over steps of E_n − E_{n−1}
  int samples = 0;
};

void on_step(void* context, double /*time_s*/, const State& s) {
  auto& track = *static_cast<EnergyTrack*>(context);
  const double energy = 0.5 * track.mass_kg * s.velocity_m_s.squaredNorm() +
                        0.5 * track.inertia_kg_m2 * s.spin_rad_s.squaredNorm() +
                        track.mass_kg * track.gravity_m_s2 * s.position_m.z();
  if (track.samples > 0) track.worst_rise_j = std::max(track.worst_rise_j, energy - track.previous_j);
  track.previous_j = energy;
  ++track.samples;
}

TEST(Energy, NeverRisesWithDragAndNoWind) {
  const Granule g = test::typical_granule();
  State steep = test::typical_launch();
  steep.velocity_m_s = Vec3(10.0, 5.0, 25.0);
  steep.spin_rad_s = Vec3(-800.0, 600.0, 100.0);
  for (const State& launch : {test::typical_launch(), steep}) {
    for (LiftModel lift : {LiftModel::kSmoothSaturating, LiftModel::kOesterleBuiDinh}) {
      for (Settings settings : {test::rk4(1e-3), test::rk4(2e-2), Settings{}}) {
        for (EffectSet effects : {EffectSet{kDrag}, test::kDiscEffects, EffectSet{kDrag | kMagnus}}) {
          settings.lift = lift;
          EnergyTrack track;
          track.mass_kg = g.density_kg_m3 * kPi * std::pow(g.diameter_m, 3) / 6.0;
          track.inertia_kg_m2 = track.mass_kg * g.diameter_m * g.diameter_m / 10.0;
          const Landing landing =
              fly_to_ground(g, launch, 0.0, Air{}, effects, settings, StepObserver{&on_step, &track});
          ASSERT_TRUE(landing.landed);
          EXPECT_GT(track.samples, 3);
          EXPECT_LT(track.worst_rise_j, 0.0) << "effects " << effects_to_string(effects) << " scheme "
                                            << static_cast<int>(settings.scheme) << " dt " << settings.dt_s;
        }
      }
    }
  }
}

}  // namespace
}  // namespace spread::flight
