// Run-time version, checked at compile time against the CMake project version so the header macros
// cannot drift from the release.
#include <string_view>

#include "spread/spread.h"

static_assert(std::string_view(SPREAD_VERSION_STRING) == std::string_view(SPREAD_PROJECT_VERSION),
              "capi/include/spread/spread.h version macros differ from project(libspread VERSION ...)");

extern "C" uint32_t spread_version(void) { return SPREAD_VERSION_NUMBER; }
extern "C" const char* spread_version_string(void) { return SPREAD_VERSION_STRING; }
