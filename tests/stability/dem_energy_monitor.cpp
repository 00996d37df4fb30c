// Energy and penetration monitoring over a mesh-disc `simulate` run: scenes/case1.toml with
// the inlet feeding the spinning mesh disc; the monitor (libspread/physics/dem/energy_monitor.hpp) books every
// step. Asserted: max penetration under a bound, the energy balance closes within the tolerance measured
// for this step (docs/stability.md), the budget is consistent with the launch records, the monitor does
// not change the result, and bad use is refused with a message naming the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/physics/dem/energy_monitor.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/physics/dem/simulate.hpp"
#include "libspread/io/scene/scene.hpp"

namespace spread::dem {
namespace {

SimulationConfig short_case1_run(double rpm, double duration_s) {
  SimulationConfig c = config_from_scene(scene::load_scene_file(std::string(SPREAD_SOURCE_DIR) + "/scenes/case1.toml"));
  c.rpm = rpm;
  c.duration_s = duration_s;
  c.fly = false;  // the DEM part is what is monitored
  return c;
}

TEST(DemEnergyMonitor, ShortMeshDiscSimulateKeepsPenetrationAndBalance) {
  SimulationConfig config = short_case1_run(1500.0, 0.06);
  config.energy_monitor_every_steps = 100;
  const SimulationResult r = simulate(config);
  ASSERT_TRUE(r.energy_monitored);
  const EnergyReport& e = r.energy;
  ASSERT_GT(r.launches.size(), 10u) << "the run must reach the collector for the budget to mean anything";
  EXPECT_TRUE(std::isfinite(e.dissipated_j) && std::isfinite(e.disc_work_j) && std::isfinite(e.energy_input_j));
  // Bound: the Hertz maximum overlap of the softest possible case, a smallest granule striking the rigid
  // disc at the rim speed plus 5 m/s (the engine's t_c speed): δ = (15 m v² / (16 E* √r))^{2/5}, the
  // energy ½ m v² stored as 8/15 E* √r δ^{5/2}. An unstable contact would overshoot it. E = 5e7 Pa at
  // 1500 rpm makes this large (≈ 0.6 R): soft DEM granules at 50 m/s, not an instability.
  const Material& granule = config.materials[0];
  const double r_min = 0.5 * LognormalDiameter(config.inlet.diameter_mean_m, config.inlet.diameter_sd_m).min_m();
  const double m_min = granule.density_kg_m3 * 4.0 / 3.0 * kPi * r_min * r_min * r_min;
  const double e_star = granule.youngs_modulus_pa / (1.0 - granule.poisson_ratio * granule.poisson_ratio);
  const double v = std::abs(config.rpm) * 2.0 * kPi / 60.0 * config.disc.radius_m + 5.0;
  const double hertz_max_ratio = std::pow(15.0 * m_min * v * v / (16.0 * e_star * std::sqrt(r_min)), 0.4) / r_min;
  std::printf("simulate case1 %.0f rpm %.3f s: %zu launched, %llu steps, max penetration/R %.4f (Hertz bound %.4f), "
              "disc work %.4g J, gravity work %.4g J, added T %.4g J, launched T %.4g J, dissipated %.4g J, "
              "created %.3g J, input %.4g J, residual %.3g\n",
              config.rpm, config.duration_s, r.launches.size(), static_cast<unsigned long long>(e.steps),
              e.max_penetration_ratio, hertz_max_ratio, e.disc_work_j, e.gravity_work_j, e.added_kinetic_j,
              e.launched_kinetic_j, e.dissipated_j, e.energy_created_j, e.energy_input_j, e.balance_residual());
  EXPECT_GT(e.max_penetration_ratio, 0.0);
  EXPECT_LE(e.max_penetration_ratio, hertz_max_ratio);
  EXPECT_GT(e.disc_work_j, 0.0);
  EXPECT_GT(e.dissipated_j, 0.0);
  EXPECT_LE(e.balance_residual(), 0.01);
  // The budget against the launch records: what came in (initial, added, disc and gravity work) minus
  // what was dissipated equals what is still there plus what the collector took away. The launch
  // records carry T only; the elastic energy of contacts broken by a launch is the difference (small).
  const double in = e.initial_kinetic_j + e.initial_elastic_j + e.added_kinetic_j + e.disc_work_j + e.gravity_work_j;
  const double out = e.dissipated_j + e.kinetic_j + e.elastic_j + e.launched_kinetic_j;
  EXPECT_NEAR(in, out, 0.01 * in);
  EXPECT_GT(e.launched_kinetic_j, 0.0);
  // Samples every 100 steps, cumulative values never decreasing by more than the created energy.
  ASSERT_EQ(r.energy_samples.size(), static_cast<std::size_t>(e.steps / 100));
  for (std::size_t k = 1; k < r.energy_samples.size(); ++k) {
    EXPECT_GE(r.energy_samples[k].dissipated_j, r.energy_samples[k - 1].dissipated_j - e.energy_created_j - 1e-15);
    EXPECT_GE(r.energy_samples[k].time_s, r.energy_samples[k - 1].time_s);
  }
}

TEST(DemEnergyMonitor, MonitoringDoesNotChangeTheRun) {
  SimulationConfig config = short_case1_run(1500.0, 0.03);
  const SimulationResult off = simulate(config);
  config.energy_monitor_every_steps = 7;
  const SimulationResult on = simulate(config);
  std::printf("simulate case1 1500 rpm 0.03 s: wall time %.3f s monitor off, %.3f s on\n", off.wall_time_s, on.wall_time_s);
  EXPECT_FALSE(off.energy_monitored);
  ASSERT_EQ(off.launches.size(), on.launches.size());
  EXPECT_EQ(off.particle_steps, on.particle_steps);
  for (std::size_t k = 0; k < on.launches.size(); ++k) {
    ASSERT_EQ(off.launches[k].position_m, on.launches[k].position_m) << k;
    ASSERT_EQ(off.launches[k].velocity_m_s, on.launches[k].velocity_m_s) << k;
  }
}

TEST(DemEnergyMonitor, BadUseIsRefusedNamingTheProblem) {
  try {
    EnergyMonitor monitor(0);
    FAIL() << "a sample interval of 0 steps was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sample_every_steps"), std::string::npos) << e.what();
  }
  SimulationConfig config = short_case1_run(500.0, 0.01);
  config.energy_monitor_every_steps = -1;
  try {
    simulate(config);
    FAIL() << "a negative monitor interval was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("energy_monitor_every_steps"), std::string::npos) << e.what();
  }
  // A spinning disc next to a second wall group: the per-group disc work cannot be split.
  std::vector<Material> materials(2);
  materials[1].rigid = true;
  WallSet walls;
  walls.groups.push_back(make_disc(config.disc, 500.0, 1, 1.5e-3));
  walls.groups.push_back(make_disc(config.disc, 0.0, 1, 1.5e-3));
  EngineParams params;
  params.min_particle_radius_m = 1.5e-3;
  DemEngine engine(materials, {}, std::move(walls), params);
  engine.add_particle(Vec3(0.1, 0.1, 0.05), Vec3::Zero(), 1.5e-3, 0);
  EnergyMonitor monitor(1);
  engine.set_energy_monitor(&monitor);
  try {
    engine.step();
    FAIL() << "a moving group next to another group was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2 groups, 1 moving"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace spread::dem
