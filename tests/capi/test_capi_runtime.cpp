// The C API in a controller: the stack a prediction needs (measured on a thread whose stack this test
// owns), per-thread workspaces on one shared handle, the caller's allocator, handle tags against double
// close and use after close, the thread-local error detail, and the trajectory's step cap.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "spread/spread.h"
#include "tests/capi/capi_test_files.hpp"
#include "tests/capi/stack_depth.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace {

using spread::testing::temp_path;

const std::string& table_path() {
  static const std::string path = [] {
    const std::string p = temp_path("runtime.sqlite");
    spread::testing::write_synthetic_table(p);
    return p;
  }();
  return path;
}

// Requests that reach the widest paths: narrow trays over the widest layout (4,000 trays), a high disc and
// a lateral wind (both discs fly), the widest bout a request may ask for, a wind along the track (the
// return pass of a to-and-fro field flown as well: two bouts).
std::vector<spread_prediction_def> requests() {
  std::vector<spread_prediction_def> defs;
  for (int k = 0; k < 4; ++k) {
    spread_prediction_def d = spread_prediction_def_default();
    d.material = k % 2 == 0 ? "can" : "urea";  // urea: rows of unequal count, interpolated by quantile cells
    d.rpm = 520.0 + 50.0 * k;
    defs.push_back(d);
  }
  defs[1].tray_width_m = 0.1;
  defs[1].disc_height_m = 50.0;
  defs[1].wind_m_s[0] = 20.0;
  defs[2].bout_width_m = 1000.0;
  defs[2].tray_width_m = 0.1;
  defs[3].wind_m_s[0] = -3.0;
  defs[3].wind_m_s[1] = 2.0;
  defs[3].cv_target_percent = 5.0;
  return defs;
}

struct Outcome {
  spread_status status = SPREAD_ERROR_INTERNAL;
  spread_prediction result{};
  std::vector<double> trays;
};

// Bitwise: the same computation on another thread or workspace must give the same bits.
void expect_same(const Outcome& a, const Outcome& b, const std::string& what) {
  ASSERT_EQ(a.status, SPREAD_OK) << what;
  ASSERT_EQ(b.status, SPREAD_OK) << what;
  EXPECT_EQ(std::memcmp(&a.result, &b.result, sizeof a.result), 0) << what;
  EXPECT_EQ(a.trays, b.trays) << what;
}

Outcome predict_on(spread_tables* tables, spread_workspace* workspace, const spread_prediction_def& def) {
  Outcome o;
  size_t capacity = 0;
  EXPECT_EQ(spread_transverse_bound(tables, def.tray_width_m, &capacity), SPREAD_OK);
  o.trays.assign(capacity, 0.0);
  std::memset(&o.result, 0, sizeof o.result);
  o.status = workspace != nullptr
                 ? spread_workspace_predict(workspace, &def, &o.result, o.trays.data(), o.trays.size())
                 : spread_predict(tables, &def, &o.result, o.trays.data(), o.trays.size());
  o.trays.resize(static_cast<std::size_t>(std::max(o.result.tray_count, 0)));
  return o;
}

TEST(CapiStack, PredictionNeedsLessThanTheStatedStackAndGivesTheSameResult) {
  using spread::testing::kSanitizedBuild;
  using spread::testing::kStatedStackBytes;
  spread_tables* tables = nullptr;
  ASSERT_EQ(spread_open(table_path().c_str(), &tables), SPREAD_OK);
  std::size_t need = 0;
  for (const spread_prediction_def& def : requests()) {
    const Outcome on_main = predict_on(tables, nullptr, def);
    // Measured on a roomy stack first (the paint shows the depth), then on a stack of the stated need plus
    // the thread's own start-up and a margin: 16 KiB, the smallest stack glibc allows (PTHREAD_STACK_MIN).
    Outcome roomy, small;
    auto on_roomy = [&] { roomy = predict_on(tables, nullptr, def); };
    need = std::max(need, spread::testing::stack_depth_of(on_roomy, 256 * 1024));
    expect_same(on_main, roomy, "256 KiB stack");
    if (!kSanitizedBuild) {
      auto on_small = [&] { small = predict_on(tables, nullptr, def); };
      spread::testing::stack_depth_of(on_small, 16 * 1024);
      expect_same(on_main, small, "16 KiB stack");
    }
  }
  // Under AddressSanitizer locals may live on its fake stack (detect_stack_use_after_return), so the
  // painted thread stack shows nothing: the need is measured in the plain build only.
  if (!kSanitizedBuild) {
    EXPECT_LE(need, kStatedStackBytes) << "stack need " << need << " bytes";
    EXPECT_GT(need, 0u);
  }
  std::printf("spread_predict stack need: %zu bytes\n", need);
  spread_close(tables);
}

