#pragma once
// Per-process temporary paths for the C API tests (ctest runs the discovered tests in parallel processes,
// so every file name carries the process id).
#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace spread::testing {

inline std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / ("spread_capi_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

}  // namespace spread::testing
