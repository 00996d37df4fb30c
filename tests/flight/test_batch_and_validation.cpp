// fly_batch equals single flights for any thread count; bad input is rejected naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/core/unit_uniform.hpp"
#include "libspread/physics/flight/flight.hpp"
#include "tests/flight/flight_test_support.hpp"

namespace spread::flight {
namespace {

// Uniform in [lo, hi) from the raw 64-bit engine output (std:: distributions differ across libraries).
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * spread::unit_uniform(rng());
}

TEST(Batch, EqualsSingleFlightsForAnyThreadCount) {
  std::mt19937_64 rng(20240611);
  const std::size_t n = 61;  // not a multiple of the thread count
  std::vector<Granule> granules(n);
  std::vector<State> launches(n);
  for (std::size_t i = 0; i < n; ++i) {
    granules[i] = Granule{uniform(rng, 2e-3, 5e-3), uniform(rng, 900.0, 2000.0)};
    launches[i].position_m = Vec3(uniform(rng, -0.6, 0.6), uniform(rng, -0.6, 0.6), 0.8);
    launches[i].velocity_m_s = Vec3(uniform(rng, -30, 30), uniform(rng, -30, 30), uniform(rng, -2, 6));
    launches[i].spin_rad_s = Vec3(uniform(rng, -500, 500), uniform(rng, -500, 500), uniform(rng, -500, 500));
  }
  for (Scheme scheme : {Scheme::kRk4, Scheme::kDormandPrince45}) {
    Settings settings;
    settings.scheme = scheme;
    std::vector<Landing> single(n);
    for (std::size_t i = 0; i < n; ++i) {
      single[i] = fly_to_ground(granules[i], launches[i], 0.0, Air{}, test::kDiscEffects, settings);
    }
    for (int threads : {1, 4, 0}) {
      std::vector<Landing> batch(n);
      fly_batch(granules, launches, 0.0, Air{}, test::kDiscEffects, settings, batch, threads);
      for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(batch[i].state.position_m, single[i].state.position_m) << i << " threads " << threads;
        EXPECT_EQ(batch[i].state.velocity_m_s, single[i].state.velocity_m_s);
        EXPECT_EQ(batch[i].state.spin_rad_s, single[i].state.spin_rad_s);
        EXPECT_EQ(batch[i].flight_time_s, single[i].flight_time_s);
        EXPECT_EQ(batch[i].steps, single[i].steps);
        EXPECT_EQ(batch[i].landed, single[i].landed);
      }
    }
  }
}

// fly_many (SIMD lanes for drag/wind, one by one otherwise) gives fly_to_ground's landings bit for bit:
// every field, flights of different lengths (lanes refilled at different times), a launch already on the
// ground, flights stopped by max_time_s, an odd count, and one granule for all.
TEST(Batch, FlyManyEqualsSingleFlightsBitForBit) {
  std::mt19937_64 rng(20261124);
  const std::size_t n = 37;
  std::vector<Granule> granules(n);
  std::vector<State> launches(n);
  for (std::size_t i = 0; i < n; ++i) {
    granules[i] = Granule{uniform(rng, 1e-3, 6e-3), uniform(rng, 900.0, 2000.0)};
    launches[i].position_m = Vec3(uniform(rng, -0.6, 0.6), uniform(rng, -0.6, 0.6), uniform(rng, 0.1, 3.0));
    launches[i].velocity_m_s = Vec3(uniform(rng, -35, 35), uniform(rng, -35, 35), uniform(rng, -3, 8));
    launches[i].spin_rad_s = Vec3(uniform(rng, -500, 500), uniform(rng, -500, 500), uniform(rng, -500, 500));
  }
  launches[5].position_m.z() = 0.0;  // on the ground, falling: landed at t = 0
  launches[5].velocity_m_s.z() = -1.0;
  Air air;
  air.wind_m_s = Vec3(3.0, -1.5, 0.0);
  for (const EffectSet effects : {EffectSet{0}, EffectSet{kDrag}, EffectSet{kWind}, EffectSet{kDrag | kWind},
                                  EffectSet{kDrag | kMagnus | kSpinDecay | kWind}}) {
    for (const double max_time_s : {60.0, 0.3}) {
      for (const bool one_granule : {false, true}) {
        Settings settings;
        settings.rel_tol = settings.abs_tol = 1e-3;
        settings.dt_s = 0.02;
        settings.max_time_s = max_time_s;
        const std::span<const Granule> g = one_granule ? std::span<const Granule>(granules).first(1) : granules;
        std::vector<Landing> many(n);
        fly_many(g, launches, 0.0, air, effects, settings, many);
        for (std::size_t i = 0; i < n; ++i) {
          const Landing single = fly_to_ground(g[one_granule ? 0 : i], launches[i], 0.0, air, effects, settings);
          SCOPED_TRACE(testing::Message() << "effects " << effects << " max_time " << max_time_s << " flight " << i);
          EXPECT_EQ(many[i].landed, single.landed);
          EXPECT_EQ(many[i].steps, single.steps);
          EXPECT_EQ(many[i].rejected_steps, single.rejected_steps);
          EXPECT_EQ(many[i].flight_time_s, single.flight_time_s);
          for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(many[i].state.position_m[c], single.state.position_m[c]);
            EXPECT_EQ(many[i].state.velocity_m_s[c], single.state.velocity_m_s[c]);
            EXPECT_EQ(many[i].state.spin_rad_s[c], single.state.spin_rad_s[c]);
          }
        }
        if (max_time_s < 1.0) {
          EXPECT_FALSE(many[0].landed && many[1].landed && many[2].landed && many[3].landed);
        }
      }
    }
  }
  std::vector<Landing> too_few(n - 1);
  EXPECT_THROW(fly_many(granules, launches, 0.0, air, kDrag, Settings{}, too_few), std::invalid_argument);
}

