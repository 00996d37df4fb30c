#include "tools/spread/number_format.hpp"

#include <cstdio>

namespace spread::cli {

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

}  // namespace spread::cli