TEST(CapiWorkspace, ThreadsWithWorkspacesOnOneHandleGiveTheHandlesResults) {
  spread_tables* tables = nullptr;
  ASSERT_EQ(spread_open(table_path().c_str(), &tables), SPREAD_OK);
  const std::vector<spread_prediction_def> defs = requests();
  std::vector<Outcome> expected;
  for (const auto& d : defs) expected.push_back(predict_on(tables, nullptr, d));

  constexpr int kThreads = 4;
  std::vector<spread_workspace*> workspaces(kThreads, nullptr);
  for (auto& w : workspaces) ASSERT_EQ(spread_workspace_create(tables, &w), SPREAD_OK);
  std::vector<std::vector<Outcome>> got(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int repeat = 0; repeat < 3; ++repeat) {
        for (std::size_t k = 0; k < defs.size(); ++k) {
          // Each thread starts at another request, so different requests overlap in time.
          const std::size_t i = (k + static_cast<std::size_t>(t)) % defs.size();
          Outcome o = predict_on(tables, workspaces[static_cast<std::size_t>(t)], defs[i]);
          if (repeat == 2) got[static_cast<std::size_t>(t)].push_back(std::move(o));
        }
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) {
    for (std::size_t k = 0; k < defs.size(); ++k) {
      const std::size_t i = (k + static_cast<std::size_t>(t)) % defs.size();
      expect_same(expected[i], got[static_cast<std::size_t>(t)][k], "thread " + std::to_string(t));
    }
  }
  for (auto* w : workspaces) spread_workspace_free(w);
  spread_close(tables);
}

// Counts the allocator's blocks; `fail_after` makes the n-th alloc fail; `keep` never releases memory
// (the blocks stay readable after free, so a test can touch a closed handle without undefined
// behaviour in the test itself).
struct CountingAllocator {
  std::mutex mutex;
  std::map<void*, std::size_t> live;
  std::vector<void*> kept;
  long allocs = 0, frees = 0, size_mismatches = 0;
  long fail_after = -1;
  bool keep = false;
  std::size_t live_bytes() {
    std::lock_guard<std::mutex> lock(mutex);
    std::size_t sum = 0;
    for (const auto& [p, n] : live) sum += n;
    return sum;
  }
  ~CountingAllocator() {
    for (void* p : kept) std::free(p);
  }
  static void* alloc(void* user, std::size_t size, std::size_t alignment) {
    auto* self = static_cast<CountingAllocator*>(user);
    std::lock_guard<std::mutex> lock(self->mutex);
    if (self->fail_after >= 0 && self->allocs >= self->fail_after) return nullptr;
    ++self->allocs;
    void* p = std::aligned_alloc(std::max<std::size_t>(alignment, alignof(std::max_align_t)),
                                 (std::max<std::size_t>(size, 1) + 63) / 64 * 64);
    self->live[p] = size;
    return p;
  }
  static void release(void* user, void* pointer, std::size_t size) {
    auto* self = static_cast<CountingAllocator*>(user);
    std::lock_guard<std::mutex> lock(self->mutex);
    ++self->frees;
    const auto it = self->live.find(pointer);
    if (it == self->live.end() || it->second != size) ++self->size_mismatches;
    if (it != self->live.end()) self->live.erase(it);
    if (self->keep) {
      self->kept.push_back(pointer);
    } else {
      std::free(pointer);
    }
  }
  spread_allocator c() { return spread_allocator{alloc, release, this}; }
};

