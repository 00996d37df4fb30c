#pragma once
// The objects behind the opaque handles: spread_tables (the predictor: table in memory, cells, and one
// workspace) and spread_workspace (one more workspace for another thread), both in memory from the
// caller's allocator, each with a tag that marks it live.
#include <cstddef>
#include <cstdint>
#include <memory_resource>

#include "capi/src/abi_layout.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "spread/spread.h"

namespace spread::capi {

// The caller's spread_allocator as a std::pmr::memory_resource, so that the predictor's buffers come
// from it. A NULL from alloc is std::bad_alloc (SPREAD_ERROR_OUT_OF_MEMORY at the entry point).
class CallerMemory final : public std::pmr::memory_resource {
 public:
  explicit CallerMemory(const spread_allocator& allocator) : allocator_(allocator) {}
  const spread_allocator& allocator() const { return allocator_; }

 private:
  void* do_allocate(std::size_t bytes, std::size_t alignment) override;
  void do_deallocate(void* pointer, std::size_t bytes, std::size_t alignment) override;
  bool do_is_equal(const std::pmr::memory_resource& other) const noexcept override { return this == &other; }
  spread_allocator allocator_;
};

// malloc / free (aligned_alloc above the fundamental alignment): what spread_open uses.
const spread_allocator& default_allocator();

// Tags: set by the constructors, overwritten with kDeadTag just before the memory is released. A live
// handle holds its tag; a closed one holds kDeadTag until the memory is reused (best effort).
inline constexpr std::uint64_t kTablesTag = 0x5350524541445442u;     // "SPREADTB"
inline constexpr std::uint64_t kWorkspaceTag = 0x5350524541445753u;  // "SPREADWS"
inline constexpr std::uint64_t kDeadTag = 0xDEADDEADDEADDEADu;

// A controller's limits: requests outside the landing grid's domain are refused unless they opt in to
// flying every launch sample (docs/c-api.md "Landing grid"), so the time of any request that does not
// opt in is the grid's. Trays at least 0.1 m wide: a fifth of the 0.5 m tray of ISO 5690 tray tests and
// finer than the kernel that smooths a table's few thousand launches (0.2–0.5 m half width on the
// default table), so narrower trays resolve nothing more — and the widest layout (2,000 trays over the
// ±100 m extent) bounds each handle's tray buffers and the kernel and standard-error passes.
inline constexpr double kControllerMinTrayWidth_m = 0.1;
inline predict::PredictorLimits controller_limits() {
  predict::PredictorLimits limits;
  limits.refuse_outside_domain = true;
  limits.min_tray_width_m = kControllerMinTrayWidth_m;
  return limits;
}

}  // namespace spread::capi

struct spread_tables {
  // The file is read with the samples going straight into a block from the caller's allocator; `flags`
  // are spread_open_with_flags' SPREAD_OPEN_* bits.
  spread_tables(const char* path, const spread_allocator& allocator, std::uint32_t flags)
      : memory(allocator), predictor(read(path, flags), spread::capi::controller_limits(), &memory) {
    for (std::size_t m = 0; m < predictor.material_count(); ++m) {
      if (!predictor.landing_data_from_table(m)) table_flags |= SPREAD_TABLE_LANDING_DATA_DERIVED;
    }
  }
  // The same handle over contents already read (in-tree tools: spread::capi::open_contents).
  spread_tables(spread::tables::TableContents contents, const spread_allocator& allocator)
      : memory(allocator), predictor(flag(std::move(contents)), spread::capi::controller_limits(), &memory) {
    for (std::size_t m = 0; m < predictor.material_count(); ++m) {
      if (!predictor.landing_data_from_table(m)) table_flags |= SPREAD_TABLE_LANDING_DATA_DERIVED;
    }
  }
  std::uint64_t tag = spread::capi::kTablesTag;  // first member: read before anything else
  spread::capi::CallerMemory memory;  // before the predictor: it outlives the predictor's buffers
  std::uint32_t table_flags = 0;      // SPREAD_TABLE_* bits (spread_table_flags); before the predictor
  spread::predict::Predictor predictor;
  // spread_predict's result before it is copied out (one thread at a time per handle): over a kilobyte with
  // its bands, kept here rather than on the caller's stack (spread.h: under 8 KiB, unoptimised too).
  spread::predict::Prediction prediction;

 private:
  spread::tables::TableContents read(const char* path, std::uint32_t flags) {
    spread::tables::ReadOptions options;
    options.legacy_files = (flags & SPREAD_OPEN_LEGACY_FILES) != 0;
    return flag(spread::tables::read_table_file(path, &memory, options));
  }
  spread::tables::TableContents flag(spread::tables::TableContents contents) {
    if (!contents.runs_listed) table_flags |= SPREAD_TABLE_RUNS_UNCHECKED;
    return contents;
  }
};

struct spread_workspace {
  explicit spread_workspace(const spread_tables& owner)
      : tables(&owner), memory(owner.memory.allocator()), workspace(owner.predictor, &memory) {}
  std::uint64_t tag = spread::capi::kWorkspaceTag;
  const spread_tables* tables;
  // Its own copy of the handle's allocator: freeing the workspace never touches the handle.
  spread::capi::CallerMemory memory;
  spread::predict::PredictorWorkspace workspace;
  spread::predict::Prediction prediction;  // as spread_tables::prediction, for this workspace's thread
};

namespace spread::capi {

inline bool live(const spread_tables* tables) { return tables->tag == kTablesTag; }
inline bool live(const spread_workspace* workspace) { return workspace->tag == kWorkspaceTag; }
// The tag store must not be dropped as a dead store before the memory is released.
inline void mark_dead(std::uint64_t& tag) { *static_cast<volatile std::uint64_t*>(&tag) = kDeadTag; }

}  // namespace spread::capi
