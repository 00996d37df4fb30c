// DiscRun: the one disc run behind dem::simulate and lookup_builder's DEM source. A run stepped to T by
// hand (as lookup_builder does in batches) launches what simulate() with duration T launches, to the bit;
// the collector's floor lies kFallenBelowApex_m under the apex.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/physics/dem/disc_run.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/io/scene/scene.hpp"

namespace spread::dem {
namespace {

// Short Case-1 run that launches granules (inlet near the rim, dropped from 5 mm; test_scene_stl.cpp's).
SimulationConfig short_case1(double duration_s) {
  const std::string path = std::string(SPREAD_SOURCE_DIR) + "/scenes/case1.toml";
  SimulationConfig c = config_from_scene(scene::load_scene_file(
      path, {"numerics.duration_s=" + std::to_string(duration_s), "inlet.offset_m=0.25", "inlet.drop_height_m=0.005",
             "machine.mesh_size_m=0.005", "numerics.threads=1"}));
  c.fly = false;
  return c;
}

TEST(DemDiscRun, SteppedInBatchesLaunchesWhatSimulateLaunches) {
  const SimulationConfig c = short_case1(0.035);
  const SimulationResult whole = simulate(c);
  ASSERT_GT(whole.launches.size(), 10u);

  DiscRun run(c);
  for (const double batch_end_s : {0.01, 0.02, 0.035})
    while (run.before(batch_end_s)) run.step();
  const std::vector<LaunchRecord>& launches = run.engine().launches();
  ASSERT_EQ(launches.size(), whole.launches.size());
  for (std::size_t k = 0; k < launches.size(); ++k) {
    const LaunchRecord& a = launches[k];
    const LaunchRecord& b = whole.launches[k];
    EXPECT_EQ(a.id, b.id) << k;
    EXPECT_EQ(a.time_s, b.time_s) << k;
    EXPECT_EQ(a.position_m, b.position_m) << k;
    EXPECT_EQ(a.velocity_m_s, b.velocity_m_s) << k;
    EXPECT_EQ(a.spin_rad_s, b.spin_rad_s) << k;
  }
  EXPECT_EQ(run.inlet().released(), whole.released);
  EXPECT_EQ(run.engine().stats().particle_steps, whole.particle_steps);
}

TEST(DemDiscRun, CollectorIsTheDiscRimWithItsFloorUnderTheApex) {
  SimulationConfig c = short_case1(0.01);
  Collector col = disc_collector(c);
  EXPECT_TRUE(col.enabled);
  EXPECT_EQ(col.radius_m, c.disc.radius_m);
  EXPECT_EQ(col.lost_below_z_m, c.disc.z_apex_m - kFallenBelowApex_m);
  c.collector_radius_m = 0.4;
  col = disc_collector(c);
  EXPECT_EQ(col.radius_m, 0.4);

  // The engine's radius range is the inlet's truncated diameter law, halved.
  const EngineParams ep = disc_engine_params(c);
  const LognormalDiameter dist(c.inlet.diameter_mean_m, c.inlet.diameter_sd_m);
  EXPECT_EQ(ep.min_particle_radius_m, 0.5 * dist.min_m());
  EXPECT_EQ(ep.max_particle_radius_m, 0.5 * dist.max_m());
  EXPECT_EQ(DiscRun(c).engine().params().max_particle_radius_m, ep.max_particle_radius_m);
}

TEST(DemDiscRun, UnknownInletMaterialIsRefused) {
  SimulationConfig c = short_case1(0.01);
  c.inlet.material = static_cast<int>(c.materials.size());
  EXPECT_THROW(DiscRun{c}, std::invalid_argument);
}

}  // namespace
}  // namespace spread::dem
