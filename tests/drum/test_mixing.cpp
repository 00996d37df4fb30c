// Lacey's mixing index (measurements.cpp) on hand-made beds: fully segregated, random, and fully
// mixed cells.
#include <gtest/gtest.h>

#include <random>

#include "libspread/physics/drum/measurements.hpp"

namespace drum = spread::drum;
using spread::Vec3;

namespace {

constexpr double kD = 0.004;  // particle diameter (m); Lacey cells are 3d wide as in measure()
constexpr int kSide = 18;     // 18 × 18 particles: 6 × 6 cells of 9

// A square block of kSide × kSide particles one diameter apart, cell-aligned; species from `species_of`.
template <class F>
spread::dem::ParticleArrays block(F species_of) {
  spread::dem::ParticleArrays p;
  std::uint32_t id = 1;
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j)
      p.push_back(Vec3((i + 0.5) * kD, (j + 0.5) * kD, 0.002), Vec3::Zero(), Vec3::Zero(), 0.5 * kD, 1e-4, 1e-10,
                  static_cast<std::uint16_t>(species_of(i, j)), id++, 0.0);
  return p;
}

}  // namespace

TEST(Lacey, SegregatedBedIsZero) {
  // Left half species 0, right half species 1: every cell is pure, σ² = σ0².
  EXPECT_NEAR(drum::lacey_index(block([](int i, int) { return i < kSide / 2 ? 0 : 1; }), 3.0 * kD), 0.0, 1e-12);
  // Layered (the drum's initial bed: species 0 below).
  EXPECT_NEAR(drum::lacey_index(block([](int, int j) { return j < 6 ? 0 : 1; }), 3.0 * kD), 0.0, 1e-12);
}

TEST(Lacey, RandomBedIsAboutOne) {
  // σ² of a random bed scatters about σ_R²; over 36 cells of 9 the index scatters by ~0.05 about 1.
  double mean = 0.0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 rng(seed);
    std::bernoulli_distribution half(0.5);
    const double m = drum::lacey_index(block([&](int, int) { return half(rng) ? 1 : 0; }), 3.0 * kD);
    EXPECT_GT(m, 0.8) << "seed " << seed;
    EXPECT_LT(m, 1.2) << "seed " << seed;
    mean += m / 8.0;
  }
  EXPECT_NEAR(mean, 1.0, 0.06);
}

TEST(Lacey, OrderedMixAndPartialSegregation) {
  // Every cell holds the global share (a checkerboard): σ² = 0, M = σ0²/(σ0² − σ_R²) = 1/(1 − 1/9).
  EXPECT_NEAR(drum::lacey_index(block([](int i, int j) { return (i + j) % 2; }), 3.0 * kD), 9.0 / 8.0, 0.02);
  // Half the bed segregated, half a checkerboard: strictly between.
  const double half = drum::lacey_index(block([](int i, int j) { return i < kSide / 2 ? (i + j) % 2 : (j < kSide / 2 ? 0 : 1); }),
                                        3.0 * kD);
  EXPECT_GT(half, 0.3);
  EXPECT_LT(half, 0.8);
  // One species only: no index (0).
  EXPECT_EQ(drum::lacey_index(block([](int, int) { return 0; }), 3.0 * kD), 0.0);
}