TEST(CapiAllocator, EveryHandleAndWorkspaceBlockComesFromTheCallerAndGoesBack) {
  CountingAllocator counting;
  const spread_allocator allocator = counting.c();
  spread_tables* tables = nullptr;
  ASSERT_EQ(spread_open_with_allocator(table_path().c_str(), &allocator, &tables), SPREAD_OK);
  const long after_open = counting.allocs;
  const std::size_t table_bytes = counting.live_bytes();
  EXPECT_GT(after_open, 3);
  spread_workspace* workspace = nullptr;
  ASSERT_EQ(spread_workspace_create(tables, &workspace), SPREAD_OK);
  const std::size_t workspace_bytes = counting.live_bytes() - table_bytes;
  EXPECT_GT(workspace_bytes, 0u);
  EXPECT_GT(counting.allocs, after_open);
  // Predictions take nothing from it.
  const long before_predict = counting.allocs;
  for (const auto& d : requests()) {
    EXPECT_EQ(predict_on(tables, workspace, d).status, SPREAD_OK);
    EXPECT_EQ(predict_on(tables, nullptr, d).status, SPREAD_OK);
  }
  EXPECT_EQ(counting.allocs, before_predict);
  // The same results as a handle on the C++ heap.
  spread_tables* plain = nullptr;
  ASSERT_EQ(spread_open(table_path().c_str(), &plain), SPREAD_OK);
  for (const auto& d : requests()) expect_same(predict_on(plain, nullptr, d), predict_on(tables, workspace, d), "allocator");
  spread_close(plain);
  spread_workspace_free(workspace);
  EXPECT_EQ(counting.live_bytes(), table_bytes);
  spread_close(tables);
  EXPECT_EQ(counting.live_bytes(), 0u);
  EXPECT_EQ(counting.allocs, counting.frees);
  EXPECT_EQ(counting.size_mismatches, 0);
}

