// spread_open on every kind of file: ours, missing, not ours (garbage, foreign SQLite, zero bytes, a
// directory), corrupt, wrong version, without runs, left mid-transaction by a crashed writer (i/o). The broken files are made from a real one.
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "spread/spread.h"
#include "tests/capi/capi_test_files.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace {

using spread::testing::temp_path;

std::string real_table() {
  static const std::string path = [] {
    const std::string p = temp_path("real.sqlite");
    spread::testing::write_synthetic_table(p);
    return p;
  }();
  return path;
}

std::string copy_of_real(const std::string& name) {
  const std::string p = temp_path(name);
  std::filesystem::copy_file(real_table(), p, std::filesystem::copy_options::overwrite_existing);
  return p;
}

void exec_sql(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* err = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err);
  std::string message = err ? err : "";
  sqlite3_free(err);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << message;
}

spread_status open_status(const std::string& path) {
  spread_tables* tables = reinterpret_cast<spread_tables*>(0x1);  // must be reset to NULL on failure
  const spread_status s = spread_open(path.c_str(), &tables);
  if (s == SPREAD_OK) {
    EXPECT_NE(tables, nullptr);
  } else {
    EXPECT_EQ(tables, nullptr);
  }
  spread_close(tables);
  return s;
}

TEST(CapiOpen, OpensOurFile) { EXPECT_EQ(open_status(real_table()), SPREAD_OK); }

TEST(CapiOpen, MissingFile) {
  EXPECT_EQ(open_status(temp_path("does-not-exist.sqlite")), SPREAD_ERROR_FILE_MISSING);
}

TEST(CapiOpen, GarbageBytesAreNotOurs) {
  const std::string p = temp_path("garbage.sqlite");
  std::ofstream(p, std::ios::binary) << std::string(5000, '\x5a') << "not a database";
  EXPECT_EQ(open_status(p), SPREAD_ERROR_FILE_NOT_OURS);
}

TEST(CapiOpen, ForeignSqliteDatabaseIsNotOurs) {
  const std::string p = temp_path("foreign.sqlite");
  std::filesystem::remove(p);
  exec_sql(p, "CREATE TABLE birds(name TEXT); INSERT INTO birds VALUES ('wren');");
  EXPECT_EQ(open_status(p), SPREAD_ERROR_FILE_NOT_OURS);
}

TEST(CapiOpen, ZeroByteFileAndDirectoryAreNotOurs) {
  const std::string p = temp_path("zero.sqlite");
  std::ofstream(p, std::ios::binary).close();
  EXPECT_EQ(open_status(p), SPREAD_ERROR_FILE_NOT_OURS);
  EXPECT_EQ(open_status(std::filesystem::path(p).parent_path().string()), SPREAD_ERROR_FILE_NOT_OURS);
}

TEST(CapiOpen, WrongVersion) {
  const std::string p = copy_of_real("wrong-version.sqlite");
  exec_sql(p, "PRAGMA user_version = 99;");
  EXPECT_EQ(open_status(p), SPREAD_ERROR_FILE_WRONG_VERSION);
}

TEST(CapiOpen, FileWithoutRunsIsEmpty) {
  const std::string p = temp_path("no-runs.sqlite");
  spread::testing::write_table_without_runs(p);
  EXPECT_EQ(open_status(p), SPREAD_ERROR_FILE_EMPTY);
  // Every run of a real file deleted behind the writer's back: its list of runs names the missing ones.
  const std::string q = copy_of_real("runs-deleted.sqlite");
  exec_sql(q, "DELETE FROM runs;");
  EXPECT_EQ(open_status(q), SPREAD_ERROR_FILE_CORRUPT);
  // ... and with the list gone too, a table without runs.
  exec_sql(q, "DELETE FROM meta WHERE key = 'runs_manifest';");
  EXPECT_EQ(open_status(q), SPREAD_ERROR_FILE_EMPTY);
}

TEST(CapiOpen, FlippedBytesAreCorrupt) {
  // Overwrite the b-tree page headers of every page but the first (which holds the SQLite header and the
  // application id): the file still looks like ours, and the integrity check must catch it.
  const std::string p = copy_of_real("corrupt.sqlite");
  const auto size = std::filesystem::file_size(p);
  ASSERT_GT(size, 3 * 4096u);
  std::fstream f(p, std::ios::in | std::ios::out | std::ios::binary);
  for (std::uintmax_t page = 4096; page + 16 < size; page += 4096) {
    f.seekp(static_cast<std::streamoff>(page));
    f.write("\x7f\x7f\x7f\x7f\x7f\x7f\x7f\x7f", 8);
  }
  f.close();
  EXPECT_EQ(open_status(p), SPREAD_ERROR_FILE_CORRUPT);
}

