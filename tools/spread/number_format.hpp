#pragma once
// One number in printf notation, for the `spread` commands' text output.
#include <string>

namespace spread::cli {

// `value` formatted by the printf `pattern` with one double conversion ("%.2f m"); at most 63 characters.
std::string format(const char* pattern, double value);

}  // namespace spread::cli
