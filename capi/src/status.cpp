// spread_status_str: one static string per code (zstd's ZSTD_getErrorName pattern).
#include "spread/spread.h"

extern "C" const char* spread_status_str(spread_status status) {
  switch (status) {
    case SPREAD_OK: return "SPREAD_OK: success";
    case SPREAD_ERROR_NULL_POINTER: return "SPREAD_ERROR_NULL_POINTER: a required pointer is NULL";
    case SPREAD_ERROR_NOT_FINITE: return "SPREAD_ERROR_NOT_FINITE: an argument is NaN or infinite";
    case SPREAD_ERROR_OUT_OF_RANGE: return "SPREAD_ERROR_OUT_OF_RANGE: an argument is outside its range";
    case SPREAD_ERROR_RPM_OUTSIDE_TABLE: return "SPREAD_ERROR_RPM_OUTSIDE_TABLE: rpm outside the table rows";
    case SPREAD_ERROR_UNKNOWN_MATERIAL: return "SPREAD_ERROR_UNKNOWN_MATERIAL: unknown material";
    case SPREAD_ERROR_UNKNOWN_EFFECT: return "SPREAD_ERROR_UNKNOWN_EFFECT: unknown effect bits";
    case SPREAD_ERROR_BUFFER_TOO_SMALL: return "SPREAD_ERROR_BUFFER_TOO_SMALL: caller buffer too small";
    case SPREAD_ERROR_FILE_MISSING: return "SPREAD_ERROR_FILE_MISSING: no such file";
    case SPREAD_ERROR_FILE_NOT_OURS: return "SPREAD_ERROR_FILE_NOT_OURS: not a libspread launch-table file";
    case SPREAD_ERROR_FILE_CORRUPT: return "SPREAD_ERROR_FILE_CORRUPT: launch-table file is corrupt";
    case SPREAD_ERROR_FILE_WRONG_VERSION:
      return "SPREAD_ERROR_FILE_WRONG_VERSION: launch-table file of another format version";
    case SPREAD_ERROR_FILE_EMPTY: return "SPREAD_ERROR_FILE_EMPTY: launch-table file has no runs";
    case SPREAD_ERROR_IO: return "SPREAD_ERROR_IO: launch-table file could not be read";
    case SPREAD_ERROR_OUT_OF_MEMORY: return "SPREAD_ERROR_OUT_OF_MEMORY: out of memory";
    case SPREAD_ERROR_NOT_LANDED: return "SPREAD_ERROR_NOT_LANDED: the granule did not reach the ground";
    case SPREAD_ERROR_INTERNAL: return "SPREAD_ERROR_INTERNAL: internal error";
    case SPREAD_ERROR_BAD_HANDLE: return "SPREAD_ERROR_BAD_HANDLE: not a live handle (closed or freed)";
    case SPREAD_ERROR_OUTSIDE_DOMAIN: return "SPREAD_ERROR_OUTSIDE_DOMAIN: outside the landing grid's domain";
  }
  return "unknown status";
}
