#include "capi/src/error_detail.hpp"

#include <cstdarg>
#include <cstdio>

namespace {

// 512 bytes: a table file's path and the reader's record/field sentence fit; longer text is cut.
thread_local char g_detail[512] = "";

}  // namespace

namespace spread::capi {

spread_status fail(spread_status status, const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  std::vsnprintf(g_detail, sizeof g_detail, format, args);
  va_end(args);
  return status;
}

}  // namespace spread::capi

extern "C" const char* spread_last_error_detail(void) { return g_detail; }
