// Tray layout, accumulation into trays, and the twin-disc mirror (docs/design.md §3).
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/metrics/wide_kernel.hpp"

namespace sm = spread::metrics;

TEST(TrayLayout, CoversTheExtentSymmetrically) {
  const sm::TrayLayout t = sm::tray_layout_covering(12.0, 0.5);
  EXPECT_EQ(t.tray_count, 48);
  EXPECT_DOUBLE_EQ(t.left_edge_m(), -12.0);
  EXPECT_DOUBLE_EQ(t.centre_m(0), -11.75);
  EXPECT_EQ(sm::tray_layout_covering(12.1, 0.5).tray_count, 49);
  EXPECT_EQ(sm::tray_layout_covering(0.0, 0.5).tray_count, 0);
  EXPECT_THROW(sm::tray_layout_covering(12.0, 0.0), std::invalid_argument);
  EXPECT_THROW(sm::tray_layout_covering(-1.0, 0.5), std::invalid_argument);
}

TEST(Accumulate, OneDiscPutsMassInItsTrayAndCountsLoss) {
  sm::TrayLayout trays;
  trays.tray_count = 4;  // edges -1, -0.5, 0, 0.5, 1
  const sm::MachineLayout one{1, 0.0};
  const std::vector<double> x{-0.9, -0.5, 0.0, 0.99, 1.0, -1.2, std::nan("")};
  const std::vector<double> m{1, 2, 3, 4, 5, 6, 7};
  std::vector<double> tray(4, 0.0);
  const double lost = sm::accumulate_transverse(x, m, one, trays, tray);
  EXPECT_EQ(tray, (std::vector<double>{1, 2, 3, 4}));  // half-open trays: -0.5 → tray 1, 0 → tray 2
  EXPECT_DOUBLE_EQ(lost, 5 + 6 + 7);                  // x = 1 is outside, x = -1.2 too, NaN too
  // Accumulates (does not clear).
  sm::accumulate_transverse(x, m, one, trays, tray);
  EXPECT_EQ(tray, (std::vector<double>{2, 4, 6, 8}));
}

TEST(Accumulate, TwinDiscMirrorsTheLeftDiscAtTheSpacing) {
  // A left-disc sample at +a relative to its centre (at -s/2) lands at a - s/2; the right disc's
  // mirror image lands at s/2 - a.
  sm::TrayLayout trays;
  trays.tray_count = 40;  // [-10, 10] m
  const double s = 1.0;
  const sm::MachineLayout twin{2, s};
  const std::vector<double> x{4.2};
  const std::vector<double> m{1.0};
  std::vector<double> tray(40, 0.0);
  EXPECT_EQ(sm::accumulate_transverse(x, m, twin, trays, tray), 0.0);
  const int left = static_cast<int>(std::floor((4.2 - 0.5 + 10.0) / 0.5));
  const int right = static_cast<int>(std::floor((0.5 - 4.2 + 10.0) / 0.5));
  for (int k = 0; k < 40; ++k) {
    EXPECT_DOUBLE_EQ(tray[static_cast<std::size_t>(k)], (k == left || k == right) ? 1.0 : 0.0) << k;
  }
}

