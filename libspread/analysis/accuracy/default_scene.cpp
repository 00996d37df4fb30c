#include "libspread/analysis/accuracy/accuracy.hpp"

#include <filesystem>

namespace spread::accuracy {

// The source tree's scenes/default.toml (the Case-1 twin-disc machine the bundled tables describe).
std::string default_scene_path() { return SPREAD_ACCURACY_DEFAULT_SCENE; }

std::string scene_display_name(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(default_scene_path()).parent_path().parent_path();
  const fs::path relative = fs::absolute(path).lexically_normal().lexically_relative(root);
  if (relative.empty() || *relative.begin() == "..") return path;
  return relative.generic_string();
}

}  // namespace spread::accuracy
