// The pair list against the definition it implements: every pair (i, j > i) of active particles closer
// than r_i + r_j + skin, grouped by i with j ascending — found here by looking at all n² pairs.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "libspread/physics/dem/neighbor_list.hpp"
#include "libspread/physics/dem/particles.hpp"

namespace spread::dem {
namespace {

// 600 spheres of 0.5–1.5 mm at random in a 30 × 20 × 16 mm box, added in random order (so that a cell's
// slots are not those of a packing), every seventh inactive.
ParticleArrays scattered(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(0.0, 0.03), y(0.0, 0.02), z(0.0, 0.016), r(0.5e-3, 1.5e-3);
  ParticleArrays p;
  for (std::uint32_t id = 1; id <= 600; ++id)
    p.push_back(Vec3(x(rng), y(rng), z(rng)), Vec3::Zero(), Vec3::Zero(), r(rng), 1e-5, 4e-12, 0, id, 0.0);
  for (std::size_t i = 0; i < p.size(); i += 7) p.active[i] = 0;
  return p;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> all_pairs_within(const ParticleArrays& p, double skin_m,
                                                                      const PeriodicZ& periodic) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::uint32_t i = 0; i < p.size(); ++i)
    for (std::uint32_t j = i + 1; j < p.size(); ++j) {
      if (!p.active[i] || !p.active[j]) continue;
      double dz = p.z[i] - p.z[j];
      if (periodic.enabled) dz = minimum_image_z(dz, periodic.length_m());
      const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j], cut = p.radius_m[i] + p.radius_m[j] + skin_m;
      if (dx * dx + dy * dy + dz * dz < cut * cut) pairs.emplace_back(i, j);
    }
  return pairs;
}

void expect_the_pairs_within(const ParticleArrays& p, double skin_m, const PeriodicZ& periodic) {
  ParticleArrays q = p;
  PairList list;
  build_pair_list(q, skin_m, list, periodic);
  const auto expected = all_pairs_within(p, skin_m, periodic);
  ASSERT_GT(expected.size(), 100u);
  ASSERT_EQ(list.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(list.first[k], expected[k].first) << "pair " << k;
    EXPECT_EQ(list.second[k], expected[k].second) << "pair " << k;
  }
  for (std::uint32_t i = 0; i < p.size(); ++i)
    for (std::uint32_t k = list.first_start[i]; k < list.first_start[i + 1]; ++k) EXPECT_EQ(list.first[k], i);
}

TEST(PairList, HoldsExactlyThePairsWithinTheCutOff) { expect_the_pairs_within(scattered(11), 1e-3, PeriodicZ{}); }

TEST(PairList, HoldsExactlyThePairsWithinTheCutOffAlongAPeriodicAxis) {
  expect_the_pairs_within(scattered(12), 1e-3, PeriodicZ{true, 0.0, 0.016});
}

}  // namespace
}  // namespace spread::dem
