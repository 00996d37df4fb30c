// Landing grid (libspread/analysis/predict/landing_grid.hpp): exact at its nodes, close to flying every granule
// elsewhere in its domain (rows, between rows by both interpolations, heights, winds), continuous, and not
// used where it does not hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "libspread/analysis/predict/flight_defaults.hpp"
#include "libspread/analysis/predict/landing_grid.hpp"
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

TEST(LandingGrid, ExactAtItsNodes) {
  // A small grid flown at the reference tolerance: at its nodes the interpolant is the flown landing (up to
  // the float storage of its values), in still air and, through the Galilean frame change, in a wind.
  LandingGrid::Axes axes;
  axes[LandingGrid::kDiameter] = GridAxis{2e-3, 1e-3, 4};
  axes[LandingGrid::kVerticalSpeed] = GridAxis{-1.0, 1.5, 4};
  axes[LandingGrid::kHeight] = GridAxis{0.7, 0.2, 5};  // √m: heights 0.49 m to 1.96 m
  axes[LandingGrid::kSpeed] = GridAxis{0.0, 6.0, 6};
  const double density_kg_m3 = 1800.0;
  LandingGrid grid;
  ASSERT_TRUE(grid.build(axes, density_kg_m3, flight::kDrag, reference_flight_settings(), flight::Air{}));
  EXPECT_EQ(grid.bytes(), sizeof(float) * LandingGrid::value_count(axes));
  for (std::uint32_t d = 0; d < 4; d += 3) {
    for (std::uint32_t v = 0; v < 4; ++v) {
      for (std::uint32_t h = 0; h < 5; h += 2) {
        for (std::uint32_t u = 1; u < 6; u += 2) {
          const double root_height = 0.7 + 0.2 * h;
          const double diameter_m = 2e-3 + 1e-3 * d, vz = -1.0 + 1.5 * v, height_m = root_height * root_height;
          const double speed = 6.0 * u;
          // Launched along (3, 4)/5 from (0.2, −0.1); the wind (1, −2) m/s changes the speed relative to the
          // air, so launch with the air-relative speed of the node.
          const double wind_x = 1.0, wind_y = -2.0;
          const double vx = 0.6 * speed + wind_x, vy = 0.8 * speed + wind_y;
          double x = 0.0, y = 0.0;
          grid.landing(diameter_m, 0.2, -0.1, height_m, vx, vy, vz, wind_x, wind_y, x, y);
          flight::State launch;
          launch.position_m = Vec3(0.2, -0.1, height_m);
          launch.velocity_m_s = Vec3(vx, vy, vz);
          flight::Air air;
          air.wind_m_s = Vec3(wind_x, wind_y, 0.0);
          const flight::Landing flown = flight::fly_to_ground(flight::Granule{diameter_m, density_kg_m3}, launch, 0.0, air,
                                                              flight::kDrag | flight::kWind, reference_flight_settings());
          ASSERT_TRUE(flown.landed);
          EXPECT_NEAR(x, flown.state.position_m.x(), 1e-4) << d << " " << v << " " << h << " " << u;
          EXPECT_NEAR(y, flown.state.position_m.y(), 1e-4) << d << " " << v << " " << h << " " << u;
        }
      }
    }
  }
  // Through u = 0 by symmetry: a granule dropped with no horizontal speed lands below its launch point.
  double range_m = 1.0, time_s = 0.0;
  grid.range_and_time(3e-3, 0.5, 1.0, 0.0, range_m, time_s);
  EXPECT_NEAR(range_m, 0.0, 1e-6);
  EXPECT_GT(time_s, 0.3);
}

// A small grid of 1800 kg/m³ granules flown at the default tolerance (drag), for the bit-for-bit tests.
bool build_small_grid(LandingGrid& grid) {
  LandingGrid::Axes axes;
  axes[LandingGrid::kDiameter] = GridAxis{2e-3, 1e-3, 5};
  axes[LandingGrid::kVerticalSpeed] = GridAxis{-1.0, 1.5, 5};
  axes[LandingGrid::kHeight] = GridAxis{0.7, 0.2, 6};
  axes[LandingGrid::kSpeed] = GridAxis{0.0, 6.0, 7};
  return grid.build(axes, 1800.0, flight::kDrag, default_flight_settings(), flight::Air{});
}

