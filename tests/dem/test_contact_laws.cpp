// Golden force histories of the composed contact laws, one per force variant a scene reaches
// (force_variants.hpp): a fixed sequence of a sphere pair and a sphere on a spinning floor, 300 steps,
// compared bit for bit (a hash of every force and torque) and by its per-particle sums against the values
// the fused laws gave before the laws were composed from sub-models (HertzThornton and
// LinearSpringDashpot of that time, recorded with the same scenario). Then the sub-models that no
// scene reaches, and the start-up checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/force_variants.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/io/scene/scene.hpp"

using namespace spread;
using namespace spread::dem;

namespace {

struct GoldenSums { std::uint64_t hash = 14695981039346656037ull; double sums[4][6] = {}; int steps = 0; double dt_s = 0.0; };
void golden_mix(GoldenSums& g, double v) {
  std::uint64_t bits; std::memcpy(&bits, &v, sizeof bits);
  for (int b = 0; b < 8; ++b) { g.hash ^= (bits >> (8 * b)) & 0xffu; g.hash *= 1099511628211ull; }
}
// Four spheres and a spinning floor: A and B (one material, unequal radii: per-contact coefficients)
// meet obliquely in the air with spin; D (second material, D and C equal: the material-pair table)
// falls on C, which slides and spins on the floor. 300 steps; every force and torque is hashed bitwise
// and summed per particle.
GoldenSums golden_run(bool hertz, bool rotation, bool rolling) {
  Material a; a.name = "a"; a.friction_particle = a.friction_wall = 0.4; a.restitution = 0.6; a.youngs_modulus_pa = 5e7; a.poisson_ratio = 0.25; a.rolling_friction = 0.05;
  Material c = a; c.name = "c"; c.friction_particle = c.friction_wall = 0.5; c.restitution = 0.4; c.youngs_modulus_pa = 8e7; c.poisson_ratio = 0.3; c.rolling_friction = 0.1;
  Material w = a; w.name = "floor"; w.rigid = true; w.friction_wall = 0.3;
  WallGroup floor;
  floor.pieces.push_back(make_plane(Vec3::Zero(), Vec3::UnitZ()));
  floor.material = 2;
  floor.angular_velocity_rad_s = 3.0;
  WallSet walls;
  walls.groups.push_back(floor);
  EngineParams ep;
  ep.contact_law = hertz ? kHertzThorntonLaw : kLinearSpringDashpotLaw;
  if (rolling) {
    ep.contact_law.rolling = RollingModel::kConstantTorque;
    ep.effects |= spread::effect::kRolling;
  }
  if (!rotation) ep.effects &= ~spread::effect::kRotation;
  ep.linear.normal_stiffness_n_m = 2e3;
  ep.linear.tangential_ratio = 2.0 / 7.0;
  ep.integrator = Integrator::kVelocityVerlet;
  ep.min_particle_radius_m = 1.8e-3;
  ep.max_particle_radius_m = 2.0e-3;
  ep.impact_speed_m_s = 1.0;
  ep.threads = 1;
  DemEngine e({a, c, w}, {}, walls, ep);
  e.add_particle(Vec3(0.0, 0.0, 0.05), Vec3(0.5, 0.0, 0.0), 2.0e-3, 0, Vec3(0.0, 40.0, 10.0));
  e.add_particle(Vec3(4.0e-3, 1.2e-3, 0.05), Vec3(-0.5, 0.1, 0.0), 1.8e-3, 0, Vec3(-20.0, 0.0, 0.0));
  e.add_particle(Vec3(0.02, 0.0, 1.95e-3), Vec3(0.2, 0.05, 0.0), 2.0e-3, 1, Vec3(0.0, 0.0, 30.0));
  e.add_particle(Vec3(0.0205, 0.0003, 6.2e-3), Vec3(0.0, 0.0, -0.4), 2.0e-3, 1, Vec3(15.0, 0.0, 0.0));
  GoldenSums g;
  g.dt_s = e.dt_s();
  for (int s = 0; s < 300; ++s) {
    e.step();
    const auto& p = e.particles();
    for (std::size_t i = 0; i < 4; ++i) {
      const double v[6] = {p.fx[i], p.fy[i], p.fz[i], rotation ? p.tx[i] : 0.0, rotation ? p.ty[i] : 0.0, rotation ? p.tz[i] : 0.0};
      for (int k = 0; k < 6; ++k) { golden_mix(g, v[k]); g.sums[i][k] += v[k]; }
    }
    ++g.steps;
  }
  return g;
}

struct Golden {
  bool hertz, rotation, rolling;
  std::uint64_t hash;
  double dt_s;
  double sums[4][6];
};
// Recorded before the composition (the named laws), same scenario; hexadecimal floats are exact.
constexpr Golden kGolden[] = {
{true, false, false, 0x2dba9144154277a2ull, 0x1.4b66115ea1a32p-18,
 {{-0x1.aad5ec594f547p+2, 0x1.49e7cb9fb3af9p-3, 0x0p+0, 0x0p+0, 0x0p+0, 0x0p+0},
  {0x1.aad5ec594f547p+2, -0x1.49e7cb9fb3af9p-3, 0x0p+0, 0x0p+0, 0x0p+0, 0x0p+0},
  {-0x1.e9f66dfbc3855p+0, -0x1.5aea5ae32cb79p-2, -0x1.15817b5d4d082p+0, 0x0p+0, 0x0p+0, 0x0p+0},
  {0x1.53df3ceb18e5bp-3, 0x1.b47b9a225dd3dp-2, 0x1.20744209a2a4p+3, 0x0p+0, 0x0p+0, 0x0p+0}}},
{true, true, false, 0x3340e3ec4bcf01d5ull, 0x1.4b66115ea1a32p-18,
 {{-0x1.82053fb1ebf35p+2, -0x1.a28fe3efd7463p+0, 0x1.9e7e701a570adp-4, 0x1.0d5780f29b047p-14, -0x1.86cba23edc19ap-13, 0x1.e14c70b303d3cp-11},
  {0x1.82053fb1ebf35p+2, 0x1.a28fe3efd7463p+0, -0x1.9e7e701a570adp-4, 0x1.e48c9701e7f0ep-15, -0x1.5f85a3ac3c325p-13, 0x1.b0ed1a5515f65p-11},
  {-0x1.0367ae1ea8efdp+1, -0x1.089e1005d41eap-1, -0x1.10070c87ce782p+0, -0x1.113cdfb7cc201p-13, 0x1.ecbb088f4d85bp-11, 0x1.e0fc375664d8ap-15},
  {0x1.4f1b56f2aacb5p+0, 0x1.1b042016745c1p-1, 0x1.1fc4f42ef2d1ep+3, -0x1.a47095a70715cp-13, -0x1.e4478044ac85fp-12, 0x1.e0fc375664d8ap-15}}},
{true, true, true, 0xf9971aee211fc5f9ull, 0x1.4b66115ea1a32p-18,
 {{-0x1.8249d3fa665p+2, -0x1.9f8f4ad370b6p+0, 0x1.e65ab248d79a1p-4, -0x1.53660fad2b50cp-17, -0x1.dfbe07f2ea8f6p-12, 0x1.19592d7877777p-10},
  {0x1.8249d3fa665p+2, 0x1.9f8f4ad370b6p+0, -0x1.e65ab248d79a1p-4, 0x1.42ed5491f7c07p-13, 0x1.5ceac65238d06p-15, 0x1.7807062f5987p-11},
  {-0x1.25b4d0a5a1fb9p+1, -0x1.f7546ff8c54e6p-2, -0x1.0761a32fb8a88p+0, -0x1.08d58978f3853p-14, 0x1.a61506a5b63e4p-13, -0x1.21acb846ef2edp-12},
  {0x1.3614bbd3ae90cp+0, 0x1.176d582b0f1dep-1, 0x1.1eb04703f017fp+3, -0x1.38d3db38c6f51p-12, 0x1.91d895b00221p-12, 0x1.338fe83233bacp-14}}},
{false, false, false, 0x2e1bc12fa1d86d28ull, 0x1.f8793f736aeddp-17,
 {{-0x1.0f91b6f07c699p+1, -0x1.72f56e5bb799fp-3, 0x0p+0, 0x0p+0, 0x0p+0, 0x0p+0},
  {0x1.0f91b6f07c699p+1, 0x1.72f56e5bb799fp-3, 0x0p+0, 0x0p+0, 0x0p+0, 0x0p+0},
  {-0x1.2ffde022b875ep-1, 0x1.ff0d7c4ff87adp-10, 0x1.4e5315cb8bc73p-3, 0x0p+0, 0x0p+0, 0x0p+0},
  {0x1.9c46fdf894ca1p-3, 0x1.2ff8beecac268p-3, 0x1.a1fa95421e08p+0, 0x0p+0, 0x0p+0, 0x0p+0}}},
{false, true, false, 0xe48e73cb0d3c5e6dull, 0x1.f8793f736aeddp-17,
 {{-0x1.01f5971b8baa9p+1, -0x1.e0c5aa727fcbp-2, 0x1.a495276139513p-5, 0x1.18e60b15cfa9fp-15, -0x1.888dbf24e26b8p-14, 0x1.ece8d2412aae1p-12},
  {0x1.01f5971b8baa9p+1, 0x1.e0c5aa727fcbp-2, -0x1.a495276139513p-5, 0x1.f8dc3a72579e5p-16, -0x1.60c5c31dce0dap-14, 0x1.baf42a0acfa59p-12},
  {-0x1.cc6bf795ce49ep-2, -0x1.b55e88404d3efp-6, 0x1.3eea3d1413e9ap-3, 0x1.565e5935caf2p-15, 0x1.d49c4dc88704cp-13, 0x1.34ccc133f54dep-16},
  {0x1.07b027a792bfdp-2, 0x1.47c677bc0b74p-4, 0x1.a628120106aafp+0, -0x1.11e5f45a928f6p-14, -0x1.48e893b2312ecp-13, 0x1.34ccc133f54dep-16}}},
{false, true, true, 0x38e9ce3071f722b0ull, 0x1.f8793f736aeddp-17,
 {{-0x1.021244328c1p+1, -0x1.de527f3d7d9adp-2, 0x1.d07fc4dd1b388p-5, 0x1.2e1bd218a22dep-17, -0x1.7989a7134263ep-13, 0x1.0e5a6a308b55cp-11},
  {0x1.021244328c1p+1, 0x1.de527f3d7d9adp-2, -0x1.d07fc4dd1b388p-5, 0x1.0190ca6ad1a9p-14, -0x1.135147563e18ap-16, 0x1.95269a8336052p-12},
  {-0x1.266c66facc3f4p-1, -0x1.0de48502f86cdp-6, 0x1.4e6b7e97fa1e8p-3, 0x1.4f19b01fe76f2p-15, 0x1.26dab96b7bbd9p-13, -0x1.14783a20ec7a8p-13},
  {0x1.0533e48e9d92bp-2, 0x1.71f8e5e418cadp-4, 0x1.a46f8b86994ccp+0, -0x1.18e69bbc280a2p-14, 0x1.e0d9c6faa62ddp-18, 0x1.a0ea3f7e244dbp-15}}},
};

std::string variant_name(const Golden& g) {
  return std::string(g.hertz ? "hertz_thornton" : "linear") + (g.rotation ? " +rotation" : "") + (g.rolling ? " +rolling" : "");
}

template <class Law>
ContactForce one_contact(const PairParams& p, double overlap_m, const Vec3& slip_m_s, double* history) {
  ContactInput in;
  in.normal = Vec3::UnitZ();
  in.overlap_m = overlap_m;
  in.slip_m_s = slip_m_s;
  in.r_eff_m = 1e-3;
  in.m_eff_kg = 1e-5;
  in.dt_s = 1e-6;
  return Law::eval(p, in, history);
}

PairParams hertz_pair() {
  PairParams p;
  p.e_star_pa = 2.7e7;
  p.g_star_pa = 1.0e7;
  p.damping_ratio = 0.3;
  p.friction = 0.5;
  return p;
}

DemEngine engine_with(const ContactLaw& law, bool rotation) {
  Material m;
  m.name = "m";
  EngineParams ep;
  ep.contact_law = law;
  if (!rotation) ep.effects &= ~spread::effect::kRotation;
  if (law.rolling != RollingModel::kNone) ep.effects |= spread::effect::kRolling;
  ep.min_particle_radius_m = 1e-3;
  return DemEngine({m}, {}, WallSet{}, ep);
}

void expect_refused(const ContactLaw& law, bool rotation, const std::string& words) {
  try {
    engine_with(law, rotation);
    ADD_FAILURE() << "accepted: " << to_string(law);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(to_string(law)), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(DemContactLawGolden, EveryReachableVariantReproducesTheNamedLawsBitForBit) {
  ASSERT_EQ(std::size(kGolden), kForceVariantCount);
  for (const Golden& g : kGolden) {
    SCOPED_TRACE(variant_name(g));
    const GoldenSums r = golden_run(g.hertz, g.rotation, g.rolling);
    EXPECT_EQ(r.dt_s, g.dt_s);
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 6; ++k) EXPECT_EQ(r.sums[i][k], g.sums[i][k]) << "particle " << i << " component " << k;
    EXPECT_EQ(r.hash, g.hash);
  }
}

TEST(DemContactLawGolden, TheSequenceHasContactsThatSlideSpinAndRoll) {
  // The sums are not trivially zero: both contacts push, the floor contact drags sideways, and with
  // rotation the moments (and with rolling resistance, other moments) differ.
  const Golden& plain = kGolden[1];    // hertz_thornton + rotation
  const Golden& rolling = kGolden[2];  // + rolling
  ASSERT_TRUE(plain.rotation && !plain.rolling && rolling.rolling);
  EXPECT_GT(std::abs(plain.sums[0][0]), 1.0);  // pair A–B normal impulse (N · steps)
  EXPECT_GT(std::abs(plain.sums[2][0]), 1.0);  // C on the floor: friction along x
  EXPECT_NE(plain.sums[2][5], 0.0);            // spin about z from the spinning floor
  EXPECT_NE(plain.sums[0][5], rolling.sums[0][5]);
}

TEST(DemContactLawGolden, ADifferentSubModelChangesTheHistory) {
  // The comparison can fail: the same sequence with one sub-model swapped (rolling none → constant_torque)
  // misses the other variant's recorded hash and sums.
  const Golden& plain = kGolden[4];  // linear + rotation
  ASSERT_TRUE(!plain.hertz && plain.rotation && !plain.rolling);
  const GoldenSums swapped = golden_run(false, true, true);
  EXPECT_NE(swapped.hash, plain.hash);
  EXPECT_NE(swapped.sums[0][3], plain.sums[0][3]);
}

TEST(DemContactLaws, NamedLawsAreTheScenesSubModels) {
  EXPECT_EQ(HertzThornton::kLaw, kHertzThorntonLaw);
  EXPECT_EQ(LinearSpringDashpot::kLaw, kLinearSpringDashpotLaw);
  EXPECT_EQ(to_string(kHertzThorntonLaw), "normal hertz, damping hertz, tangential thornton, rolling none, cohesion none");
  EXPECT_EQ(to_string(kLinearSpringDashpotLaw), "normal linear, damping linear_viscous, tangential linear, rolling none, cohesion none");
}

TEST(DemContactLaws, OnlyTheScenesVariantsAreCompiledOfTheValidProduct) {
  std::size_t valid = 0;
  for (std::size_t i = 0; i < detail::kProductSize; ++i) {
    const ForceVariant v = detail::product_variant(i);
    valid += contact_law_conflict(v.law, v.rotation()) == nullptr ? 1 : 0;
  }
  EXPECT_EQ(valid, 24u);
  EXPECT_EQ(kForceVariantCount, 6u);
  for (const ForceVariant& v : kForceVariants) EXPECT_TRUE(detail::reachable_from_scenes(v.law)) << to_string(v.law);
}

TEST(DemContactLaws, DampingNoneIsElasticAndTangentialNoneIsFrictionless) {
  const PairParams p = hertz_pair();
  double h[kHistoryDoubles] = {};
  using Elastic = ComposedLaw<NormalHertz, DampingNone, TangentialThornton, RollingNone>;
  using Full = HertzThornton;
  using Frictionless = ComposedLaw<NormalHertz, DampingHertz, TangentialNone, RollingNone>;
  // Closing at 1 m/s with 1 µm overlap: the elastic force alone is 4/3 √R* E* δ^{3/2}.
  const Vec3 closing(0.3, 0.0, -1.0);
  const double expected = (4.0 / 3.0) * std::sqrt(1e-3) * p.e_star_pa * std::pow(1e-6, 1.5);
  EXPECT_NEAR(one_contact<Elastic>(p, 1e-6, closing, h).normal_force_n, expected, 1e-12 * expected);
  double h2[kHistoryDoubles] = {};
  EXPECT_GT(one_contact<Full>(p, 1e-6, closing, h2).normal_force_n, expected);  // the dashpot adds while closing
  double h3[kHistoryDoubles] = {};
  const ContactForce f = one_contact<Frictionless>(p, 1e-6, closing, h3);
  EXPECT_EQ(f.tangential_force_n, Vec3::Zero());
  EXPECT_EQ(f.force_n.x(), 0.0);
  EXPECT_EQ(h3[0], 0.0);
  EXPECT_EQ(h3[3], 1e-6);  // the overlap is kept (energy monitor, unloading)
  double h4[kHistoryDoubles] = {};
  EXPECT_LT(one_contact<Full>(p, 1e-6, closing, h4).force_n.x(), 0.0);  // friction opposes the slip
}

TEST(DemContactLaws, LinearSubModelsGiveHookeAndTheViscousDashpot) {
  PairParams p;
  p.kn_linear_n_m = 1000.0;
  p.kt_linear_n_m = 285.7;
  p.damping_ratio = 0.2;
  p.friction = 0.5;
  const auto c = LinearSpringDashpot::coeffs(p, 1e-3, 1e-5);
  EXPECT_EQ(c.normal.stiffness_n_m, 1000.0);
  EXPECT_DOUBLE_EQ(c.damping.coefficient_n_s_m, 2.0 * 0.2 * std::sqrt(1e-5 * 1000.0));
  EXPECT_DOUBLE_EQ(c.tangential.damping_n_s_m, 2.0 * 0.2 * std::sqrt(1e-5 * 285.7));
  double h[kHistoryDoubles] = {};
  using Spring = ComposedLaw<NormalLinear, DampingNone, TangentialNone, RollingNone>;
  EXPECT_DOUBLE_EQ(one_contact<Spring>(p, 2e-5, Vec3(0.0, 0.0, -0.1), h).normal_force_n, 1000.0 * 2e-5);
}

TEST(DemContactLaws, StartUpChecksNameTheSubModelsThatDoNotFit) {
  ContactLaw law = kLinearSpringDashpotLaw;
  law.damping = DampingModel::kHertz;
  expect_refused(law, true, "damping 'hertz'");
  law = kHertzThorntonLaw;
  law.damping = DampingModel::kLinearViscous;
  expect_refused(law, true, "needs the 'linear' normal model");
  law = kLinearSpringDashpotLaw;
  law.tangential = TangentialModel::kThornton;
  expect_refused(law, true, "tangential 'thornton'");
  law = kHertzThorntonLaw;
  law.tangential = TangentialModel::kLinear;
  expect_refused(law, true, "tangential 'linear'");
  law = kHertzThorntonLaw;
  law.normal = NormalModel::kNone;
  expect_refused(law, true, "normal model is 'none'");
  expect_refused(with_rolling(kHertzThorntonLaw, RollingModel::kConstantTorque), false, "needs the 'rotation' effect");
  // Valid, but no scene reaches it: not compiled, and the message says which are.
  law = kHertzThorntonLaw;
  law.damping = DampingModel::kNone;
  expect_refused(law, true, "not compiled");
  EXPECT_NO_THROW(engine_with(with_rolling(kLinearSpringDashpotLaw, RollingModel::kConstantTorque), true));
}

TEST(DemContactLaws, ScenesNameTheHertzLawHertzThorntonWithHertzMindlinAsAlias) {
  const std::string disc = std::string(SPREAD_SOURCE_DIR) + "/scenes/case1.toml";
  for (const char* name : {"hertz_thornton", "hertz_mindlin"}) {
    const SimulationConfig c = config_from_scene(scene::load_scene_file(disc, {std::string("numerics.contact_model=") + name}));
    EXPECT_EQ(c.engine.contact_law, kHertzThorntonLaw) << name;
  }
  EXPECT_EQ(config_from_scene(scene::load_scene_file(disc, {"numerics.contact_model=linear"})).engine.contact_law,
            kLinearSpringDashpotLaw);
  const SimulationConfig rolling = config_from_scene(scene::load_scene_file(
      disc, {"effects.enabled=[\"particle_contact\",\"wall_contact\",\"rotation\",\"rolling\",\"drag\"]"}));
  EXPECT_EQ(rolling.engine.contact_law, with_rolling(kHertzThorntonLaw, RollingModel::kConstantTorque));
}