TEST(Batch, OneGranuleForAllAndSizeChecks) {
  const std::vector<Granule> one{test::typical_granule()};
  const std::vector<State> launches(5, test::typical_launch());
  std::vector<Landing> out(5);
  fly_batch(one, launches, 0.0, Air{}, kDrag, Settings{}, out, 2);
  for (const Landing& l : out) EXPECT_EQ(l.state.position_m, out[0].state.position_m);
  std::vector<Landing> short_out(4);
  EXPECT_THROW(fly_batch(one, launches, 0.0, Air{}, kDrag, Settings{}, short_out, 2), std::invalid_argument);
  const std::vector<Granule> two(2, test::typical_granule());
  EXPECT_THROW(fly_batch(two, launches, 0.0, Air{}, kDrag, Settings{}, out, 2), std::invalid_argument);
}

// Expects std::invalid_argument whose message contains `field`.
template <class F>
void expect_rejects(F&& call, const std::string& field) {
  try {
    call();
    ADD_FAILURE() << "accepted bad " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(Validation, NamesTheBadField) {
  const auto fly_with = [](Granule g, State s, double ground, Air air, Settings settings, EffectSet effects) {
    return [=] { fly_to_ground(g, s, ground, air, effects, settings); };
  };
  const Granule g = test::typical_granule();
  const State s = test::typical_launch();
  const Settings ok;
  const Air air;
  const double nan = std::nan("");

  expect_rejects(fly_with(Granule{0.0, 1500.0}, s, 0.0, air, ok, kDrag), "granule.diameter_m");
  expect_rejects(fly_with(Granule{3e-3, -1.0}, s, 0.0, air, ok, kDrag), "granule.density_kg_m3");
  State bad = s;
  bad.velocity_m_s.y() = nan;
  expect_rejects(fly_with(g, bad, 0.0, air, ok, kDrag), "launch.velocity_m_s.y");
  bad = s;
  bad.spin_rad_s.z() = INFINITY;
  expect_rejects(fly_with(g, bad, 0.0, air, ok, kDrag), "launch.spin_rad_s.z");
  expect_rejects(fly_with(g, s, 5.0, air, ok, kDrag), "below ground_z_m");
  expect_rejects(fly_with(g, s, nan, air, ok, kDrag), "ground_z_m");
  Air bad_air;
  bad_air.density_kg_m3 = -1.0;
  expect_rejects(fly_with(g, s, 0.0, bad_air, ok, kDrag), "air.density_kg_m3");
  bad_air = Air{};
  bad_air.viscosity_pa_s = 0.0;
  expect_rejects(fly_with(g, s, 0.0, bad_air, ok, kDrag), "air.viscosity_pa_s");
  bad_air = Air{};
  bad_air.wind_m_s.x() = nan;
  expect_rejects(fly_with(g, s, 0.0, bad_air, ok, kDrag), "air.wind_m_s.x");
  Settings bad_settings;
  bad_settings.dt_s = 0.0;
  expect_rejects(fly_with(g, s, 0.0, air, bad_settings, kDrag), "settings.dt_s");
  bad_settings = Settings{};
  bad_settings.rel_tol = -1e-6;
  expect_rejects(fly_with(g, s, 0.0, air, bad_settings, kDrag), "settings.rel_tol");
  bad_settings = Settings{};
  bad_settings.max_steps = 0;
  expect_rejects(fly_with(g, s, 0.0, air, bad_settings, kDrag), "settings.max_steps");
  expect_rejects(fly_with(g, s, 0.0, air, ok, EffectSet{1u << 7}), "effects");

  // In a batch the element is named.
  std::vector<State> launches(3, s);
  launches[2].position_m.x() = nan;
  std::vector<Landing> out(3);
  expect_rejects([&] { fly_batch(std::span<const Granule>(&g, 1), launches, 0.0, air, kDrag, ok, out, 2); },
                 "element 2: launch.position_m.x");
}

}  // namespace
}  // namespace spread::flight