TEST(CapiOpen, MalformedRecordIsCorrupt) {
  // A structurally sound database whose sample BLOB has the wrong size.
  const std::string p = copy_of_real("bad-record.sqlite");
  exec_sql(p, "UPDATE runs SET samples = x'00010203';");
  EXPECT_EQ(open_status(p), SPREAD_ERROR_FILE_CORRUPT);
}

TEST(CapiOpen, HotJournalOfACrashedWriterIsIo) {
  // A writer (e.g. lookup_builder) dies inside a write transaction: its rollback journal stays beside the
  // file ("hot"). Only a read-write connection may roll it back; the C API opens read-only, so SQLite
  // answers SQLITE_READONLY_ROLLBACK, which is neither "not ours" nor "corrupt": SPREAD_ERROR_IO.
  const std::string p = copy_of_real("crashed-writer.sqlite");
  std::filesystem::remove(p + "-journal");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    sqlite3* db = nullptr;
    if (sqlite3_open(p.c_str(), &db) != SQLITE_OK) _exit(3);
    // A one-page cache makes SQLite spill changed pages into the file before COMMIT: it first syncs the
    // journal (header magic written), then overwrites pages of the table. (Without a spill the journal
    // header stays zeroed and the file untouched: nothing to roll back.)
    const char* sql = "PRAGMA cache_size = 1; BEGIN; UPDATE runs SET samples = zeroblob(length(samples));";
    if (sqlite3_exec(db, sql, nullptr, nullptr, nullptr) != SQLITE_OK) _exit(4);
    _exit(0);  // no COMMIT, no close: the process "crashes" with the journal on disk
  }
  int wait_status = 0;
  ASSERT_EQ(waitpid(child, &wait_status, 0), child);
  ASSERT_TRUE(WIFEXITED(wait_status));
  ASSERT_EQ(WEXITSTATUS(wait_status), 0);
  ASSERT_TRUE(std::filesystem::exists(p + "-journal"));
  EXPECT_EQ(open_status(p), SPREAD_ERROR_IO);
  EXPECT_NE(std::string(spread_status_str(SPREAD_ERROR_IO)).find("could not be read"), std::string::npos);
  // Any read-write connection rolls the journal back; the file is then whole again, samples included.
  exec_sql(p, "SELECT count(*) FROM runs;");
  EXPECT_FALSE(std::filesystem::exists(p + "-journal"));
  EXPECT_EQ(open_status(p), SPREAD_OK);
}

TEST(CapiOpen, NullArguments) {
  spread_tables* tables = nullptr;
  EXPECT_EQ(spread_open(nullptr, &tables), SPREAD_ERROR_NULL_POINTER);
  EXPECT_EQ(spread_open(real_table().c_str(), nullptr), SPREAD_ERROR_NULL_POINTER);
  spread_close(nullptr);  // no-op
}

}  // namespace

namespace {

TEST(CapiOpen, FailureDetailNamesFileAndRecord) {
  // spread_open fails without a handle: the detail is the thread's, and it is the reader's sentence.
  const std::string p = copy_of_real("bad-record-detail.sqlite");
  exec_sql(p, "UPDATE runs SET samples = x'00010203' WHERE material = 'urea';");
  ASSERT_EQ(open_status(p), SPREAD_ERROR_FILE_CORRUPT);
  const std::string detail = spread_last_error_detail();
  EXPECT_NE(detail.find(p), std::string::npos) << detail;
  EXPECT_NE(detail.find("urea"), std::string::npos) << detail;
  EXPECT_NE(detail.find("4 bytes"), std::string::npos) << detail;
  // A successful call leaves it; a missing file replaces it.
  ASSERT_EQ(open_status(real_table()), SPREAD_OK);
  EXPECT_EQ(detail, spread_last_error_detail());
  const std::string missing = temp_path("no-such-file.sqlite");
  ASSERT_EQ(open_status(missing), SPREAD_ERROR_FILE_MISSING);
  EXPECT_NE(std::string(spread_last_error_detail()).find(missing), std::string::npos);
}

}  // namespace
