// Quantile cells of a row (primary key groups, secondary key cells inside, equal mass) and the
// interpolation that moves each cell's mean between two rows of different counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "libspread/analysis/predict/launch_interpolation.hpp"
#include "libspread/analysis/predict/launch_quantile_cells.hpp"

namespace spread::predict {
namespace {

// A deterministic scramble of 0..n−1 (multiplicative step coprime with n), so rows are not stored in
// key order.
std::vector<std::size_t> scrambled(std::size_t n) {
  std::size_t step = 7919;
  while (std::gcd(step, n) != 1) ++step;
  std::vector<std::size_t> p(n);
  for (std::size_t k = 0; k < n; ++k) p[k] = (k * step) % n;
  return p;
}

struct Celled {
  std::vector<tables::LaunchSample> samples;
  std::vector<CellIndex> cell;
  std::vector<tables::LaunchSample> mean;
  CelledRow view() const { return CelledRow{samples, cell, mean}; }
};

// A row whose vx_norm takes the mass quantiles of the uniform distribution on [lo, hi], stored in a
// scrambled order; every third sample is 3× heavier. vy_norm = 2·vx_norm (moved along with vx: a cell
// shift keeps it), diameter is the granule's own (never moved). Cells: 16 along vx.
Celled uniform_row(std::size_t n, double lo, double hi) {
  Celled row;
  row.samples.resize(n);
  std::vector<double> mass(n), cumulative(n + 1, 0.0);
  for (std::size_t r = 0; r < n; ++r) mass[r] = r % 3 == 0 ? 3e-5 : 1e-5;
  for (std::size_t r = 0; r < n; ++r) cumulative[r + 1] = cumulative[r] + mass[r];
  const auto place = scrambled(n);
  for (std::size_t r = 0; r < n; ++r) {
    const double u = (cumulative[r] + 0.5 * mass[r]) / cumulative[n];  // mid-slice quantile
    auto& s = row.samples[place[r]];
    s.vx_norm = static_cast<float>(lo + (hi - lo) * u);
    s.vy_norm = 2.0f * s.vx_norm;
    s.mass_kg = static_cast<float>(mass[r]);
    s.diameter_m = static_cast<float>(3e-3 * std::cbrt(mass[r] / 1e-5));
  }
  std::vector<double> key(n), m(n);
  for (std::size_t k = 0; k < n; ++k) {
    key[k] = row.samples[k].vx_norm;
    m[k] = row.samples[k].mass_kg;
  }
  std::vector<std::uint32_t> order(n);
  row.cell.resize(n);
  assign_quantile_cells(key, key, m, QuantileCellCounts{16, 1}, order, row.cell);
  row.mean.resize(16);
  quantile_cell_means(row.samples, row.cell, row.mean);
  return row;
}

// Weighted quantile (lower) of vx_norm among the first `count` output samples.
double quantile(const std::vector<tables::LaunchSample>& s, const std::vector<double>& w, std::size_t count,
                double q) {
  std::vector<std::size_t> idx(count);
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return s[a].vx_norm < s[b].vx_norm; });
  const double total = std::accumulate(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(count), 0.0);
  double below = 0.0;
  for (std::size_t k : idx) {
    below += w[k];
    if (below >= q * total) return s[k].vx_norm;
  }
  return s[idx.back()].vx_norm;
}

TEST(QuantileCells, PrimaryGroupsThenSecondaryCellsOfEqualMass) {
  // 100 samples of equal mass; primary = k mod 10, secondary = −k. 10 × 2 cells: group g holds the ten
  // samples with primary g; inside, the five with the smallest secondary (largest k) are cell 0.
  const std::size_t n = 100;
  std::vector<double> primary(n), secondary(n), mass(n, 2.0);
  for (std::size_t k = 0; k < n; ++k) {
    primary[k] = static_cast<double>(k % 10);
    secondary[k] = -static_cast<double>(k);
  }
  std::vector<std::uint32_t> order(n);
  std::vector<CellIndex> cell(n);
  assign_quantile_cells(primary, secondary, mass, QuantileCellCounts{10, 2}, order, cell);
  for (std::size_t k = 0; k < n; ++k) {
    EXPECT_EQ(cell[k], (k % 10) * 2 + (k / 10 >= 5 ? 0u : 1u)) << k;
  }
  // Masses count, not samples: one heavy sample (9 of 18 kg) fills the first half alone.
  const std::vector<double> key{0.0, 1.0, 2.0, 3.0}, heavy{9.0, 3.0, 3.0, 3.0};
  std::vector<std::uint32_t> order4(4);
  std::vector<CellIndex> cell4(4);
  assign_quantile_cells(key, key, heavy, QuantileCellCounts{2, 1}, order4, cell4);
  EXPECT_EQ(cell4, (std::vector<CellIndex>{0, 1, 1, 1}));
}

