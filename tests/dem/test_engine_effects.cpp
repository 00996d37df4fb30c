// The engine's DEM effects (EngineParams::effects, registry bits): each contact effect is a real switch,
// an effect that is off is not run, and what cannot run is refused with the reason.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/force_variants.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/physics/flight/flight.hpp"

using namespace spread;
using namespace spread::dem;

namespace {
constexpr double kRadius_m = 1e-3;

Material granule() {
  Material m;
  m.name = "granule";
  m.density_kg_m3 = 1500.0;
  return m;
}

// The floor's material: the granule's, rigid.
Material rigid_floor(Material m) {
  m.name = "floor";
  m.rigid = true;
  return m;
}

// A fixed floor at z = 0 of material 1.
WallSet floor_walls() {
  WallGroup g;
  g.pieces.push_back(make_plane(Vec3::Zero(), Vec3::UnitZ()));
  g.material = 1;
  WallSet walls;
  walls.groups.push_back(g);
  return walls;
}

// A granule released just above a fixed floor (z = 0), run for 0.1 s under gravity; returns its height.
double height_after_drop_m(effect::EffectSet effects) {
  EngineParams ep;
  ep.effects = effects;
  ep.min_particle_radius_m = kRadius_m;
  ep.impact_speed_m_s = 1.0;
  DemEngine e({granule(), rigid_floor(granule())}, {}, floor_walls(), ep);
  e.add_particle(Vec3(0.0, 0.0, 1.2 * kRadius_m), Vec3::Zero(), kRadius_m, 0);
  e.run_until(0.1);
  return e.particles().z[0];
}

std::string refusal(const EngineParams& ep) {
  try {
    DemEngine e({granule()}, {}, WallSet{}, ep);
  } catch (const std::invalid_argument& ex) {
    return ex.what();
  }
  return "";
}
}  // namespace

TEST(DemEngineEffects, WallContactOffLetsAGranuleFallThroughTheFloor) {
  // On: it settles on the floor (centre one radius up, less the static overlap). Off: free fall,
  // z = 1.2 r − g t²/2 ≈ −4.9 cm after 0.1 s.
  const double on_m = height_after_drop_m(effect::kWallContact | effect::kRotation);
  EXPECT_NEAR(on_m, kRadius_m, 0.05 * kRadius_m);
  const double off_m = height_after_drop_m(effect::kRotation);
  EXPECT_NEAR(off_m, 1.2 * kRadius_m - 0.5 * kStandardGravity_m_s2 * 0.1 * 0.1, 1e-3);
}

TEST(DemEngineEffects, ParticleContactOffRunsNoPairSearchAndNoPairForce) {
  // Two overlapping granules, no gravity, no walls: with particle_contact they push apart; without it no
  // pair list is built, the pair pass is not entered, and they stay at rest.
  auto run = [](effect::EffectSet effects, std::uint64_t& pair_list_builds) {
    EngineParams ep;
    ep.effects = effects;
    ep.min_particle_radius_m = kRadius_m;
    ep.impact_speed_m_s = 1.0;
    ep.gravity_m_s2 = Vec3::Zero();
    DemEngine e({granule()}, {}, WallSet{}, ep);
    e.add_particle(Vec3::Zero(), Vec3::Zero(), kRadius_m, 0);
    e.add_particle(Vec3(1.9 * kRadius_m, 0.0, 0.0), Vec3::Zero(), kRadius_m, 0);
    for (int i = 0; i < 50; ++i) e.step();
    pair_list_builds = e.stats().pair_list_builds;
    return e.particles().vx[1];
  };
  std::uint64_t builds = 0;
  EXPECT_GT(run(effect::kParticleContact | effect::kWallContact | effect::kRotation, builds), 0.0);
  EXPECT_GT(builds, 0u);
  EXPECT_EQ(run(effect::kWallContact | effect::kRotation, builds), 0.0);
  EXPECT_EQ(builds, 0u);
}