// The stencil summed in AVX registers or in SSE ones gives the same bits, and a sample's two discs in one
// call give what two calls give: over random launches across a small grid (and past its edges), still
// air and winds, speeds through 0. Stored and restored, the values are the same.
TEST(LandingGrid, AvxSseAndPairedLandingsAreTheSameBits) {
  LandingGrid grid;
  ASSERT_TRUE(build_small_grid(grid));
  LandingGrid restored;
  ASSERT_TRUE(restored.restore(grid.axes(), grid.effects(), grid.values()));
  EXPECT_EQ(restored.values(), grid.values());
  const bool avx = grid.set_avx(true);
  restored.set_avx(false);
  std::uint64_t state = 0x9e3779b97f4a7c15ULL;
  const auto uniform = [&state](double lo, double hi) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(state >> 11) * 0x1p-53;
  };
  int compared = 0;
  for (int i = 0; i < 2000; ++i) {
    const double d = uniform(1.5e-3, 6.5e-3), vz = uniform(-1.5, 5.5), z = uniform(0.4, 3.0);
    const double vx = uniform(-25.0, 25.0), vy = uniform(-25.0, 25.0), x = uniform(-0.5, 0.5), y = uniform(-0.5, 0.5);
    const double wind_x = i % 3 == 0 ? 0.0 : uniform(-8.0, 8.0), wind_y = i % 3 == 0 ? 0.0 : uniform(-8.0, 8.0);
    double ax = 0, ay = 0, bx = 0, by = 0;
    grid.landing(d, x, y, z, vx, vy, vz, wind_x, wind_y, ax, ay);
    restored.landing(d, x, y, z, vx, vy, vz, wind_x, wind_y, bx, by);
    ASSERT_EQ(ax, bx) << i;
    ASSERT_EQ(ay, by) << i;
    double mirror_x = 0, mirror_y = 0, pair_x[2], pair_y[2];
    restored.landing(d, -1.0 * x, y, z, -1.0 * vx, vy, vz, wind_x, wind_y, mirror_x, mirror_y);
    for (const LandingGrid* g : {&grid, &restored}) {
      g->mirrored_landings(d, x, y, z, vx, vy, vz, wind_x, wind_y, pair_x, pair_y);
      ASSERT_EQ(pair_x[0], ax) << i;
      ASSERT_EQ(pair_y[0], ay) << i;
      ASSERT_EQ(pair_x[1], mirror_x) << i;
      ASSERT_EQ(pair_y[1], mirror_y) << i;
    }
    ++compared;
  }
  EXPECT_EQ(compared, 2000);
  if (!avx) GTEST_SKIP() << "no AVX here: the SSE sums were compared with themselves";
}

// A chunk of samples landed a block at a time (stencils set up side by side in SIMD lanes) gives, bit for
// bit, what landing() and mirrored_landings() give one sample at a time — as stored, mirrored and both,
// in still air and a wind, with AVX-512 (where the processor has it), AVX and neither, over a count that
// fills neither a block nor its lanes.
TEST(LandingGrid, BlockLandingsAreTheOneAtATimeBits) {
  LandingGrid grid;
  ASSERT_TRUE(build_small_grid(grid));
  std::uint64_t state = 0x2545f4914f6cdd1dULL;
  const auto uniform = [&state](double lo, double hi) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<float>(lo + (hi - lo) * static_cast<double>(state >> 11) * 0x1p-53);
  };
  std::vector<tables::LaunchSample> samples(2 * LandingGrid::kBlock + 13);
  for (tables::LaunchSample& s : samples) {
    s = tables::LaunchSample{};
    s.x_m = uniform(-0.5, 0.5);
    s.y_m = uniform(-0.5, 0.5);
    s.z_m = uniform(-0.1, 0.6);
    s.vx_norm = uniform(-1.0, 1.0);
    s.vy_norm = uniform(-1.0, 1.0);
    s.vz_norm = uniform(-0.05, 0.2);
    s.diameter_m = uniform(1.5e-3, 6.5e-3);
  }
  samples[5].vx_norm = samples[5].vy_norm = 0.0f;  // no horizontal speed: the speed axis's node −1
  const double rim_speed_m_s = 24.0, disc_height_m = 0.9;
  auto block = std::make_unique<LandingGrid::StencilBlock>();
  const std::size_t n = samples.size();
  std::vector<double> xs(2 * n), ys(2 * n);
  int compared = 0;
  enum class Registers { kAvx512, kAvx, kSse };
  for (const Registers registers : {Registers::kAvx512, Registers::kAvx, Registers::kSse}) {
    grid.set_avx(registers != Registers::kSse);
    grid.set_avx512(registers == Registers::kAvx512);
    for (const double wind_x : {0.0, 3.0, -7.0}) {
      const double wind_y = wind_x == 0.0 ? 0.0 : 1.5;
      for (const auto sides : {LandingGrid::Sides::kAsStored, LandingGrid::Sides::kMirrored, LandingGrid::Sides::kBoth}) {
        grid.sample_landings(samples, rim_speed_m_s, disc_height_m, wind_x, wind_y, sides, *block, xs, ys);
        for (std::size_t i = 0; i < n; ++i) {
          const tables::LaunchSample& s = samples[i];
          const double vx = rim_speed_m_s * s.vx_norm, vy = rim_speed_m_s * s.vy_norm, vz = rim_speed_m_s * s.vz_norm;
          const double z = s.z_m + disc_height_m;
          double x[2], y[2];
          if (sides == LandingGrid::Sides::kBoth) {
            grid.mirrored_landings(s.diameter_m, s.x_m, s.y_m, z, vx, vy, vz, wind_x, wind_y, x, y);
            ASSERT_EQ(xs[n + i], x[1]) << i;
            ASSERT_EQ(ys[n + i], y[1]) << i;
          } else if (sides == LandingGrid::Sides::kAsStored) {
            grid.landing(s.diameter_m, s.x_m, s.y_m, z, vx, vy, vz, wind_x, wind_y, x[0], y[0]);
          } else {
            grid.landing(s.diameter_m, -1.0 * s.x_m, s.y_m, z, -1.0 * vx, vy, vz, wind_x, wind_y, x[0], y[0]);
          }
          ASSERT_EQ(xs[i], x[0]) << i;
          ASSERT_EQ(ys[i], y[0]) << i;
          ++compared;
        }
      }
    }
  }
  EXPECT_EQ(compared, 3 * 3 * 3 * static_cast<int>(n));
}