TEST(Accumulate, TwinDiscEqualsOneDiscWithBothImages) {
  sm::TrayLayout trays;
  trays.tray_count = 60;
  const double s = 0.9;
  std::vector<double> x, m, x_both, m_both;
  for (int i = 0; i < 200; ++i) {
    const double xi = -3.0 + 0.061 * i;  // left-disc samples, relative to that disc's centre
    x.push_back(xi);
    m.push_back(0.001 * (1 + i % 7));
    x_both.push_back(xi - 0.5 * s);
    x_both.push_back(0.5 * s - xi);
    m_both.push_back(m.back());
    m_both.push_back(m.back());
  }
  std::vector<double> twin(60, 0.0), one(60, 0.0);
  sm::accumulate_transverse(x, m, sm::MachineLayout{2, s}, trays, twin);
  sm::accumulate_transverse(x_both, m_both, sm::MachineLayout{1, 0.0}, trays, one);
  EXPECT_EQ(twin, one);
  // The machine pattern is symmetric, so its two overlaps agree.
  for (int k = 0; k < 60; ++k) {
    EXPECT_NEAR(twin[static_cast<std::size_t>(k)], twin[static_cast<std::size_t>(59 - k)], 1e-15) << k;
  }
  // Widening the spacing by 2 trays moves the left image one tray left and the right one tray right.
  std::vector<double> wider(60, 0.0), left_only(60, 0.0), left_wider(60, 0.0);
  sm::accumulate_transverse(x, m, sm::MachineLayout{2, s + 1.0}, trays, wider);
  std::vector<double> x_left, x_left_wider;
  for (double xi : x) {
    x_left.push_back(xi - 0.5 * s);
    x_left_wider.push_back(xi - 0.5 * s - 0.5);
  }
  sm::accumulate_transverse(x_left, m, sm::MachineLayout{1, 0.0}, trays, left_only);
  sm::accumulate_transverse(x_left_wider, m, sm::MachineLayout{1, 0.0}, trays, left_wider);
  for (int k = 1; k < 60; ++k) {
    EXPECT_NEAR(left_wider[static_cast<std::size_t>(k - 1)], left_only[static_cast<std::size_t>(k)], 1e-15) << k;
  }
  for (int k = 0; k < 60; ++k) {
    EXPECT_NEAR(wider[static_cast<std::size_t>(k)],
                left_wider[static_cast<std::size_t>(k)] + left_wider[static_cast<std::size_t>(59 - k)], 1e-15);
  }
}

TEST(Accumulate, RejectsBadInput) {
  sm::TrayLayout trays;
  trays.tray_count = 4;
  std::vector<double> tray(4), x(3), m(2);
  EXPECT_THROW(sm::accumulate_transverse(x, m, sm::MachineLayout{}, trays, tray), std::invalid_argument);
  std::vector<double> m3(3);
  EXPECT_THROW(sm::accumulate_transverse(x, m3, sm::MachineLayout{3, 0.0}, trays, tray), std::invalid_argument);
  std::vector<double> tray5(5);
  EXPECT_THROW(sm::accumulate_transverse(x, m3, sm::MachineLayout{}, trays, tray5), std::invalid_argument);
  // Empty spans: nothing added, nothing lost.
  EXPECT_EQ(sm::accumulate_transverse({}, {}, sm::MachineLayout{}, trays, tray), 0.0);
}

// A kernel many trays wide binned by difference arrays (wide_kernel.hpp) puts the same mass in every tray
// and the same mass outside the layout as tray by tray, within the rounding the header states; landings
// near and beyond both outer edges and a non-finite one included.
TEST(WideKernel, BinsAsTrayByTrayWithinRounding) {
  sm::TrayLayout trays;
  trays.tray_width_m = 0.1;
  trays.tray_count = 400;  // [-20, 20] m
  std::vector<double> x, m;
  for (int i = 0; i < 3000; ++i) {
    x.push_back(-24.0 + 48.0 * std::fmod(0.618033988749895 * i, 1.0));
    m.push_back(1e-5 * (1.0 + 0.5 * std::sin(0.1 * i)));
  }
  x.push_back(std::nan(""));
  m.push_back(2e-5);
  double total = 0.0;
  for (double v : m) total += v;
  for (double h : {0.2, 0.37, 0.8, 2.5, 10.0}) {
    ASSERT_TRUE(sm::wide_kernel(h, trays));
    std::vector<double> direct(400, 0.0), wide(400, 0.0), scratch(sm::wide_kernel_scratch_size(trays));
    const double lost_direct = sm::accumulate_transverse_kernel(x, m, trays, h, direct);
    const double lost_wide = sm::accumulate_transverse_kernel(x, m, trays, h, wide, scratch);
    EXPECT_NEAR(lost_wide, lost_direct, 1e-12 * total) << h;
    double worst = 0.0;
    for (int k = 0; k < 400; ++k) worst = std::max(worst, std::abs(wide[k] - direct[k]));
    EXPECT_LT(worst, 1e-12 * total) << "h " << h << " m";
  }
  // Without scratch, or for a kernel of a few trays, the tray-by-tray sum itself.
  std::vector<double> a(400, 0.0), b(400, 0.0), scratch(sm::wide_kernel_scratch_size(trays));
  sm::accumulate_transverse_kernel(x, m, trays, 0.15, a);
  sm::accumulate_transverse_kernel(x, m, trays, 0.15, b, scratch);
  EXPECT_EQ(a, b);
}

