// A blend fed onto the disc: each granule draws its component by the components' granule shares, so the
// released mass splits by the mass fractions; each component keeps its own sizes, density and friction
// (its disc pair exactly its own values); the launches carry their component; the same seed gives the
// same run; a single material's feed is unchanged by the blend code (its draws do not include a
// component draw).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "libspread/io/scene/scene.hpp"
#include "libspread/physics/dem/disc_run.hpp"
#include "libspread/physics/dem/inlet.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/physics/dem/simulate.hpp"

namespace spread::dem {
namespace {

const std::string kLibrary = std::string(SPREAD_SOURCE_DIR) + "/scenes/products.toml";

std::string blend_text(double urea_fraction) {
  const double rest = (1.0 - urea_fraction) / 2.0;
  return "[products]\nfile = \"" + kLibrary + "\"\n" +
         "[machine]\ndisc_radius_m = 0.29\ncone_angle_rad = 0.157\nvane_count = 2\nrpm = 600\n"
         "[inlet]\nradius_m = 0.03\noffset_m = 0.12\nmass_flow_kg_s = 0.5\n"
         "[numerics]\nthreads = 1\nduration_s = 0.06\n"
         "[[materials]]\nname = \"blend\"\n"
         "[[materials.components]]\nproduct = \"Urea, granular\"\nmass_fraction = " + std::to_string(urea_fraction) + "\n" +
         "[[materials.components]]\nproduct = \"DAP, granular\"\nmass_fraction = " + std::to_string(rest) + "\n" +
         "[[materials.components]]\nproduct = \"MOP, granular\"\nmass_fraction = " + std::to_string(rest) + "\n";
}

TEST(BlendFeed, MaterialsAndDiscPairsAreEachComponentsOwn) {
  const scene::Scene s = scene::parse_scene(blend_text(0.5), "blend.toml");
  const SimulationConfig c = config_from_scene(s);
  ASSERT_EQ(c.materials.size(), 4u);
  EXPECT_EQ(c.disc_material, 3);
  EXPECT_TRUE(c.materials[3].rigid);
  EXPECT_EQ(c.materials[1].density_kg_m3, 1606);
  EXPECT_EQ(c.materials[2].friction_wall, 0.6);
  ASSERT_EQ(c.inlet.components.size(), 3u);
  EXPECT_EQ(c.inlet.components[2].density_kg_m3, 1937);
  ASSERT_EQ(c.overrides.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(c.overrides[static_cast<std::size_t>(k)].material_a, k);
    EXPECT_EQ(c.overrides[static_cast<std::size_t>(k)].material_b, 3);
    EXPECT_EQ(c.overrides[static_cast<std::size_t>(k)].friction, c.materials[static_cast<std::size_t>(k)].friction_wall);
  }
}

// The released granules' mass by component is the recipe's (4 %-points at ~1,500 granules), each
// component's granules within its own sieve analysis's range. The inlet alone on an engine without walls,
// gravity or contacts (as DemInlet's tests): the release, not the disc, is under test.
TEST(BlendFeed, ReleasedMassSplitsByTheMassFractions) {
  const scene::Scene s = scene::parse_scene(blend_text(0.5), "blend.toml");
  SimulationConfig c = config_from_scene(s);
  c.inlet.radius_m = 0.05;
  c.inlet.centre_m = Vec3::Zero();
  EngineParams ep;
  ep.effects &= ~spread::effect::kParticleContact;
  const auto [min_m, max_m] = inlet_diameter_range_m(c.inlet);
  EXPECT_EQ(min_m, 0.5e-3);  // DAP's bottom sieve
  EXPECT_EQ(max_m, 5e-3);    // urea's and potash's top sieve
  ep.min_particle_radius_m = 0.5 * min_m;
  ep.max_particle_radius_m = 0.5 * max_m;
  ep.gravity_m_s2 = Vec3::Zero();
  ep.dt_s = 3e-6;  // the stable bound of the smallest granule (the step only paces the batches: nothing touches)
  DemEngine e(c.materials, {}, WallSet{}, ep);
  Inlet inlet(c.inlet, 1.0);  // the single material's density: unused for a blend
  while (e.time_s() < 0.04) {
    inlet.release_due(e, e.time_s());
    e.step();
  }
  EXPECT_EQ(inlet.deferred(), 0u);
  const ParticleArrays& p = e.particles();
  ASSERT_GT(p.size(), 1000u);
  std::vector<double> mass(3, 0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_LT(p.material[i], 3);
    mass[p.material[i]] += p.mass_kg[i];
    total += p.mass_kg[i];
    const double d = 2.0 * p.radius_m[i];
    const InletComponent& own = c.inlet.components[p.material[i]];
    EXPECT_GE(d, own.sieve.sieve_mm.front() * 1e-3 * (1 - 1e-9));
    EXPECT_LE(d, own.sieve.sieve_mm.back() * 1e-3 * (1 + 1e-9));
    EXPECT_NEAR(p.mass_kg[i], own.density_kg_m3 * kPi / 6.0 * d * d * d, 1e-9 * p.mass_kg[i]);
  }
  EXPECT_NEAR(mass[0] / total, 0.5, 0.04);
  EXPECT_NEAR(mass[1] / total, 0.25, 0.04);
  EXPECT_NEAR(mass[2] / total, 0.25, 0.04);
  EXPECT_NEAR(total / 0.04, 0.5, 0.05 * 0.5);  // the feed's mass rate
}

// Components of their own (one lognormal size each, so the contact step stays that of the bundled
// scenes), dropped near the rim (as test_disc_run.cpp's short run) so that granules launch within 60 ms,
// without granule contacts: the draws and the disc are what is under test.
TEST(BlendFeed, SameSeedSameRunOtherSeedOtherRun) {
  const scene::Scene s = scene::parse_scene(
      "[machine]\ndisc_radius_m = 0.29\ncone_angle_rad = 0.157\nvane_count = 2\nrpm = 600\n"
      "[inlet]\nradius_m = 0.03\noffset_m = 0.25\ndrop_height_m = 0.005\nmass_flow_kg_s = 0.3\n"
      "[numerics]\nthreads = 1\n[effects]\nenabled = [\"wall_contact\", \"rotation\", \"drag\"]\n"
      "[[materials]]\nname = \"blend\"\n"
      "[[materials.components]]\nname = \"u\"\ndensity_kg_m3 = 1257\nmass_fraction = 0.4\n"
      "[[materials.components]]\nname = \"d\"\ndensity_kg_m3 = 1606\nfriction_wall = 0.6\nmass_fraction = 0.3\n"
      "[[materials.components]]\nname = \"m\"\ndensity_kg_m3 = 1937\nfriction_wall = 0.6\nmass_fraction = 0.3\n",
      "blend.toml");
  SimulationConfig c = config_from_scene(s);
  c.fly = false;
  c.duration_s = 0.06;
  const SimulationResult a = simulate(c), b = simulate(c);
  ASSERT_GT(a.launches.size(), 20u);
  bool seen[3] = {false, false, false};
  for (const LaunchRecord& l : a.launches) seen[l.material] = true;
  EXPECT_TRUE(seen[0] && seen[1] && seen[2]) << "every component launches";
  ASSERT_EQ(a.launches.size(), b.launches.size());
  for (std::size_t k = 0; k < a.launches.size(); ++k) {
    EXPECT_EQ(a.launches[k].material, b.launches[k].material) << k;
    EXPECT_EQ(a.launches[k].position_m, b.launches[k].position_m) << k;
    EXPECT_EQ(a.launches[k].diameter_m, b.launches[k].diameter_m) << k;
  }
  c.inlet.seed += 1;
  const SimulationResult other = simulate(c);
  bool differs = other.launches.size() != a.launches.size();
  for (std::size_t k = 0; !differs && k < a.launches.size(); ++k) differs = other.launches[k].diameter_m != a.launches[k].diameter_m;
  EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace spread::dem