// The grid against every granule flown at the tight reference tolerance: rows and between rows, pairwise
// ("can") and by quantile cells ("urea": rows of different counts), still air and winds up to the
// domain's, the stored height and others across the domain.
TEST(LandingGrid, GridLandingsMatchFlownOnes) {
  Predictor gridded(drag_contents());
  Predictor flown(drag_contents());
  flown.set_flight_settings(reference_flight_settings());
  ASSERT_GT(gridded.landing_grid_bytes(), 0u);
  EXPECT_EQ(flown.landing_grid_bytes(), 0u);
  struct Case {
    const char* material;
    double rpm, wind_x, wind_y, height_m;
  };
  const double stored = std::numeric_limits<double>::quiet_NaN();
  const Case cases[] = {{"can", 600.0, 0.0, 0.0, stored},  {"can", 640.0, 0.0, 0.0, 0.2},  {"can", 640.0, 3.0, 0.0, 1.37},
                        {"can", 760.0, 0.0, -3.0, 2.0},    {"can", 555.0, 7.0, 7.0, stored}, {"urea", 500.0, 0.0, 0.0, 0.55},
                        {"urea", 610.0, 0.0, 0.0, stored}, {"urea", 610.0, -10.0, 0.0, 1.1}, {"urea", 690.0, 4.0, 3.0, 1.9}};
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.material) + " @ " + std::to_string(c.rpm) + " rpm, wind " + std::to_string(c.wind_x) +
                 ", " + std::to_string(c.wind_y) + ", height " + std::to_string(c.height_m));
    PredictionRequest r = request(c.material, c.rpm, c.wind_x, c.wind_y);
    r.disc_height_m = c.height_m;
    Prediction a, b;
    ASSERT_EQ(gridded.predict(r, a), PredictStatus::kOk);
    ASSERT_EQ(flown.predict(r, b), PredictStatus::kOk);
    EXPECT_EQ(a.flights, 0);
    EXPECT_GT(b.flights, 0);
    ASSERT_EQ(a.landing_x_m.size(), b.landing_x_m.size());
    // Measured: landings within 0.08 mm, widths within 0.06 mm (the synthetic launches are smooth; the DEM
    // table's measured worst case is in landing_grid.hpp).
    EXPECT_LT(max_landing_distance(a, b), 1e-3);
    EXPECT_NEAR(a.working_width_to_and_fro_m, b.working_width_to_and_fro_m, 1e-3);
    EXPECT_NEAR(a.throw_width_m, b.throw_width_m, 1e-3);
    EXPECT_NEAR(a.mean_radius_m, b.mean_radius_m, 1e-3);
  }
}

// Inside the domain the answer is continuous: a disc 1 mm higher or a wind 1 mm/s stronger moves no
// landing by more than a millimetre or so.
TEST(LandingGrid, NeighbouringRequestsGiveNeighbouringLandings) {
  Predictor p(drag_contents());
  for (double height_m : {0.2, 0.8, 1.2345, 1.999}) {
    PredictionRequest r = request("urea", 610.0, 4.999, 0.0);
    r.disc_height_m = height_m;
    Prediction a, b, c;
    ASSERT_EQ(p.predict(r, a), PredictStatus::kOk);
    r.disc_height_m = height_m + 0.001;
    ASSERT_EQ(p.predict(r, b), PredictStatus::kOk);
    r.wind_x_m_s += 0.001;
    ASSERT_EQ(p.predict(r, c), PredictStatus::kOk);
    EXPECT_EQ(b.flights, 0);
    EXPECT_EQ(c.flights, 0);
    EXPECT_LT(max_landing_distance(a, b), 0.003) << height_m;
    EXPECT_LT(max_landing_distance(b, c), 0.003) << height_m;
  }
}

