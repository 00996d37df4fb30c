// Landing cache (libspread/analysis/predict/landing_cache.hpp): exact at its nodes, close to flying every granule
// elsewhere (rows, between rows by both interpolations, in a wind), and not used where it does not hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "libspread/analysis/predict/flight_defaults.hpp"
#include "libspread/analysis/predict/landing_cache.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace spread::predict {
namespace {

// The synthetic table with runs that record drag as their flight effects (the product's default table).
tables::TableContents drag_contents() {
  auto contents = testing::synthetic_contents();
  for (auto& run : contents.runs) run.stats_json = R"({"flight_effects":"drag"})";
  return contents;
}

PredictionRequest request(const char* material, double rpm, double wind_x = 0.0, double wind_y = 0.0) {
  PredictionRequest r;
  r.material = material;
  r.rpm = rpm;
  r.wind_x_m_s = wind_x;
  r.wind_y_m_s = wind_y;
  return r;
}

double max_landing_distance(const Prediction& a, const Prediction& b) {
  double worst = 0.0;
  for (std::size_t k = 0; k < a.landing_x_m.size(); ++k) {
    worst = std::max(worst, std::hypot(a.landing_x_m[k] - b.landing_x_m[k], a.landing_y_m[k] - b.landing_y_m[k]));
  }
  return worst;
}

TEST(LandingCache, ExactAtItsNodes) {
  // One row of a few granules: at the speed nodes u + Δ·(±⅓, ±1) the cubic passes through the flown
  // landings (up to the float storage of its coefficients).
  const auto samples = testing::synthetic_samples(600.0, 8, 1800.0);
  LandingCache::Flying flying;
  flying.rim_speed_m_s = 600.0 * 2.0 * kPi / 60.0 * 0.3;
  flying.disc_height_m = 0.8;
  flying.density_kg_m3 = 1800.0;
  flying.effects = flight::kDrag;
  flying.settings = reference_flight_settings();
  const std::span<const tables::LaunchSample> nodes[1] = {samples};
  const LandingCache::Flying node_flying[1] = {flying};
  LandingCache cache;
  ASSERT_TRUE(cache.build(nodes, node_flying));
  double weight[LandingCache::kPairNodes];
  cache.node_weights(0.0, weight);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& s = samples[i];
    flight::State launch;
    launch.position_m = Vec3(s.x_m, s.y_m, s.z_m + flying.disc_height_m);
    launch.velocity_m_s = flying.rim_speed_m_s * Vec3(s.vx_norm, s.vy_norm, s.vz_norm);
    const double u = std::hypot(launch.velocity_m_s.x(), launch.velocity_m_s.y());
    for (double node : {-1.0, -1.0 / 3.0, 1.0 / 3.0, 1.0}) {
      // A head wind along the launch direction changes the relative speed by exactly the node offset.
      const double scale = -node * LandingCache::kWindRadius_m_s / u;
      const double wind_x = scale * launch.velocity_m_s.x(), wind_y = scale * launch.velocity_m_s.y();
      double x = 0.0, y = 0.0;
      const LandingCache::Launch horizontal{launch.position_m.x(), launch.position_m.y(), launch.velocity_m_s.x(),
                                            launch.velocity_m_s.y()};
      cache.landing(i, weight, horizontal, wind_x, wind_y, x, y);
      flight::Air air;
      air.wind_m_s = Vec3(wind_x, wind_y, 0.0);
      const flight::Landing flown = flight::fly_to_ground(flight::Granule{s.diameter_m, flying.density_kg_m3}, launch,
                                                          0.0, air, flight::kDrag | flight::kWind, flying.settings);
      ASSERT_TRUE(flown.landed);
      EXPECT_NEAR(x, flown.state.position_m.x(), 1e-4) << "sample " << i << " node " << node;
      EXPECT_NEAR(y, flown.state.position_m.y(), 1e-4) << "sample " << i << " node " << node;
    }
  }
}

// Cached against every granule flown at the tight reference tolerance: rows and between rows, pairwise
// ("can") and by quantile cells ("urea": rows of different counts), still air and winds up to the cache's
// radius. The bounds are the measured worst cases with a margin (docs/c-api.md "Landing cache").
TEST(LandingCache, CachedLandingsMatchFlownOnes) {
  Predictor cached(drag_contents());
  Predictor flown(drag_contents());
  flown.set_flight_settings(reference_flight_settings());
  ASSERT_GT(cached.landing_cache_bytes(), 0u);
  EXPECT_EQ(flown.landing_cache_bytes(), 0u);
  struct Case {
    const char* material;
    double rpm, wind_x, wind_y;
  };
  const Case cases[] = {{"can", 600.0, 0.0, 0.0},  {"can", 640.0, 0.0, 0.0},   {"can", 640.0, 3.0, 0.0},
                        {"can", 760.0, 0.0, -3.0}, {"can", 555.0, 3.5, 3.5},   {"urea", 500.0, 0.0, 0.0},
                        {"urea", 610.0, 0.0, 0.0}, {"urea", 610.0, -3.0, 0.0}, {"urea", 690.0, 4.0, 3.0}};
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.material) + " @ " + std::to_string(c.rpm) + " rpm, wind " + std::to_string(c.wind_x) +
                 ", " + std::to_string(c.wind_y));
    Prediction a, b;
    ASSERT_EQ(cached.predict(request(c.material, c.rpm, c.wind_x, c.wind_y), a), PredictStatus::kOk);
    ASSERT_EQ(flown.predict(request(c.material, c.rpm, c.wind_x, c.wind_y), b), PredictStatus::kOk);
    EXPECT_EQ(a.flights, 0);
    EXPECT_GT(b.flights, 0);
    ASSERT_EQ(a.landing_x_m.size(), b.landing_x_m.size());
    EXPECT_LT(max_landing_distance(a, b), 0.02);
    EXPECT_NEAR(a.working_width_to_and_fro_m, b.working_width_to_and_fro_m, 0.02);
    EXPECT_NEAR(a.throw_width_m, b.throw_width_m, 0.02);
    EXPECT_NEAR(a.mean_radius_m, b.mean_radius_m, 0.005);
  }
}

TEST(LandingCache, FliesWhereTheCacheDoesNotHold) {
  Predictor p(drag_contents());
  Prediction out;
  ASSERT_EQ(p.predict(request("can", 640.0), out), PredictStatus::kOk);
  EXPECT_EQ(out.flights, 0);
  // A wind beyond the cached speed range.
  ASSERT_EQ(p.predict(request("can", 640.0, 4.0, 3.5), out), PredictStatus::kOk);
  EXPECT_GT(out.flights, 0);
  // Another disc height than the machine's.
  PredictionRequest higher = request("can", 640.0);
  higher.disc_height_m = 1.0;
  ASSERT_EQ(p.predict(higher, out), PredictStatus::kOk);
  EXPECT_GT(out.flights, 0);
  // Effects other than the table's: lift is not planar.
  PredictionRequest lift = request("can", 640.0);
  lift.effects = flight::kDrag | flight::kMagnus;
  ASSERT_EQ(p.predict(lift, out), PredictStatus::kOk);
  EXPECT_GT(out.flights, 0);
  // Switched off.
  p.set_landing_cache_enabled(false);
  ASSERT_EQ(p.predict(request("can", 640.0), out), PredictStatus::kOk);
  EXPECT_GT(out.flights, 0);
  // A table whose runs fly every effect has no cache.
  Predictor all_effects(testing::synthetic_contents());
  EXPECT_EQ(all_effects.landing_cache_bytes(), 0u);
}

}  // namespace
}  // namespace spread::predict