TEST(CapiAllocator, FailingAllocatorIsOutOfMemoryWithoutLeaks) {
  for (long fail_after : {0L, 1L, 3L}) {
    CountingAllocator counting;
    counting.fail_after = fail_after;
    const spread_allocator allocator = counting.c();
    spread_tables* tables = reinterpret_cast<spread_tables*>(0x1);
    EXPECT_EQ(spread_open_with_allocator(table_path().c_str(), &allocator, &tables), SPREAD_ERROR_OUT_OF_MEMORY);
    EXPECT_EQ(tables, nullptr);
    EXPECT_EQ(counting.live_bytes(), 0u) << fail_after;
    EXPECT_NE(std::string(spread_last_error_detail()).find("out of memory"), std::string::npos);
  }
  // A workspace that cannot be allocated.
  CountingAllocator counting;
  const spread_allocator allocator = counting.c();
  spread_tables* tables = nullptr;
  ASSERT_EQ(spread_open_with_allocator(table_path().c_str(), &allocator, &tables), SPREAD_OK);
  counting.fail_after = counting.allocs + 2;
  spread_workspace* workspace = reinterpret_cast<spread_workspace*>(0x1);
  EXPECT_EQ(spread_workspace_create(tables, &workspace), SPREAD_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(workspace, nullptr);
  spread_close(tables);
  EXPECT_EQ(counting.live_bytes(), 0u);
}

TEST(CapiAllocator, NullAllocatorIsRefused) {
  spread_tables* tables = nullptr;
  EXPECT_EQ(spread_open_with_allocator(table_path().c_str(), nullptr, &tables), SPREAD_ERROR_NULL_POINTER);
  spread_allocator half{CountingAllocator::alloc, nullptr, nullptr};
  EXPECT_EQ(spread_open_with_allocator(table_path().c_str(), &half, &tables), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(tables, nullptr);
}

TEST(CapiHandleTag, DoubleCloseAndUseAfterCloseAreBadHandle) {
  // The allocator keeps freed blocks readable: what is checked is the library's tag, not the luck of
  // the C heap (with malloc the check reads freed memory: best effort, docs/c-api.md).
  CountingAllocator counting;
  counting.keep = true;
  const spread_allocator allocator = counting.c();
  spread_tables* tables = nullptr;
  ASSERT_EQ(spread_open_with_allocator(table_path().c_str(), &allocator, &tables), SPREAD_OK);
  spread_workspace* workspace = nullptr;
  ASSERT_EQ(spread_workspace_create(tables, &workspace), SPREAD_OK);
  spread_workspace_free(workspace);
  const long frees = counting.frees;
  spread_workspace_free(workspace);  // double free of a workspace: left alone
  EXPECT_EQ(counting.frees, frees);
  EXPECT_NE(std::string(spread_last_error_detail()).find("spread_workspace_free"), std::string::npos);
  const spread_prediction_def d = requests()[0];
  spread_prediction r{};
  EXPECT_EQ(spread_workspace_predict(workspace, &d, &r, nullptr, 0), SPREAD_ERROR_BAD_HANDLE);

  spread_workspace* orphan = nullptr;  // a live workspace whose handle gets closed under it
  ASSERT_EQ(spread_workspace_create(tables, &orphan), SPREAD_OK);
  spread_close(tables);
  const long frees_after_close = counting.frees;
  spread_close(tables);  // double close: left alone
  EXPECT_EQ(counting.frees, frees_after_close);
  EXPECT_NE(std::string(spread_last_error_detail()).find("spread_close"), std::string::npos);
  EXPECT_EQ(spread_predict(tables, &d, &r, nullptr, 0), SPREAD_ERROR_BAD_HANDLE);
  EXPECT_EQ(spread_workspace_predict(orphan, &d, &r, nullptr, 0), SPREAD_ERROR_BAD_HANDLE);
  int32_t count = 0;
  EXPECT_EQ(spread_material_count(tables, &count), SPREAD_ERROR_BAD_HANDLE);
  const char* name = nullptr;
  EXPECT_EQ(spread_material_name(tables, 0, &name), SPREAD_ERROR_BAD_HANDLE);
  double lo = 0.0, hi = 0.0, h = 0.0;
  EXPECT_EQ(spread_material_rpm_range(tables, 0, &lo, &hi), SPREAD_ERROR_BAD_HANDLE);
  EXPECT_EQ(spread_default_disc_height(tables, &h), SPREAD_ERROR_BAD_HANDLE);
  size_t bound = 0;
  EXPECT_EQ(spread_transverse_bound(tables, 0.5, &bound), SPREAD_ERROR_BAD_HANDLE);
  spread_workspace* late = nullptr;
  EXPECT_EQ(spread_workspace_create(tables, &late), SPREAD_ERROR_BAD_HANDLE);
  EXPECT_EQ(late, nullptr);
  EXPECT_STRNE(spread_status_str(SPREAD_ERROR_BAD_HANDLE), "unknown status");
  // A workspace freed after its handle (against the documented order) still gives its blocks back.
  spread_workspace_free(orphan);
  EXPECT_EQ(counting.live_bytes(), 0u);
}

TEST(CapiErrorDetail, NamesTheRefusedArgumentAndIsPerThread) {
  spread_tables* tables = nullptr;
  ASSERT_EQ(spread_open(table_path().c_str(), &tables), SPREAD_OK);
  spread_prediction_def d = requests()[0];
  d.material = "gravel";
  spread_prediction r{};
  ASSERT_EQ(spread_predict(tables, &d, &r, nullptr, 0), SPREAD_ERROR_UNKNOWN_MATERIAL);
  EXPECT_NE(std::string(spread_last_error_detail()).find("gravel"), std::string::npos);
  d = requests()[0];
  d.rpm = 9000.0;
  ASSERT_EQ(spread_predict(tables, &d, &r, nullptr, 0), SPREAD_ERROR_RPM_OUTSIDE_TABLE);
  const std::string rpm_detail = spread_last_error_detail();
  EXPECT_NE(rpm_detail.find("9000"), std::string::npos) << rpm_detail;
  d = requests()[0];
  d.disc_height_m = 150.0;
  ASSERT_EQ(spread_predict(tables, &d, &r, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_NE(std::string(spread_last_error_detail()).find("disc_height_m 150"), std::string::npos);
  // Another thread has its own (empty) detail, and its failure does not touch this thread's.
  std::string other_before, other_after;
  std::thread([&] {
    other_before = spread_last_error_detail();
    spread_prediction_def bad = requests()[0];
    bad.material = "slag";
    spread_prediction rr{};
    spread_predict(tables, &bad, &rr, nullptr, 0);
    other_after = spread_last_error_detail();
  }).join();
  EXPECT_EQ(other_before, "");
  EXPECT_NE(other_after.find("slag"), std::string::npos);
  EXPECT_NE(std::string(spread_last_error_detail()).find("disc_height_m 150"), std::string::npos);
  spread_close(tables);
}

TEST(CapiTrajectory, DustStopsAtTheStepCapNotAfterAMillionSteps) {
  // 1 µm dust: its drag relaxation time is nanoseconds, so the explicit integrator crawls; the call gives
  // up after the documented step cap (a bounded time) with NOT_LANDED.
  spread_trajectory_def def = spread_trajectory_def_default();
  def.diameter_m = 1e-6;
  def.density_kg_m3 = 1.0;
  spread_landing landing{};
  EXPECT_EQ(spread_trajectory(&def, &landing), SPREAD_ERROR_NOT_LANDED);
  EXPECT_GT(landing.steps, 1000);
  EXPECT_LE(landing.steps, 3072);  // predict::kMaxFlightSteps
  EXPECT_NE(std::string(spread_last_error_detail()).find("steps"), std::string::npos);
  // A spreader granule still lands well within it.
  def = spread_trajectory_def_default();
  def.velocity_m_s[0] = 30.0;
  def.position_m[2] = 50.0;
  ASSERT_EQ(spread_trajectory(&def, &landing), SPREAD_OK);
  EXPECT_LT(landing.steps, 300);
}

}  // namespace
