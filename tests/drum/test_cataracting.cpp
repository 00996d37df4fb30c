// Cataracting on a small drum: the bead-lined drum of scenes/drum_cataracting.toml throws
// particles off its shoulder at Fr 0.6 and rolls at Fr 0.05. Short runs (label drum): 0.6 s of rotation
// at Fr 0.6 (0.58 revolutions), measured over [0.3, 0.6] s; figures in docs/drum.md ("Cataracting").
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "libspread/physics/drum/drum_scene.hpp"
#include "libspread/physics/drum/drum_simulation.hpp"

namespace drum = spread::drum;

namespace {

drum::DrumResult run(const std::vector<std::string>& set) {
  auto s = drum::load_drum_scene(std::string(SPREAD_SOURCE_DIR) + "/scenes/drum_cataracting.toml", set);
  s.output_directory.clear();  // no files from a test
  const auto r = drum::run_drum(s);
  const auto& e = r.evidence;
  std::printf("Fr %.2f N %zu: %s — %s | sagitta %.3f airborne %.4f corot %.2f cover %.2f wall speed %.2f centroid %.1f\n",
              r.froude, r.particles, drum::regime_name(e.regime).c_str(), e.reason.c_str(), e.surface_sagitta,
              e.airborne_fraction, e.co_rotating_fraction, e.wall_coverage, e.wall_speed_ratio, e.centroid_angle_deg);
  return r;
}

const std::vector<std::string> kShort = {"numerics.rotate_s=0.6", "numerics.measure_from_s=0.3"};

std::vector<std::string> with(std::vector<std::string> set, const std::string& more) {
  set.push_back(more);
  return set;
}

}  // namespace

// Fr 0.6 (inside Mellmann's cataracting band 0.1–1): the lining lifts the bed without slip and particles
// leave it from the shoulder into free flight.
TEST(DrumCataracting, RoughDrumCataractsAtFroudePointSix) {
  const auto r = run(kShort);
  EXPECT_EQ(r.evidence.regime, drum::Regime::kCataracting) << r.evidence.reason;
  EXPECT_GE(r.evidence.airborne_fraction, 0.01);
  EXPECT_GT(r.evidence.wall_speed_ratio, 0.8);  // no slip at the lining: the bed is carried up
}

// The same drum at Fr 0.05 rolls: nothing in flight.
TEST(DrumCataracting, SameDrumDoesNotCataractAtLowFroude) {
  const auto r = run(with(kShort, "drum.froude=0.05"));
  EXPECT_NE(r.evidence.regime, drum::Regime::kCataracting) << r.evidence.reason;
  EXPECT_LT(r.evidence.airborne_fraction, 0.005);
}
