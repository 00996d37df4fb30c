#pragma once
// The table loader and spread_open take a path, not bytes: each input is written to one per-process file
// on a tmpfs when there is one (/dev/shm), so the fuzzer does not wear the disk.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace spread::fuzz {

class TempInputFile {
 public:
  explicit TempInputFile(const char* stem) {
    const std::filesystem::path dir =
        std::filesystem::is_directory("/dev/shm") ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
    path_ = (dir / (std::string(stem) + "_" + std::to_string(::getpid()) + ".sqlite")).string();
  }
  ~TempInputFile() { remove_all(); }
  TempInputFile(const TempInputFile&) = delete;
  TempInputFile& operator=(const TempInputFile&) = delete;

  // Replaces the file's content with `data`; false if it could not be written.
  bool write(const std::uint8_t* data, std::size_t size) {
    remove_all();
    std::FILE* file = std::fopen(path_.c_str(), "wb");
    if (file == nullptr) return false;
    const bool ok = size == 0 || std::fwrite(data, 1, size, file) == size;
    return std::fclose(file) == 0 && ok;
  }

  const std::string& path() const { return path_; }

 private:
  // SQLite may leave -journal/-wal/-shm companions next to a file whose header asks for them.
  void remove_all() {
    for (const char* suffix : {"", "-journal", "-wal", "-shm"}) std::remove((path_ + suffix).c_str());
  }

  std::string path_;
};

}  // namespace spread::fuzz
