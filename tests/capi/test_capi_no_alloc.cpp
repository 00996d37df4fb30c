// spread_predict must not allocate (docs/design.md §5): this binary replaces malloc & co. (glibc lets an
// executable interpose them; operator new goes through malloc) and counts calls while a flag is set.
// The same hook, told to fail, shows spread_open turning an allocation failure into
// SPREAD_ERROR_OUT_OF_MEMORY instead of an exception crossing into C.
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include "spread/spread.h"
#include "tests/capi/capi_test_files.hpp"
#include "tests/predict/synthetic_table.hpp"

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
void __libc_free(void* pointer);
}

namespace {
std::atomic<bool> g_counting{false};
std::atomic<bool> g_failing{false};
std::atomic<long> g_calls{0};

bool note_call() {
  if (g_counting.load(std::memory_order_relaxed)) g_calls.fetch_add(1, std::memory_order_relaxed);
  return !g_failing.load(std::memory_order_relaxed);
}
}  // namespace

extern "C" {
void* malloc(std::size_t size) { return note_call() ? __libc_malloc(size) : nullptr; }
void* calloc(std::size_t count, std::size_t size) { return note_call() ? __libc_calloc(count, size) : nullptr; }
void* realloc(void* pointer, std::size_t size) { return note_call() ? __libc_realloc(pointer, size) : nullptr; }
void* memalign(std::size_t alignment, std::size_t size) {
  return note_call() ? __libc_memalign(alignment, size) : nullptr;
}
void* aligned_alloc(std::size_t alignment, std::size_t size) { return memalign(alignment, size); }
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
  void* p = memalign(alignment, size);
  if (p == nullptr) return 12;  // ENOMEM
  *out = p;
  return 0;
}
void free(void* pointer) { __libc_free(pointer); }
}

namespace {

class CountingScope {
 public:
  CountingScope() {
    g_calls = 0;
    g_counting = true;
  }
  ~CountingScope() { g_counting = false; }
  long calls() const { return g_calls.load(); }
};

TEST(CapiNoAllocation, HookSeesAllocations) {
  CountingScope scope;
  std::vector<double>* v = new std::vector<double>(100);  // must be counted, or the test proves nothing
  const long seen = scope.calls();
  delete v;
  EXPECT_GE(seen, 2);
}

TEST(CapiNoAllocation, PredictDoesNotAllocate) {
  const std::string path = spread::testing::temp_path("no-alloc.sqlite");
  spread::testing::write_synthetic_table(path);
  spread_tables* tables = nullptr;
  ASSERT_EQ(spread_open(path.c_str(), &tables), SPREAD_OK);
  size_t bound = 0;
  ASSERT_EQ(spread_transverse_bound(tables, 0.5, &bound), SPREAD_OK);
  std::vector<double> trays(bound);
  spread_prediction result{};

  // Exact row, interpolated pairwise, mixture rows, lateral wind (both discs flown), refusals.
  struct Case {
    const char* material;
    double rpm;
    double wind_x_m_s;
    spread_status expected;
  };
  const Case cases[] = {{"can", 600.0, 0.0, SPREAD_OK},
                        {"can", 655.5, 0.0, SPREAD_OK},
                        {"urea", 612.0, 0.0, SPREAD_OK},
                        {"can", 700.0, 3.0, SPREAD_OK},
                        {"gravel", 600.0, 0.0, SPREAD_ERROR_UNKNOWN_MATERIAL},
                        {"can", 900.0, 0.0, SPREAD_ERROR_RPM_OUTSIDE_TABLE}};
  for (const Case& c : cases) {
    spread_prediction_def def = spread_prediction_def_default();
    def.material = c.material;
    def.rpm = c.rpm;
    def.wind_m_s[0] = c.wind_x_m_s;
    spread_status status;
    long calls;
    {
      CountingScope scope;
      status = spread_predict(tables, &def, &result, trays.data(), trays.size());
      calls = scope.calls();
    }
    EXPECT_EQ(status, c.expected) << c.material << " " << c.rpm;
    EXPECT_EQ(calls, 0) << c.material << " " << c.rpm << " wind " << c.wind_x_m_s;
  }
  {
    // Each disc at its own setting, and the wind compensation's search (45 or so predictions).
    spread_prediction_def def = spread_prediction_def_default();
    def.material = "can";
    def.rpm = 0.0;
    def.disc_rpm[0] = 620.0;
    def.disc_rpm[1] = 700.0;
    def.bout_width_m = 12.0;
    def.wind_m_s[0] = 3.0;
    CountingScope scope;
    EXPECT_EQ(spread_predict(tables, &def, &result, trays.data(), trays.size()), SPREAD_OK);
    EXPECT_EQ(spread_compensate_wind(tables, &def, &result, trays.data(), trays.size()), SPREAD_OK);
    EXPECT_EQ(scope.calls(), 0);
  }
  {
    spread_trajectory_def t = spread_trajectory_def_default();
    spread_landing landing{};
    CountingScope scope;
    EXPECT_EQ(spread_trajectory(&t, &landing), SPREAD_OK);
    EXPECT_EQ(scope.calls(), 0);
  }
  spread_close(tables);
}

TEST(CapiNoAllocation, OpenReportsOutOfMemory) {
  const std::string path = spread::testing::temp_path("oom.sqlite");
  spread::testing::write_synthetic_table(path);
  spread_tables* tables = reinterpret_cast<spread_tables*>(0x1);
  g_failing = true;
  const spread_status status = spread_open(path.c_str(), &tables);
  g_failing = false;
  EXPECT_EQ(status, SPREAD_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(tables, nullptr);
}

}  // namespace
