// What spread_open makes of a damaged or odd table file: damage is a file code (never a changed
// prediction, never the caller's SPREAD_ERROR_OUT_OF_RANGE), and paths SQLite alone handles badly
// (a FIFO, an unreadable file) get their own codes without hanging.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "spread/spread.h"
#include "tests/capi/capi_test_files.hpp"
#include "tests/predict/synthetic_table.hpp"
#include "tests/support/temp_path.hpp"

namespace {

using spread::testing::temp_path;

// A small real table: one material ("can", 64 launches at 500 and 700 rpm).
std::string small_table() {
  static const std::string path = [] {
    const std::string p = temp_path("integrity.sqlite");
    spread::testing::write_synthetic_table(p, {{"can", 1050.0, {500.0, 700.0}, 64}});
    return p;
  }();
  return path;
}

struct Outcome {
  spread_status open = SPREAD_OK;
  spread_status predict = SPREAD_OK;
  spread_prediction result{};
  std::vector<double> trays;
};

Outcome open_and_predict(const std::string& path) {
  Outcome out;
  spread_tables* tables = nullptr;
  out.open = spread_open(path.c_str(), &tables);
  if (out.open != SPREAD_OK) return out;
  spread_prediction_def def = spread_prediction_def_default();
  def.material = "can";
  def.rpm = 600.0;
  out.trays.assign(512, 0.0);
  out.predict = spread_predict(tables, &def, &out.result, out.trays.data(), out.trays.size());
  out.trays.resize(out.predict == SPREAD_OK ? static_cast<std::size_t>(out.result.tray_count) : 0);
  spread_close(tables);
  return out;
}

bool is_file_code(spread_status s) {
  return s == SPREAD_ERROR_FILE_NOT_OURS || s == SPREAD_ERROR_FILE_CORRUPT || s == SPREAD_ERROR_FILE_WRONG_VERSION ||
         s == SPREAD_ERROR_FILE_EMPTY || s == SPREAD_ERROR_IO;
}

bool same_prediction(const Outcome& a, const Outcome& b) {
  return a.predict == b.predict && std::memcmp(&a.result, &b.result, sizeof a.result) == 0 && a.trays == b.trays;
}

// Copies of the table with 1–8 random bytes changed anywhere in the file. Each copy either fails to open
// with a file code, or opens and predicts exactly what the undamaged table predicts (the byte was in
// unused space, or in a column no prediction reads and no checksum covers: none today). Before the row
// checksums, 229 of 400 such copies of the default table opened with changed predictions.
TEST(CapiIntegrity, RandomByteDamageNeverChangesAPredictionSilently) {
  const Outcome reference = open_and_predict(small_table());
  ASSERT_EQ(reference.open, SPREAD_OK);
  ASSERT_EQ(reference.predict, SPREAD_OK);
  const std::vector<char> original = spread::testing::file_bytes(small_table());
  std::mt19937_64 random(20261124);
  int refused = 0, unchanged = 0;
  const std::string copy = temp_path("damaged.sqlite");
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<char> bytes = original;
    const int flips = 1 + static_cast<int>(random() % 8);
    for (int f = 0; f < flips; ++f) {
      const std::size_t at = random() % bytes.size();
      bytes[at] = static_cast<char>(bytes[at] ^ static_cast<char>(1 + random() % 255));
    }
    std::filesystem::remove(copy + "-journal");
    spread::testing::write_bytes(copy, bytes);
    const Outcome damaged = open_and_predict(copy);
    if (damaged.open != SPREAD_OK) {
      EXPECT_TRUE(is_file_code(damaged.open)) << "trial " << trial << ": " << spread_status_str(damaged.open);
      ++refused;
      continue;
    }
    EXPECT_TRUE(same_prediction(damaged, reference))
        << "trial " << trial << ": opened SPREAD_OK but predicts differently (" << spread_status_str(damaged.predict)
        << ", working width " << damaged.result.working_width_to_and_fro_m << " m against "
        << reference.result.working_width_to_and_fro_m << " m)";
    ++unchanged;
  }
  // Most damage lands in the sample BLOBs, which fill most of the file: the checksums must be refusing.
  EXPECT_GT(refused, 150) << unchanged << " copies opened unchanged";
}

TEST(CapiIntegrity, AnImplausibleStoredValueIsAFileProblemNotTheCallers) {
  const std::string path = temp_path("height150.sqlite");
  std::filesystem::copy_file(small_table(), path, std::filesystem::copy_options::overwrite_existing);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "UPDATE machine SET disc_height_m = 150", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  spread_tables* tables = nullptr;
  EXPECT_EQ(spread_open(path.c_str(), &tables), SPREAD_ERROR_FILE_CORRUPT);
  EXPECT_EQ(tables, nullptr);
  EXPECT_NE(std::string(spread_last_error_detail()).find("machine.disc_height_m = 150"), std::string::npos)
      << spread_last_error_detail();
}

TEST(CapiIntegrity, AFifoIsNotOursAndDoesNotHang) {
  const std::string path = temp_path("fifo.sqlite");
  std::filesystem::remove(path);
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  ::alarm(20);  // a regression blocks in open(): fail loudly instead of hanging the suite
  spread_tables* tables = nullptr;
  EXPECT_EQ(spread_open(path.c_str(), &tables), SPREAD_ERROR_FILE_NOT_OURS);
  ::alarm(0);
}

// A file that exists but cannot be read is SPREAD_ERROR_IO, not _FILE_MISSING. Root reads any file, so
// the check runs in a child that has given up root.
TEST(CapiIntegrity, AnUnreadableFileIsIoNotMissing) {
  const std::string dir = temp_path("unreadable");
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/mode000.sqlite";
  std::filesystem::copy_file(small_table(), path, std::filesystem::copy_options::overwrite_existing);
  ASSERT_EQ(::chmod(dir.c_str(), 0755), 0);
  ASSERT_EQ(::chmod(path.c_str(), 0000), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(100);
    spread_tables* tables = nullptr;
    ::_exit(static_cast<int>(spread_open(path.c_str(), &tables)));
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_NE(WEXITSTATUS(status), 100) << "could not drop root to test permissions";
  EXPECT_EQ(WEXITSTATUS(status), SPREAD_ERROR_IO) << spread_status_str(static_cast<spread_status>(WEXITSTATUS(status)));
  ::chmod(path.c_str(), 0600);
}

}  // namespace