TEST(QuantileCells, CountsFollowTheSmallestRow) {
  EXPECT_EQ(quantile_cells_for(2200).primary, 16);
  EXPECT_EQ(quantile_cells_for(2200).secondary, 4);
  EXPECT_EQ(quantile_cells_for(825).cells(), 16);  // 4 × 4: each cell keeps >= 32 samples
  EXPECT_EQ(quantile_cells_for(200).cells(), 4);
  EXPECT_EQ(quantile_cells_for(0).cells(), 1);
  for (std::size_t n : {40u, 300u, 1000u, 5000u}) {
    const auto c = quantile_cells_for(n);
    EXPECT_LE(static_cast<std::size_t>(c.cells()) * 32, std::max<std::size_t>(n, 32)) << n;
  }
}

TEST(QuantileCells, MeansAreMassWeighted) {
  std::vector<tables::LaunchSample> s(3);
  s[0].vx_norm = 1.0f, s[0].wz_norm = 4.0f, s[0].mass_kg = 1.0f;
  s[1].vx_norm = 3.0f, s[1].wz_norm = 0.0f, s[1].mass_kg = 3.0f;
  s[2].vx_norm = 7.0f, s[2].mass_kg = 2.0f;
  const std::vector<CellIndex> cell{0, 0, 2};
  std::vector<tables::LaunchSample> mean(3);
  quantile_cell_means(s, cell, mean);
  EXPECT_FLOAT_EQ(mean[0].vx_norm, 2.5f);
  EXPECT_FLOAT_EQ(mean[0].wz_norm, 1.0f);
  EXPECT_FLOAT_EQ(mean[0].mass_kg, 4.0f);
  EXPECT_EQ(mean[1].mass_kg, 0.0f);  // empty
  EXPECT_FLOAT_EQ(mean[2].vx_norm, 7.0f);
}

