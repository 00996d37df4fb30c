// The span functions run in the C API's control loop and must not touch the heap. A counting global
// operator new in this test binary sees every allocation.
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

#include <gtest/gtest.h>

#include "libspread/analysis/metrics/metrics.hpp"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace sm = spread::metrics;

TEST(NoAllocation, SpanFunctionsDoNotAllocate) {
  std::vector<double> x, y, m;
  for (int i = 0; i < 512; ++i) {
    x.push_back(-8.0 + 0.031 * i);
    y.push_back(-5.0 + 0.019 * i);
    m.push_back(1e-4);
  }
  const sm::TrayLayout trays = sm::tray_layout_covering(20.0, 0.5);
  std::vector<double> tray(static_cast<std::size_t>(trays.tray_count), 0.0);
  std::vector<double> widths, cv;
  for (int n = 2; n <= trays.tray_count; ++n) widths.push_back(0.5 * n);
  cv.resize(widths.size());
  std::vector<double> bout(static_cast<std::size_t>(sm::bout_tray_count(trays, 18.0)));
  const sm::MachineLayout twin{2, 0.9};

  const long before = g_allocations.load();
  const double lost = sm::accumulate_transverse(x, m, twin, trays, tray);
  const double cv18 = sm::cv_at_width(tray, trays, 18.0, sm::Overlap::kToAndFro);
  sm::cv_curve(tray, trays, widths, sm::Overlap::kRacetrack, cv);
  sm::overlapped_profile(tray, trays, 18.0, sm::Overlap::kToAndFro, bout);
  const double w = sm::effective_working_width(tray, trays, sm::Overlap::kToAndFro, 0.15);
  const double tw = sm::throw_width(tray, trays);
  const sm::RadialStats r = sm::radial_statistics(x, y, m, 0.0, 0.0);
  const int n = sm::bout_tray_count(trays, 12.0);
  const long after = g_allocations.load();

  EXPECT_EQ(after - before, 0);
  // Use the results so nothing is optimised away, and check they are sane.
  EXPECT_EQ(lost, 0.0);
  EXPECT_TRUE(std::isfinite(cv18));
  EXPECT_GE(w, 0.0);
  EXPECT_GT(tw, 0.0);
  EXPECT_GT(r.mean_radius_m, 0.0);
  EXPECT_EQ(n, 24);
  // Sanity of the counter itself.
  std::vector<double>* probe = new std::vector<double>(3);
  EXPECT_GT(g_allocations.load(), after);
  delete probe;
}