// The kernel binned two trays at a time gives every tray the bits of its share taken alone, m (F(u_right)
// − F(u_left)) with F the Epanechnikov CDF at the tray's edges: kernels from under one tray to several,
// landings at and across the outer edges.
TEST(TransverseKernel, TraysTwoAtATimeAreTheBitsOfEachAlone) {
  sm::TrayLayout trays;
  trays.tray_width_m = 0.1;
  trays.tray_count = 120;  // [-6, 6] m
  const double left_m = trays.left_edge_m();
  std::vector<double> x, m;
  for (int i = 0; i < 1500; ++i) {
    x.push_back(-7.0 + 14.0 * std::fmod(0.618033988749895 * i, 1.0));
    m.push_back(1e-4 * (1.0 + 0.5 * std::sin(0.3 * i)));
  }
  x.push_back(left_m + 1.0);  // a landing exactly on an edge
  m.push_back(1e-4);
  for (double h : {0.04, 0.1, 0.2, 0.25, 0.37, 0.79}) {
    // Landings one at a time, four at a time and eight (AVX-512, where the processor has it).
    std::vector<double> binned(120, 0.0), one_by_one(120, 0.0), in_four(120, 0.0), in_eight(120, 0.0);
    const double lost = sm::accumulate_transverse_kernel(x, m, trays, h, binned);
    EXPECT_EQ(sm::detail::accumulate_transverse_kernel_in_lanes(x, m, trays, h, one_by_one, 1), lost) << h;
    EXPECT_EQ(sm::detail::accumulate_transverse_kernel_in_lanes(x, m, trays, h, in_four, 4), lost) << h;
    EXPECT_EQ(sm::detail::accumulate_transverse_kernel_in_lanes(x, m, trays, h, in_eight, 8), lost) << h;
    EXPECT_EQ(one_by_one, binned) << h;
    EXPECT_EQ(in_four, binned) << h;
    EXPECT_EQ(in_eight, binned) << h;
    std::vector<double> alone(120, 0.0);
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (x[i] + h <= left_m || x[i] - h >= -left_m) continue;
      for (int k = 0; k < 120; ++k) {
        const double lower = (left_m + static_cast<double>(k) * 0.1 - x[i]) * (1.0 / h);
        const double upper = (left_m + static_cast<double>(k + 1) * 0.1 - x[i]) * (1.0 / h);
        if (upper <= -1.0 || lower >= 1.0) continue;  // the kernel does not reach this tray
        alone[static_cast<std::size_t>(k)] += m[i] * (sm::epanechnikov_cdf(upper) - sm::epanechnikov_cdf(lower));
      }
    }
    for (int k = 0; k < 120; ++k) EXPECT_EQ(binned[static_cast<std::size_t>(k)], alone[static_cast<std::size_t>(k)]) << "h " << h << " tray " << k;
  }
}

// The standard errors' dot products from prefix sums, in AVX registers or SSE ones, for counts of
// gradients that fill four lanes, two and one: the same bits.
TEST(WideKernel, DotsInAvxAndSseAreTheSameBits) {
  sm::TrayLayout trays;
  trays.tray_width_m = 0.1;
  trays.tray_count = 200;
  for (std::size_t count : {1u, 2u, 7u}) {
    std::vector<std::vector<double>> gradients(count, std::vector<double>(200));
    std::vector<std::span<const double>> spans;
    for (std::size_t g = 0; g < count; ++g) {
      for (std::size_t k = 0; k < 200; ++k) gradients[g][k] = std::sin(0.07 * static_cast<double>(k * (g + 1)) + 0.3);
      spans.emplace_back(gradients[g]);
    }
    std::vector<double> sums(sm::wide_kernel_sums_size(trays, count));
    sm::wide_kernel_sums(spans, trays, sums);
    sm::WideKernelDots sse(0.37, trays, sums, count), avx(0.37, trays, sums, count);
    sse.set_avx(false);
    const bool has_avx = avx.set_avx(true);
    std::vector<double> a(count), b(count);
    for (int i = 0; i < 500; ++i) {
      const double x = -11.0 + 22.0 * std::fmod(0.618033988749895 * i, 1.0);
      sse(x, a.data());
      avx(x, b.data());
      ASSERT_EQ(a, b) << "x " << x << " count " << count;
    }
    if (!has_avx) GTEST_SKIP() << "no AVX here";
  }
}