TEST(LandingGrid, FliesWhereTheGridDoesNotHold) {
  Predictor p(drag_contents());
  const LandingDomain& domain = p.landing_domain();
  EXPECT_EQ(domain.min_disc_height_m, 0.2);
  EXPECT_EQ(domain.max_disc_height_m, 2.0);
  EXPECT_EQ(domain.max_wind_m_s, 10.0);
  Prediction out;
  ASSERT_EQ(p.predict(request("can", 640.0), out), PredictStatus::kOk);
  EXPECT_EQ(out.flights, 0);
  // A wind beyond the domain.
  ASSERT_EQ(p.predict(request("can", 640.0, 8.0, 6.1), out), PredictStatus::kOk);
  EXPECT_GT(out.flights, 0);
  // A disc above it.
  PredictionRequest higher = request("can", 640.0);
  higher.disc_height_m = 2.01;
  ASSERT_EQ(p.predict(higher, out), PredictStatus::kOk);
  EXPECT_GT(out.flights, 0);
  // Effects other than the table's: lift is not planar.
  PredictionRequest lift = request("can", 640.0);
  lift.effects = flight::kDrag | flight::kMagnus;
  ASSERT_EQ(p.predict(lift, out), PredictStatus::kOk);
  EXPECT_GT(out.flights, 0);
  // Switched off.
  p.set_landing_grid_enabled(false);
  ASSERT_EQ(p.predict(request("can", 640.0), out), PredictStatus::kOk);
  EXPECT_GT(out.flights, 0);
  // A table whose runs fly every effect has no grid.
  Predictor all_effects(testing::synthetic_contents());
  EXPECT_EQ(all_effects.landing_grid_bytes(), 0u);
}

// A controller's Predictor (refuse_outside_domain) answers inside the grid's domain from every sample and
// refuses outside it, naming what is outside; opted in, it flies every sample — never a subsample.
TEST(LandingGrid, OutsideTheDomainIsRefusedOrFlownWhole) {
  PredictorLimits limits;
  limits.refuse_outside_domain = true;
  Predictor controller(drag_contents(), limits);
  Prediction inside;
  ASSERT_EQ(controller.predict(request("can", 650.0, 3.0, 0.0), inside), PredictStatus::kOk);
  EXPECT_EQ(inside.flights, 0);
  const std::size_t every_sample = inside.sample_count;
  EXPECT_EQ(every_sample, 256u);
  struct Case {
    PredictionRequest request;
    Predictor::DomainMiss miss;
  };
  PredictionRequest high = request("can", 650.0), windy = request("can", 650.0, 7.1, -7.1),
                    lift = request("can", 650.0);
  high.disc_height_m = 2.01;
  lift.effects = flight::kDrag | flight::kMagnus;
  for (Case c : {Case{high, Predictor::DomainMiss::kHeight}, Case{windy, Predictor::DomainMiss::kWind},
                 Case{lift, Predictor::DomainMiss::kEffects}}) {
    SCOPED_TRACE(static_cast<int>(c.miss));
    EXPECT_EQ(controller.landing_domain_miss(c.request), c.miss);
    Prediction out = inside;
    ASSERT_EQ(controller.predict(c.request, out), PredictStatus::kOutsideDomain);
    EXPECT_EQ(out.working_width_to_and_fro_m, inside.working_width_to_and_fro_m);  // unchanged
    c.request.fly_outside_domain = true;
    ASSERT_EQ(controller.predict(c.request, out), PredictStatus::kOk);
    EXPECT_EQ(out.sample_count, every_sample);
    const int discs_flown = c.request.wind_x_m_s != 0.0 ? 2 : 1;
    // A wind along the track: the return pass of a to-and-fro field is flown as well (return_pass.cpp).
    const int passes_flown = c.request.wind_y_m_s != 0.0 ? 2 : 1;
    EXPECT_EQ(out.flights, passes_flown * discs_flown * static_cast<int>(every_sample));
  }
  EXPECT_EQ(controller.landing_domain_miss(request("can", 650.0)), Predictor::DomainMiss::kNone);
  // The library's default flies them whole without being asked; a table without a grid flies every
  // request whole, refusing nothing.
  Predictor tool(drag_contents());
  Prediction out;
  ASSERT_EQ(tool.predict(high, out), PredictStatus::kOk);
  EXPECT_EQ(out.flights, static_cast<int>(every_sample));
  Predictor no_grid(testing::synthetic_contents(), limits);
  EXPECT_FALSE(no_grid.has_landing_grid(0));
  ASSERT_EQ(no_grid.predict(high, out), PredictStatus::kOk);
  EXPECT_EQ(out.flights, static_cast<int>(every_sample));
}

}  // namespace
}  // namespace spread::predict
