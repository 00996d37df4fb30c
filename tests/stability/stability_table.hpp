#pragma once
// A small real launch table for the stability tests: scenes/default.toml through the lookup_builder
// library (analytic launch source), 2 rpm rows x 16 samples of "Urea". Written once per process into
// a fresh temporary directory and removed at exit.
#include <cstdlib>
#include <filesystem>
#include <string>

#include "libspread/io/scene/scene.hpp"
#include "lookup_builder/table_build.hpp"

namespace spread::stability {

class TempDirectory {
 public:
  TempDirectory() {
    std::string pattern = (std::filesystem::temp_directory_path() / "spread_stability_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDirectory(const TempDirectory&) = delete;
  TempDirectory& operator=(const TempDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline const TempDirectory& temp_directory() {
  static TempDirectory directory;
  return directory;
}

inline constexpr double kTableMinRpm = 450.0;
inline constexpr double kTableMaxRpm = 600.0;

// Path of the table (built on first use).
inline std::string stability_table_path() {
  static const std::string path = [] {
    const std::string out = (temp_directory().path() / "stability.sqlite").string();
    const scene::Scene scene =
        scene::load_scene_file(SPREAD_SOURCE_DIR "/scenes/default.toml",
                               {"sweep.source=\"analytic\"", "sweep.samples_per_run=16", "sweep.rpm=[450.0, 600.0]",
                                "sweep.materials=[\"Urea\"]"});
    lookup::BuildOptions options;
    options.output_path = out;
    lookup::build_tables(scene, options);
    return out;
  }();
  return path;
}

// A copy of the table to damage.
inline std::string copy_of_table(const std::string& name) {
  const std::filesystem::path copy = temp_directory().path() / name;
  std::filesystem::copy_file(stability_table_path(), copy, std::filesystem::copy_options::overwrite_existing);
  return copy.string();
}

}  // namespace spread::stability