TEST(DemEngineEffects, RefusesWhatCannotRunAndSaysWhy) {
  EngineParams ep;
  ep.min_particle_radius_m = kRadius_m;
  ep.effects |= effect::kDrag;
  EXPECT_NE(refusal(ep).find("'drag' not a DEM effect"), std::string::npos) << refusal(ep);
  ep.effects = effect::kDemEffects & effect::kDefault;
  ep.effects |= effect::kRolling;  // the law has no rolling model
  EXPECT_NE(refusal(ep).find("contact_law.rolling is 'none'"), std::string::npos) << refusal(ep);
  ep.effects &= ~effect::kRolling;
  ep.contact_law = with_rolling(kHertzThorntonLaw, RollingModel::kConstantTorque);
  EXPECT_NE(refusal(ep).find("the 'rolling' effect is off"), std::string::npos) << refusal(ep);
  ep.effects |= effect::kRolling;
  EXPECT_EQ(refusal(ep), "");
}

TEST(DemEngineEffects, SceneEffectsBecomeTheEngineEffects) {
  const std::string disc = std::string(SPREAD_SOURCE_DIR) + "/scenes/case1.toml";
  const SimulationConfig plain = config_from_scene(scene::load_scene_file(disc));
  EXPECT_EQ(plain.engine.effects, effect::kParticleContact | effect::kWallContact | effect::kRotation);
  const SimulationConfig rolling = config_from_scene(scene::load_scene_file(
      disc, {"effects.enabled=[\"wall_contact\",\"rotation\",\"rolling\",\"drag\"]"}));
  EXPECT_EQ(rolling.engine.effects, effect::kWallContact | effect::kRotation | effect::kRolling);
  // The engine honours a scene without walls; the disc scene does not run one (nothing holds the granules).
  try {
    config_from_scene(scene::load_scene_file(disc, {"effects.enabled=[\"particle_contact\",\"rotation\",\"drag\"]"}));
    ADD_FAILURE() << "a disc scene without wall_contact was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("nothing would hold the particles"), std::string::npos) << e.what();
  }
}

namespace {

// A small pile thrown sideways onto a floor, with friction and rolling resistance: every DEM effect acts
// in it. Returns every particle's position and velocity after 15 ms; `inspect` sees the engine after each step.
std::vector<double> pile_state(effect::EffectSet effects, const std::function<void(const DemEngine&)>& inspect = {}) {
  Material p = granule();
  p.friction_particle = p.friction_wall = 0.4;
  p.restitution = 0.5;
  p.youngs_modulus_pa = 5e7;
  p.rolling_friction = 0.1;
  EngineParams ep;
  ep.effects = effects;
  ep.min_particle_radius_m = kRadius_m;
  ep.max_particle_radius_m = 1.5 * kRadius_m;
  ep.impact_speed_m_s = 2.0;
  // As a scene maps it (scene_config.cpp): the rolling effect names its model.
  if ((effects & effect::kRolling) != 0) ep.contact_law.rolling = RollingModel::kConstantTorque;
  DemEngine e({p, rigid_floor(p)}, {}, floor_walls(), ep);
  int k = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int l = 0; l < 2; ++l, ++k) {
        e.add_particle(Vec3(i * 3.2e-3 + 1e-4 * (k % 3), j * 3.2e-3, 1.6e-3 + l * 3.2e-3),
                       Vec3(0.3 + 0.01 * (k % 5), 0.0, -0.5), kRadius_m * (1.0 + 0.05 * (k % 4)), 0);
      }
    }
  }
  while (e.time_s() + 0.5 * e.dt_s() < 0.015) {  // run_until(0.015), step by step
    e.step();
    if (inspect) inspect(e);
  }
  std::vector<double> state;
  const ParticleArrays& q = e.particles();
  for (std::size_t i = 0; i < q.size(); ++i) {
    for (double v : {q.x[i], q.y[i], q.z[i], q.vx[i], q.vy[i], q.vz[i]}) state.push_back(v);
  }
  return state;
}

