// spread_open / spread_close, the workspaces and the table queries. Every entry point catches everything:
// no C++ exception may unwind into C (docs/design.md §5).
#include <cmath>
#include <cstdlib>
#include <new>

#include "capi/src/error_detail.hpp"
#include "capi/src/fault_seam.hpp"
#include "capi/src/tables_handle.hpp"

namespace spread::capi {

void* CallerMemory::do_allocate(std::size_t bytes, std::size_t alignment) {
  void* pointer = allocator_.alloc(allocator_.user, bytes, alignment);
  if (pointer == nullptr) throw std::bad_alloc();
  return pointer;
}

void CallerMemory::do_deallocate(void* pointer, std::size_t bytes, std::size_t /*alignment*/) {
  allocator_.free(allocator_.user, pointer, bytes);
}

namespace {

void* default_alloc(void* /*user*/, std::size_t size, std::size_t alignment) {
  if (alignment <= alignof(std::max_align_t)) return std::malloc(size);
  // aligned_alloc wants a size that is a multiple of the alignment.
  return std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
}
void default_free(void* /*user*/, void* pointer, std::size_t /*size*/) { std::free(pointer); }

}  // namespace

const spread_allocator& default_allocator() {
  static const spread_allocator allocator{default_alloc, default_free, nullptr};
  return allocator;
}

}  // namespace spread::capi

namespace {

using spread::capi::fail;

spread_status status_of(spread::tables::TableErrorKind kind) {
  using K = spread::tables::TableErrorKind;
  switch (kind) {
    case K::kMissing: return SPREAD_ERROR_FILE_MISSING;
    case K::kNotOurs: return SPREAD_ERROR_FILE_NOT_OURS;
    case K::kCorrupt: return SPREAD_ERROR_FILE_CORRUPT;
    case K::kWrongVersion: return SPREAD_ERROR_FILE_WRONG_VERSION;
    case K::kEmpty: return SPREAD_ERROR_FILE_EMPTY;
    case K::kIo: return SPREAD_ERROR_IO;
    case K::kScene:
    case K::kArgument: break;  // not a file's kinds: the reader never throws them
  }
  return SPREAD_ERROR_INTERNAL;
}

// NULL, or not a live handle: the status, with the detail naming the function.
spread_status check_handle(const spread_tables* tables, const char* function) {
  if (tables == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: the handle is NULL", function);
  if (!spread::capi::live(tables)) {
    return fail(SPREAD_ERROR_BAD_HANDLE, "%s: not a live spread_tables handle (closed, or not from spread_open)",
                function);
  }
  return SPREAD_OK;
}

bool valid_index(const spread_tables* tables, int32_t index) {
  return index >= 0 && static_cast<std::size_t>(index) < tables->predictor.material_count();
}

}  // namespace

namespace {

// spread_open, spread_open_with_allocator and spread_open_with_flags: `function` names the entry point in
// the detail; a NULL allocator is refused here (spread_open_with_flags passes the default for NULL).
spread_status open_table(const char* function, const char* path, const spread_allocator* allocator, uint32_t flags,
                         spread_tables** out_tables) {
  if (out_tables == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: out_tables is NULL", function);
  *out_tables = nullptr;
  if (path == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "%s: path is NULL", function);
  if (allocator == nullptr || allocator->alloc == nullptr || allocator->free == nullptr) {
    return fail(SPREAD_ERROR_NULL_POINTER, "%s: %s is NULL", function,
                allocator == nullptr ? "allocator" : (allocator->alloc == nullptr ? "allocator->alloc" : "allocator->free"));
  }
  if ((flags & ~uint32_t{SPREAD_OPEN_LEGACY_FILES}) != 0) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: flags 0x%x has bits outside SPREAD_OPEN_LEGACY_FILES", function,
                static_cast<unsigned>(flags));
  }
  const spread_allocator a = *allocator;
  void* storage = nullptr;
  try {
    spread::capi::detail::fault_point();
    storage = a.alloc(a.user, sizeof(spread_tables), alignof(spread_tables));
    if (storage == nullptr) throw std::bad_alloc();
    *out_tables = new (storage) spread_tables(path, a, flags);  // a file without runs is TableError kEmpty
    return SPREAD_OK;
  } catch (const spread::tables::TableError& e) {
    if (storage != nullptr) a.free(a.user, storage, sizeof(spread_tables));
    return fail(status_of(e.kind()), "%s", e.what());
  } catch (const std::bad_alloc&) {
    if (storage != nullptr) a.free(a.user, storage, sizeof(spread_tables));
    return fail(SPREAD_ERROR_OUT_OF_MEMORY, "%s: %s: out of memory", function, path);
  } catch (const std::exception& e) {
    if (storage != nullptr) a.free(a.user, storage, sizeof(spread_tables));
    return fail(SPREAD_ERROR_INTERNAL, "%s: %s: %s", function, path, e.what());
  } catch (...) {
    if (storage != nullptr) a.free(a.user, storage, sizeof(spread_tables));
    return fail(SPREAD_ERROR_INTERNAL, "%s: %s: unknown exception", function, path);
  }
}

}  // namespace

