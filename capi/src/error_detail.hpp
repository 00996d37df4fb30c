#pragma once
// spread_last_error_detail: one message per thread, written by the entry point that fails. A fixed
// thread-local buffer and vsnprintf: no allocation (spread_predict must not allocate, also when it
// refuses), and spread_open can report without a handle.
#include "spread/spread.h"

namespace spread::capi {

// Writes the printf-style message as this thread's detail (truncated to the buffer) and returns status.
#if defined(__GNUC__) || defined(__clang__)
__attribute__((format(printf, 2, 3)))
#endif
spread_status fail(spread_status status, const char* format, ...);

}  // namespace spread::capi
