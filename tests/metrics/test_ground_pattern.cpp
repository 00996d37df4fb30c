// Ground pattern of the whole machine on a grid fitted to the landings.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "libspread/analysis/metrics/metrics.hpp"

namespace sm = spread::metrics;

TEST(GroundPattern, TwinDiscIsSymmetricAndHoldsBothDiscsMass) {
  std::vector<double> x, y, m;
  for (int i = 0; i < 300; ++i) {
    x.push_back(-6.0 + 0.037 * i);
    y.push_back(-4.0 + 0.023 * i);
    m.push_back(0.002);
  }
  const sm::GroundPattern g = sm::ground_pattern(x, y, m, sm::MachineLayout{2, 0.8}, 0.25);
  ASSERT_GT(g.nx, 0);
  ASSERT_GT(g.ny, 0);
  EXPECT_EQ(g.mass_kg.size(), static_cast<std::size_t>(g.nx * g.ny));
  EXPECT_NEAR(g.x0_m + 0.5 * g.nx * g.cell_m, 0.0, 1e-12);  // symmetric about x = 0
  double total = 0.0;
  for (double v : g.mass_kg) total += v;
  EXPECT_NEAR(total, 2 * 300 * 0.002, 1e-12);
  for (int iy = 0; iy < g.ny; ++iy) {
    for (int ix = 0; ix < g.nx; ++ix) {
      EXPECT_NEAR(g.density_kg_m2(ix, iy), g.density_kg_m2(g.nx - 1 - ix, iy), 1e-12);
    }
  }
  // Every landing is inside the grid with a margin: the border cells are empty.
  for (int ix = 0; ix < g.nx; ++ix) {
    EXPECT_EQ(g.mass_kg[static_cast<std::size_t>(ix)], 0.0);
    EXPECT_EQ(g.mass_kg[static_cast<std::size_t>((g.ny - 1) * g.nx + ix)], 0.0);
  }
}

TEST(GroundPattern, OneDiscCellByHand) {
  const std::vector<double> x{0.3}, y{1.1}, m{0.5};
  const sm::GroundPattern g = sm::ground_pattern(x, y, m, sm::MachineLayout{1, 0.0}, 0.5);
  // x: |0.3| lies in cell [0, 0.5) → grid from -1 m (one margin cell beyond) to 1 m, nx = 4.
  // y: 1.1 in [1.0, 1.5) → rows from 0.5 to 2.0, ny = 3.
  EXPECT_EQ(g.nx, 4);
  EXPECT_EQ(g.ny, 3);
  EXPECT_DOUBLE_EQ(g.x0_m, -1.0);
  EXPECT_DOUBLE_EQ(g.y0_m, 0.5);
  EXPECT_DOUBLE_EQ(g.density_kg_m2(2, 1), 0.5 / 0.25);
}

TEST(GroundPattern, EdgeCases) {
  const sm::GroundPattern none = sm::ground_pattern({}, {}, {}, sm::MachineLayout{}, 0.1);
  EXPECT_EQ(none.nx, 0);
  EXPECT_EQ(none.ny, 0);
  EXPECT_TRUE(none.mass_kg.empty());
  const std::vector<double> x{std::nan("")}, y{0.0}, m{1.0};
  EXPECT_EQ(sm::ground_pattern(x, y, m, sm::MachineLayout{}, 0.1).nx, 0);
  const std::vector<double> far{1e6}, y1{0.0};
  EXPECT_THROW(sm::ground_pattern(far, y1, m, sm::MachineLayout{}, 0.01), std::invalid_argument);
  EXPECT_THROW(sm::ground_pattern(y1, y1, m, sm::MachineLayout{}, 0.0), std::invalid_argument);
}
