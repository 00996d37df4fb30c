// spread_open / spread_close and the table queries. Every entry point catches everything: no C++
// exception may unwind into C (DESIGN.md §5).
#include <cmath>
#include <new>

#include "capi/src/fault_seam.hpp"
#include "capi/src/tables_handle.hpp"

namespace {

spread_status status_of(spread::tables::TableErrorKind kind) {
  using K = spread::tables::TableErrorKind;
  switch (kind) {
    case K::kMissing: return SPREAD_ERROR_FILE_MISSING;
    case K::kNotOurs: return SPREAD_ERROR_FILE_NOT_OURS;
    case K::kCorrupt: return SPREAD_ERROR_FILE_CORRUPT;
    case K::kWrongVersion: return SPREAD_ERROR_FILE_WRONG_VERSION;
    case K::kEmpty: return SPREAD_ERROR_FILE_EMPTY;
    case K::kIo: return SPREAD_ERROR_IO;
  }
  return SPREAD_ERROR_INTERNAL;
}

bool valid_index(const spread_tables* tables, int32_t index) {
  return index >= 0 && static_cast<std::size_t>(index) < tables->predictor.material_count();
}

}  // namespace

extern "C" spread_status spread_open(const char* path, spread_tables** out_tables) {
  if (out_tables == nullptr) return SPREAD_ERROR_NULL_POINTER;
  *out_tables = nullptr;
  if (path == nullptr) return SPREAD_ERROR_NULL_POINTER;
  try {
    spread::capi::detail::fault_point();
    auto contents = spread::tables::read_table_file(path);
    if (contents.runs.empty()) return SPREAD_ERROR_FILE_EMPTY;  // the reader should say so already
    *out_tables = new spread_tables(std::move(contents));
    return SPREAD_OK;
  } catch (const spread::tables::TableError& e) {
    return status_of(e.kind());
  } catch (const std::bad_alloc&) {
    return SPREAD_ERROR_OUT_OF_MEMORY;
  } catch (...) {
    return SPREAD_ERROR_INTERNAL;
  }
}

extern "C" void spread_close(spread_tables* tables) { delete tables; }

extern "C" spread_status spread_material_count(const spread_tables* tables, int32_t* out_count) {
  if (tables == nullptr || out_count == nullptr) return SPREAD_ERROR_NULL_POINTER;
  *out_count = static_cast<int32_t>(tables->predictor.material_count());
  return SPREAD_OK;
}

extern "C" spread_status spread_material_name(const spread_tables* tables, int32_t index, const char** out_name) {
  if (tables == nullptr || out_name == nullptr) return SPREAD_ERROR_NULL_POINTER;
  if (!valid_index(tables, index)) return SPREAD_ERROR_OUT_OF_RANGE;
  *out_name = tables->predictor.material(static_cast<std::size_t>(index)).name.c_str();
  return SPREAD_OK;
}

extern "C" spread_status spread_material_rpm_range(const spread_tables* tables, int32_t index,
                                                   double* out_min_rpm, double* out_max_rpm) {
  if (tables == nullptr || out_min_rpm == nullptr || out_max_rpm == nullptr) return SPREAD_ERROR_NULL_POINTER;
  if (!valid_index(tables, index)) return SPREAD_ERROR_OUT_OF_RANGE;
  *out_min_rpm = tables->predictor.min_rpm(static_cast<std::size_t>(index));
  *out_max_rpm = tables->predictor.max_rpm(static_cast<std::size_t>(index));
  return SPREAD_OK;
}

extern "C" spread_status spread_default_disc_height(const spread_tables* tables, double* out_height_m) {
  if (tables == nullptr || out_height_m == nullptr) return SPREAD_ERROR_NULL_POINTER;
  *out_height_m = tables->predictor.machine().disc_height_m;
  return SPREAD_OK;
}

extern "C" spread_status spread_transverse_bound(const spread_tables* tables, double tray_width_m,
                                                 size_t* out_tray_count) {
  if (tables == nullptr || out_tray_count == nullptr) return SPREAD_ERROR_NULL_POINTER;
  if (!std::isfinite(tray_width_m)) return SPREAD_ERROR_NOT_FINITE;
  const int capacity = tables->predictor.tray_capacity(tray_width_m);
  if (capacity <= 0) return SPREAD_ERROR_OUT_OF_RANGE;
  *out_tray_count = static_cast<size_t>(capacity);
  return SPREAD_OK;
}
