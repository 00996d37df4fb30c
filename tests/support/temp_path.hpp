#pragma once
// Test helpers shared by the suites: a unique path in the temp directory, removed (with any SQLite
// journal and a table build's staging file) at scope exit, and whole-file byte reads and writes for
// damaging files on purpose.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

namespace spread::testing {

class TempPath {
 public:
  // `name` ends the file name (e.g. "table.sqlite"); the process id and a counter make it unique.
  explicit TempPath(const std::string& name) {
    static int counter = 0;
    path_ = (std::filesystem::temp_directory_path() /
             ("spread_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" + name))
                .string();
    remove();
  }
  ~TempPath() { remove(); }
  TempPath(const TempPath&) = delete;
  TempPath& operator=(const TempPath&) = delete;
  const std::string& path() const { return path_; }

 private:
  void remove() const {
    std::error_code ec;
    for (const char* suffix : {"", "-journal", ".building", ".building-journal"}) std::filesystem::remove(path_ + suffix, ec);
  }
  std::string path_;
};

inline std::vector<char> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void write_bytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace spread::testing