TEST(QuantileCells, BadInputIsRefusedNamingTheProblem) {
  std::vector<std::uint32_t> order(2);
  std::vector<CellIndex> cell(2);
  auto message = [&](std::vector<double> k, std::vector<double> m, QuantileCellCounts counts) {
    try {
      assign_quantile_cells(k, k, m, counts, order, cell);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::vector<double> key{1.0, 2.0}, mass{1.0, 1.0};
  EXPECT_EQ(message(key, mass, {2, 1}), "accepted");
  EXPECT_NE(message({1.0, std::numeric_limits<double>::quiet_NaN()}, mass, {1, 1}).find("key of sample 1"),
            std::string::npos);
  EXPECT_NE(message(key, {1.0, 0.0}, {1, 1}).find("mass of sample 1"), std::string::npos);
  EXPECT_NE(message(key, mass, {0, 1}).find("counts"), std::string::npos);
  EXPECT_NE(message({1.0}, {1.0}, {1, 1}).find("size"), std::string::npos);
  EXPECT_NE(message({}, {}, {1, 1}).find("empty"), std::string::npos);
}

// Rows uniform on [0, 1] (300 samples) and on [1, 3] (457 samples): the interpolated quantile function
// is Q_t(u) = (1 − t)·u + t·(1 + 2u). Cells move to their interpolated means and keep their own spread
// (1/16 of a row's range), so each quantile is within ~one cell width (2/16 of the upper row) of Q_t. A
// mixture would keep both supports: its 99.5 % quantile at t = 0.5 is ~2.98, not 1.995.
TEST(InterpolateByQuantileCells, QuantilesMoveLinearlyBetweenShiftedAndScaledRows) {
  const Celled a = uniform_row(300, 0.0, 1.0), b = uniform_row(457, 1.0, 3.0);
  std::vector<tables::LaunchSample> out(757);
  std::vector<double> w(757);
  double ma = 0, mb = 0;
  for (const auto& s : a.samples) ma += s.mass_kg;
  for (const auto& s : b.samples) mb += s.mass_kg;
  for (double t : {0.25, 0.5, 0.8}) {
    SCOPED_TRACE(t);
    const std::size_t count = interpolate_by_quantile_cells(a.view(), b.view(), t, out, w);
    ASSERT_EQ(count, 757u);
    for (double q : {0.005, 0.1, 0.5, 0.9, 0.995}) {
      const double expected = (1.0 - t) * q + t * (1.0 + 2.0 * q);
      EXPECT_NEAR(quantile(out, w, count, q), expected, 0.1) << q;
    }
    // Velocity components move together (vy = 2 vx in both rows); diameters are the granules' own.
    for (std::size_t k = 0; k < count; ++k) EXPECT_NEAR(out[k].vy_norm, 2.0f * out[k].vx_norm, 1e-5);
    EXPECT_EQ(out[0].diameter_m, a.samples[0].diameter_m);
    EXPECT_NEAR(std::accumulate(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(count), 0.0),
                (1 - t) * ma + t * mb, 1e-9 * ma);
  }
}

// Two rows drawn from the same distribution (different counts) interpolate to that distribution: no
// granule is averaged with another, so nothing shrinks.
TEST(InterpolateByQuantileCells, RowsOfOneDistributionGiveThatDistribution) {
  const Celled a = uniform_row(300, 0.0, 1.0), b = uniform_row(457, 0.0, 1.0);
  std::vector<tables::LaunchSample> out(757);
  std::vector<double> w(757);
  const std::size_t count = interpolate_by_quantile_cells(a.view(), b.view(), 0.5, out, w);
  for (double q : {0.005, 0.05, 0.5, 0.95, 0.995}) EXPECT_NEAR(quantile(out, w, count, q), q, 0.01) << q;
}

// At t = 0 the lower row's granules are unchanged with their own masses and the upper row weighs 0;
// at t = 1 the other way round.
TEST(InterpolateByQuantileCells, EndpointsReproduceEachRow) {
  const Celled a = uniform_row(120, 0.0, 1.0), b = uniform_row(77, 1.0, 3.0);
  std::vector<tables::LaunchSample> out(197);
  std::vector<double> w(197);
  ASSERT_EQ(interpolate_by_quantile_cells(a.view(), b.view(), 0.0, out, w), 197u);
  for (std::size_t k = 0; k < 120; ++k) {
    EXPECT_EQ(out[k].vx_norm, a.samples[k].vx_norm);
    EXPECT_EQ(w[k], double{a.samples[k].mass_kg});
  }
  for (std::size_t k = 120; k < 197; ++k) EXPECT_EQ(w[k], 0.0);
  ASSERT_EQ(interpolate_by_quantile_cells(a.view(), b.view(), 1.0, out, w), 197u);
  for (std::size_t k = 0; k < 77; ++k) {
    EXPECT_EQ(out[120 + k].vx_norm, b.samples[k].vx_norm);
    EXPECT_EQ(w[120 + k], double{b.samples[k].mass_kg});
  }
}

TEST(InterpolateByQuantileCells, IsDeterministicAndChecksItsArguments) {
  const Celled a = uniform_row(50, 0.0, 1.0), b = uniform_row(31, 1.0, 3.0);
  std::vector<tables::LaunchSample> out1(81), out2(81);
  std::vector<double> w1(81), w2(81);
  ASSERT_EQ(interpolate_by_quantile_cells(a.view(), b.view(), 0.3, out1, w1), 81u);
  ASSERT_EQ(interpolate_by_quantile_cells(a.view(), b.view(), 0.3, out2, w2), 81u);
  for (std::size_t k = 0; k < 81; ++k) {
    EXPECT_EQ(out1[k].vx_norm, out2[k].vx_norm);
    EXPECT_EQ(w1[k], w2[k]);
  }
  std::vector<tables::LaunchSample> small(80);
  EXPECT_THROW(interpolate_by_quantile_cells(a.view(), b.view(), 0.3, small, w1), std::length_error);
  CelledRow fewer_cells = a.view();
  fewer_cells.cell_mean = fewer_cells.cell_mean.first(8);
  EXPECT_THROW(interpolate_by_quantile_cells(fewer_cells, b.view(), 0.3, out1, w1), std::invalid_argument);
  CelledRow short_cells = a.view();
  short_cells.cell_of_sample = short_cells.cell_of_sample.first(49);
  EXPECT_THROW(interpolate_by_quantile_cells(short_cells, b.view(), 0.3, out1, w1), std::invalid_argument);
}

}  // namespace
}  // namespace spread::predict
