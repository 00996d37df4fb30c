#pragma once
// The text of a file of the source tree (docs, scenes) for the tests that hold a document to the code's
// one list of names. Needs SPREAD_SOURCE_DIR (the suite's target_compile_definitions).
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace spread::testing {

// `relative` from the source root, e.g. "docs/scene-format.md"; throws when it cannot be read, so a
// moved document fails its test by name instead of passing on empty text.
inline std::string read_source_file(const std::string& relative) {
  std::ifstream in(std::string(SPREAD_SOURCE_DIR) + "/" + relative);
  if (!in) throw std::runtime_error("cannot read " + relative + " under " + SPREAD_SOURCE_DIR);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace spread::testing