extern "C" spread_status spread_open_with_allocator(const char* path, const spread_allocator* allocator,
                                                    spread_tables** out_tables) {
  return open_table("spread_open_with_allocator", path, allocator, 0u, out_tables);
}

extern "C" spread_status spread_open(const char* path, spread_tables** out_tables) {
  return open_table("spread_open", path, &spread::capi::default_allocator(), 0u, out_tables);
}

extern "C" spread_status spread_open_with_flags(const char* path, uint32_t flags, const spread_allocator* allocator,
                                                spread_tables** out_tables) {
  return open_table("spread_open_with_flags", path, allocator != nullptr ? allocator : &spread::capi::default_allocator(),
                    flags, out_tables);
}

extern "C" spread_status spread_table_flags(const spread_tables* tables, uint32_t* out_flags) {
  if (const spread_status s = check_handle(tables, "spread_table_flags"); s != SPREAD_OK) return s;
  if (out_flags == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_table_flags: out_flags is NULL");
  *out_flags = tables->table_flags;
  return SPREAD_OK;
}

extern "C" void spread_close(spread_tables* tables) {
  if (tables == nullptr) return;
  if (!spread::capi::live(tables)) {
    fail(SPREAD_ERROR_BAD_HANDLE, "spread_close: not a live spread_tables handle (closed already?): left alone");
    return;
  }
  const spread_allocator a = tables->memory.allocator();
  spread::capi::mark_dead(tables->tag);
  tables->~spread_tables();
  a.free(a.user, tables, sizeof(spread_tables));
}

extern "C" spread_status spread_workspace_create(const spread_tables* tables, spread_workspace** out_workspace) {
  if (out_workspace == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_workspace_create: out_workspace is NULL");
  *out_workspace = nullptr;
  if (const spread_status s = check_handle(tables, "spread_workspace_create"); s != SPREAD_OK) return s;
  const spread_allocator& a = tables->memory.allocator();
  void* storage = a.alloc(a.user, sizeof(spread_workspace), alignof(spread_workspace));
  if (storage == nullptr) return fail(SPREAD_ERROR_OUT_OF_MEMORY, "spread_workspace_create: out of memory");
  try {
    *out_workspace = new (storage) spread_workspace(*tables);
    return SPREAD_OK;
  } catch (const std::bad_alloc&) {
    a.free(a.user, storage, sizeof(spread_workspace));
    return fail(SPREAD_ERROR_OUT_OF_MEMORY, "spread_workspace_create: out of memory");
  } catch (...) {
    a.free(a.user, storage, sizeof(spread_workspace));
    return fail(SPREAD_ERROR_INTERNAL, "spread_workspace_create: unexpected exception");
  }
}

extern "C" void spread_workspace_free(spread_workspace* workspace) {
  if (workspace == nullptr) return;
  if (!spread::capi::live(workspace)) {
    fail(SPREAD_ERROR_BAD_HANDLE, "spread_workspace_free: not a live workspace (freed already?): left alone");
    return;
  }
  const spread_allocator a = workspace->memory.allocator();
  spread::capi::mark_dead(workspace->tag);
  workspace->~spread_workspace();
  a.free(a.user, workspace, sizeof(spread_workspace));
}

extern "C" spread_status spread_material_count(const spread_tables* tables, int32_t* out_count) {
  if (const spread_status s = check_handle(tables, "spread_material_count"); s != SPREAD_OK) return s;
  if (out_count == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_material_count: out_count is NULL");
  *out_count = static_cast<int32_t>(tables->predictor.material_count());
  return SPREAD_OK;
}

extern "C" spread_status spread_material_name(const spread_tables* tables, int32_t index, const char** out_name) {
  if (const spread_status s = check_handle(tables, "spread_material_name"); s != SPREAD_OK) return s;
  if (out_name == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_material_name: out_name is NULL");
  if (!valid_index(tables, index)) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "spread_material_name: index %d outside [0, %zu)", static_cast<int>(index),
                tables->predictor.material_count());
  }
  *out_name = tables->predictor.material(static_cast<std::size_t>(index)).name.c_str();
  return SPREAD_OK;
}

extern "C" spread_status spread_material_rpm_range(const spread_tables* tables, int32_t index,
                                                   double* out_min_rpm, double* out_max_rpm) {
  if (const spread_status s = check_handle(tables, "spread_material_rpm_range"); s != SPREAD_OK) return s;
  if (out_min_rpm == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_material_rpm_range: out_min_rpm is NULL");
  if (out_max_rpm == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_material_rpm_range: out_max_rpm is NULL");
  if (!valid_index(tables, index)) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "spread_material_rpm_range: index %d outside [0, %zu)",
                static_cast<int>(index), tables->predictor.material_count());
  }
  *out_min_rpm = tables->predictor.min_rpm(static_cast<std::size_t>(index));
  *out_max_rpm = tables->predictor.max_rpm(static_cast<std::size_t>(index));
  return SPREAD_OK;
}

extern "C" spread_status spread_default_disc_height(const spread_tables* tables, double* out_height_m) {
  if (const spread_status s = check_handle(tables, "spread_default_disc_height"); s != SPREAD_OK) return s;
  if (out_height_m == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_default_disc_height: out_height_m is NULL");
  *out_height_m = tables->predictor.machine().disc_height_m;
  return SPREAD_OK;
}

extern "C" spread_status spread_landing_domain(const spread_tables* tables, int32_t index, double* out_min_height_m,
                                               double* out_max_height_m, double* out_max_wind_m_s) {
  if (const spread_status s = check_handle(tables, "spread_landing_domain"); s != SPREAD_OK) return s;
  const struct {
    const char* name;
    const double* pointer;
  } outputs[] = {{"out_min_height_m", out_min_height_m}, {"out_max_height_m", out_max_height_m},
                 {"out_max_wind_m_s", out_max_wind_m_s}};
  for (const auto& output : outputs) {
    if (output.pointer == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_landing_domain: %s is NULL", output.name);
  }
  if (!valid_index(tables, index)) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "spread_landing_domain: index %d outside [0, %zu)", static_cast<int>(index),
                tables->predictor.material_count());
  }
  const auto material = static_cast<std::size_t>(index);
  if (!tables->predictor.has_landing_grid(material)) {
    return fail(SPREAD_ERROR_OUTSIDE_DOMAIN,
                "spread_landing_domain: \"%.200s\" has no landing grid: its runs fly more than drag, so every "
                "request flies every launch sample (set fly_outside_domain)",
                tables->predictor.material(material).name.c_str());
  }
  const auto& domain = tables->predictor.landing_domain();
  *out_min_height_m = domain.min_disc_height_m;
  *out_max_height_m = domain.max_disc_height_m;
  *out_max_wind_m_s = domain.max_wind_m_s;
  return SPREAD_OK;
}

extern "C" spread_status spread_transverse_bound(const spread_tables* tables, double tray_width_m,
                                                 size_t* out_tray_count) {
  if (const spread_status s = check_handle(tables, "spread_transverse_bound"); s != SPREAD_OK) return s;
  if (out_tray_count == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_transverse_bound: out_tray_count is NULL");
  if (!std::isfinite(tray_width_m)) return fail(SPREAD_ERROR_NOT_FINITE, "spread_transverse_bound: tray_width_m is %g", tray_width_m);
  const int capacity = tables->predictor.tray_capacity(tray_width_m);
  if (capacity <= 0) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "spread_transverse_bound: tray_width_m %g outside [%g, %g] m", tray_width_m,
                tables->predictor.limits().min_tray_width_m, tables->predictor.limits().max_half_extent_m);
  }
  *out_tray_count = static_cast<size_t>(capacity);
  return SPREAD_OK;
}