// A spinning granule thrown into a crosswind from 1 m: its landing.
flight::Landing thrown_granule(flight::EffectSet effects) {
  flight::State launch;
  launch.position_m = Vec3(0.0, 0.0, 1.0);
  launch.velocity_m_s = Vec3(20.0, 0.0, 5.0);
  launch.spin_rad_s = Vec3(0.0, 200.0, 300.0);
  flight::Air air;
  air.wind_m_s = Vec3(0.0, 3.0, 0.0);
  return flight::fly_to_ground(flight::Granule{}, launch, 0.0, air, effects, flight::Settings{});
}

}  // namespace

// Every row of the effect registry is evaluated: with everything else on, turning the effect off (and
// those that need it) changes a DEM or a flight result. A row added without an evaluator fails here.
TEST(EffectRegistry, EveryEffectChangesItsResult) {
  for (const effect::Effect& e : effect::kRegistry) {
    effect::EffectSet off = e.bit;
    for (const effect::Effect& other : effect::kRegistry) {
      if ((other.requires_effects & e.bit) != 0) off |= other.bit;
    }
    if (e.domain == effect::Domain::kDem) {
      const effect::EffectSet all = effect::kDemEffects;
      EXPECT_NE(pile_state(all), pile_state(all & ~off)) << e.name << " changes nothing in a pile";
    } else {
      const flight::EffectSet all = flight::kAllEffects;
      const flight::Landing with = thrown_granule(all), without = thrown_granule(all & ~off);
      ASSERT_TRUE(with.landed && without.landed) << e.name;
      EXPECT_GT((with.state.position_m - without.state.position_m).norm(), 1e-3) << e.name << " moves no landing";
    }
  }
}

namespace {

// What shows that a DEM effect's work was not done, in an engine that ran with the effect off: for an effect
// that shapes the passes, passes instantiated without it (and for rotation no spin arrays either); for those
// that decide what runs, no pair list (particle_contact), no wall contact recorded in any particle's slots
// although the pile lies on a floor (wall_contact), a law without a rolling model (rolling). Each must also
// be false with the effect on, so that it witnesses something.
bool skipped(effect::EffectSet bit, const DemEngine& e, bool& known) {
  known = true;
  const ParticleArrays& p = e.particles();
  if ((kPassEffects & bit) != 0) return (e.pass_effects() & bit) == 0 && (bit != effect::kRotation || (!p.with_spin && p.wx.empty()));
  if (bit == effect::kParticleContact) return e.stats().pair_list_builds == 0 && e.pair_count() == 0;
  if (bit == effect::kWallContact) {
    for (std::uint32_t key : p.wall_key)
      if (key != 0) return false;
    return true;
  }
  if (bit == effect::kRolling) return e.params().contact_law.rolling == RollingModel::kNone;
  known = false;
  return false;
}

}  // namespace

// An effect that is off costs nothing: its work is not done at all (not done and thrown away). Each DEM row
// of the registry needs its witness in skipped(): a row added without one fails here.
TEST(EffectRegistry, EveryDemEffectOffIsNotRun) {
  for (const effect::Effect& e : effect::kRegistry) {
    if (e.domain != effect::Domain::kDem) continue;
    effect::EffectSet off = e.bit;
    for (const effect::Effect& other : effect::kRegistry) {
      if ((other.requires_effects & e.bit) != 0) off |= other.bit;
    }
    // At every step with the effect off; not at every step with it on.
    bool known = false, skipped_on = true, skipped_off = true;
    pile_state(effect::kDemEffects, [&](const DemEngine& engine) { skipped_on &= skipped(e.bit, engine, known); });
    ASSERT_TRUE(known) << e.name << ": no witness that it is not run when off (add one to skipped())";
    pile_state(effect::kDemEffects & ~off, [&](const DemEngine& engine) { skipped_off &= skipped(e.bit, engine, known); });
    EXPECT_TRUE(skipped_off) << e.name << " is off, but its work was done";
    EXPECT_FALSE(skipped_on) << e.name << " is on, but the witness says its work was not done";
  }
}
