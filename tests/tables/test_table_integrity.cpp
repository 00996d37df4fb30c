// A table file's integrity on disk: row checksums, plausibility bounds, a writer killed inside its commit,
// two writers on one file, and paths SQLite alone handles badly (a FIFO, a WAL-mode file).
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <string>

#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "tests/support/temp_path.hpp"
#include "tests/tables/table_fixtures.hpp"

namespace spread::tables {
namespace {

using spread::testing::raw_exec;
using spread::testing::TempPath;
using spread::testing::write_sample_table;

// The reader's verdict on a file: "" when it opens, else the error kind and message.
std::string read_problem(const std::string& path, TableErrorKind* kind = nullptr) {
  try {
    read_table_file(path);
    return {};
  } catch (const TableError& e) {
    if (kind != nullptr) *kind = e.kind();
    return e.what();
  }
}

TEST(RowChecksum, Crc64XzCheckValue) {
  Crc64 crc;
  const std::string text = "123456789";
  crc.bytes({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
  EXPECT_EQ(crc.value(), 0x995DC9BBDF1939FAull);  // the catalogued check value of CRC-64/XZ
  EXPECT_EQ(crc.hex(), "995dc9bbdf1939fa");
}

// A long input folds eight bytes at a time: its value is xz's own (`xz -C crc64` on these 1000 bytes,
// `xz -lvv` CheckVal f033761aeb8e0b26).
TEST(RowChecksum, Crc64XzOfALongInputIsXzs) {
  std::string text(1000, '\0');
  for (std::size_t i = 0; i < text.size(); ++i) text[i] = static_cast<char>((i * 7 + 3) % 256);
  Crc64 crc;
  crc.bytes({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
  EXPECT_EQ(crc.hex(), "f033761aeb8e0b26");
}

TEST(RowChecksum, EveryChecksummedRowIsVerified) {
  // A plausible value changed after writing (what a flipped bit in a REAL usually gives) is found by
  // the checksum, row by row; the message names the row.
  const struct {
    const char* sql;
    const char* row;
  } cases[] = {
      {"UPDATE machine SET disc_height_m = 0.29", "the `machine` row: checksum mismatch"},
      {"UPDATE materials SET density_kg_m3 = 1801 WHERE name = 'B'", "material \"B\": checksum mismatch"},
      // The lowest byte of sample 0's x_m (0.29f, 0x3E947AE1 little-endian) set to 0: still a plausible value.
      {"UPDATE runs SET samples = x'00' || substr(samples, 2) WHERE material = 'A' AND rpm = 600",
       "run A @ 600.000000 rpm: checksum mismatch"},
      {"UPDATE runs SET stats_json = '{\"speed_mean\":17.0}' WHERE material = 'A' AND rpm = 450",
       "run A @ 450.000000 rpm: checksum mismatch"},
      {"UPDATE runs SET checksum = '0000000000000000' WHERE material = 'B'", "run B @ 450.000000 rpm: checksum mismatch"},
  };
  for (const auto& c : cases) {
    TempPath file("checksum.sqlite");
    write_sample_table(file.path());
    ASSERT_EQ(read_problem(file.path()), "");
    raw_exec(file.path(), c.sql);
    TableErrorKind kind{};
    const std::string problem = read_problem(file.path(), &kind);
    ASSERT_FALSE(problem.empty()) << c.sql;
    EXPECT_EQ(kind, TableErrorKind::kCorrupt) << problem;
    EXPECT_NE(problem.find(c.row), std::string::npos) << problem;
    EXPECT_NE(problem.find("checksum mismatch"), std::string::npos) << problem;
  }
}

// A run deleted or added whole keeps every row's checksum valid; the table's list of runs (meta
// `runs_manifest`, written with every run) finds it and names the run. A dropped column is a damaged
// file too, named, not an I/O error.
TEST(RunsManifest, ADeletedOrAddedRunOrADroppedColumnIsADamagedFileNamed) {
  const struct {
    const char* sql;
    const char* named;
  } cases[] = {
      {"DELETE FROM runs WHERE material = 'A' AND rpm = 600", "run A @ 600 rpm is in the table's list of runs but not in `runs`"},
      {"INSERT INTO runs SELECT material, 500, source, sample_count, record_layout, record_bytes, samples, scene_hash, "
       "scene_text, effects, dt_contact_s, dt_flight_s, particle_count, software_version, created_utc, stats_json, "
       "convergence_json, checksum, inputs_hash FROM runs WHERE material = 'A' AND rpm = 450",
       nullptr},  // its checksum no longer matches its rpm: the row's own check names it first
      {"ALTER TABLE runs DROP COLUMN checksum", "table `runs` has no column `checksum`"},
      {"ALTER TABLE materials DROP COLUMN density_kg_m3", "table `materials` has no column `density_kg_m3`"},
  };
  for (const auto& c : cases) {
    TempPath file("manifest.sqlite");
    write_sample_table(file.path());
    ASSERT_EQ(read_problem(file.path()), "");
    raw_exec(file.path(), c.sql);
    TableErrorKind kind{};
    const std::string problem = read_problem(file.path(), &kind);
    ASSERT_FALSE(problem.empty()) << c.sql;
    EXPECT_EQ(kind, TableErrorKind::kCorrupt) << problem;
    if (c.named != nullptr) {
      EXPECT_NE(problem.find(c.named), std::string::npos) << problem;
    }
  }
  // A run added whole with a valid checksum of its own (written by another writer into another file and
  // copied over): only the list finds it.
  TempPath file("added.sqlite"), other("other.sqlite");
  write_sample_table(file.path());
  write_sample_table(other.path());
  {
    TableWriter writer(other.path());
    writer.write_run(spread::testing::sample_run("B", 600.0, 64));
  }
  raw_exec(file.path(), "ATTACH '" + other.path() + "' AS o; INSERT INTO runs SELECT * FROM o.runs WHERE material = 'B' AND rpm = 600");
  TableErrorKind kind{};
  const std::string problem = read_problem(file.path(), &kind);
  EXPECT_EQ(kind, TableErrorKind::kCorrupt) << problem;
  EXPECT_NE(problem.find("run B @ 600 rpm is in `runs` but not in the table's list of runs"), std::string::npos) << problem;
}

// Landing data comes back as written (whether it is current for the rows is its reader's judgement); a
// changed byte of it is a damaged row, named; a damaged schema too.
TEST(LandingData, ReadAsWrittenAndChecked) {
  TempPath file("landing.sqlite");
  write_sample_table(file.path());
  const std::vector<std::uint8_t> bytes = {1, 2, 3, 4, 5};
  {
    TableWriter writer(file.path());
    writer.write_landing_data({"A", "model 1", "key a", bytes});
    writer.write_landing_data({"B", "model 1", "key b", bytes});
    writer.write_landing_data({"B", "model 1", "key b2", bytes});  // replaces B's
  }
  const TableContents contents = read_table_file(file.path());
  ASSERT_EQ(contents.landing_data.size(), 2u);
  EXPECT_EQ(contents.landing_data[0].material, "A");
  EXPECT_EQ(contents.landing_data[0].model, "model 1");
  EXPECT_EQ(contents.landing_data[0].source_key, "key a");
  EXPECT_EQ(contents.landing_data[0].data, bytes);
  EXPECT_EQ(contents.landing_data[1].source_key, "key b2");

  const struct {
    const char* sql;
    const char* named;
  } cases[] = {
      {"UPDATE landing_data SET data = x'0102030400' WHERE material = 'B'", "landing data B: checksum mismatch"},
      {"UPDATE landing_data SET source_key = 'key b' WHERE material = 'B'", "landing data B: checksum mismatch"},
      {"ALTER TABLE landing_data DROP COLUMN model", "table `landing_data` has no column `model`"},
  };
  for (const auto& c : cases) {
    TempPath damaged("landing-damaged.sqlite");
    std::filesystem::copy_file(file.path(), damaged.path());
    raw_exec(damaged.path(), c.sql);
    TableErrorKind kind{};
    const std::string problem = read_problem(damaged.path(), &kind);
    EXPECT_EQ(kind, TableErrorKind::kCorrupt) << c.sql;
    EXPECT_NE(problem.find(c.named), std::string::npos) << problem;
  }
}

TEST(Plausibility, ValuesThePredictorWouldRefuseAreAFileProblem) {
  const struct {
    const char* sql;
    const char* field;
  } cases[] = {
      {"UPDATE machine SET disc_height_m = 150", "machine.disc_height_m = 150"},
      {"UPDATE machine SET disc_radius_m = 50", "machine.disc_radius_m = 50"},
      {"UPDATE materials SET density_kg_m3 = 1e300 WHERE name = 'A'", "materials.A.density_kg_m3 = 1e+300"},
      {"UPDATE runs SET rpm = 1e300 WHERE material = 'B'", "rpm = 1e+300"},
  };
  for (const auto& c : cases) {
    TempPath file("plausible.sqlite");
    write_sample_table(file.path());
    raw_exec(file.path(), c.sql);
    TableErrorKind kind{};
    const std::string problem = read_problem(file.path(), &kind);
    EXPECT_EQ(kind, TableErrorKind::kCorrupt) << problem;
    EXPECT_NE(problem.find(c.field), std::string::npos) << problem;
  }
  // One granule of 4.4e25 kg (a flipped exponent bit) is refused by its implied density.
  tables::Run run = spread::testing::sample_run("A", 450.0, 8);
  run.samples[3].mass_kg = 4.4e25f;
  EXPECT_NE(run_values_problem(run).find("sample 3 mass_kg"), std::string::npos) << run_values_problem(run);
  TempPath file("heavy.sqlite");
  TableWriter writer(file.path());
  writer.write_machine(spread::testing::sample_machine());
  writer.write_materials({spread::testing::sample_material("A", 0.4)});
  EXPECT_THROW(writer.write_run(run), std::invalid_argument);
}

// A child process writes the file with SQLite and dies inside COMMIT: the commit hook runs after the
// transaction's pages are journaled (and, with a one-page cache, partly written into the file), before
// the journal is deleted. That is the state a kill -9 during a commit leaves.
void die_inside_commit(const std::string& path) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    sqlite3* db = nullptr;
    if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) ::_exit(2);
    sqlite3_commit_hook(db, [](void*) -> int { ::_exit(0); }, nullptr);
    sqlite3_exec(db, "PRAGMA cache_size = 1; BEGIN; UPDATE runs SET samples = zeroblob(length(samples)); COMMIT;",
                 nullptr, nullptr, nullptr);
    ::_exit(3);  // the hook did not run
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 0) << "the child did not die inside the commit";
}

TEST(InterruptedWrite, ReadersNameItAndTheWriterRecovers) {
  TempPath file("killed.sqlite");
  write_sample_table(file.path());
  const TableContents before = read_table_file(file.path());
  die_inside_commit(file.path());
  ASSERT_TRUE(std::filesystem::exists(file.path() + "-journal"));

  TableErrorKind kind{};
  const std::string problem = read_problem(file.path(), &kind);
  EXPECT_EQ(kind, TableErrorKind::kIo);
  EXPECT_NE(problem.find("interrupted write"), std::string::npos) << problem;
  EXPECT_NE(problem.find("rerun lookup_builder"), std::string::npos) << problem;

  {
    TableWriter writer(file.path());  // what lookup_builder opens first
    EXPECT_TRUE(writer.recovered_interrupted_write());
  }
  EXPECT_FALSE(std::filesystem::exists(file.path() + "-journal"));
  const TableContents after = read_table_file(file.path());
  ASSERT_EQ(after.runs.size(), before.runs.size());
  for (std::size_t i = 0; i < after.runs.size(); ++i) {
    ASSERT_EQ(after.runs[i].samples.size(), before.runs[i].samples.size());
    EXPECT_EQ(std::memcmp(after.runs[i].samples.data(), before.runs[i].samples.data(),
                          after.runs[i].samples.size() * sizeof(LaunchSample)),
              0);
  }
}

TEST(WriterLock, ASecondWriterIsRefusedWithTheHoldersPid) {
  TempPath file("locked.sqlite");
  write_sample_table(file.path());
  TableWriter first(file.path());
  try {
    TableWriter second(file.path());
    FAIL() << "a second writer opened the file";
  } catch (const TableBusyError& e) {
    EXPECT_NE(std::string(e.what()).find("pid " + std::to_string(::getpid())), std::string::npos) << e.what();
  }
  // Readers are not writers: they still open the file.
  EXPECT_EQ(read_problem(file.path()), "");
}

TEST(WriterLock, ReleasedWhenTheWriterGoes) {
  TempPath file("relock.sqlite");
  write_sample_table(file.path());
  { TableWriter first(file.path()); }
  EXPECT_NO_THROW(TableWriter second(file.path()));
}

TEST(TablePath, AFifoIsRefusedWithoutWaiting) {
  TempPath file("fifo.sqlite");
  ASSERT_EQ(::mkfifo(file.path().c_str(), 0600), 0);
  ::alarm(20);  // a regression would block in open(); fail loudly instead of hanging the suite
  TableErrorKind kind{};
  const std::string problem = read_problem(file.path(), &kind);
  EXPECT_EQ(kind, TableErrorKind::kNotOurs);
  EXPECT_NE(problem.find("not a regular file"), std::string::npos) << problem;
  EXPECT_THROW(TableWriter writer(file.path()), TableError);
  ::alarm(0);
}

TEST(TablePath, AWalModeFileIsReadWithoutSideFiles) {
  TempPath file("wal.sqlite");
  write_sample_table(file.path());
  raw_exec(file.path(), "PRAGMA journal_mode = WAL;");  // the log is checkpointed and removed on close
  ASSERT_FALSE(std::filesystem::exists(file.path() + "-wal"));
  EXPECT_EQ(read_problem(file.path()), "");
  // A read-only reader must not create files: in a read-only directory it could not.
  EXPECT_FALSE(std::filesystem::exists(file.path() + "-wal"));
  EXPECT_FALSE(std::filesystem::exists(file.path() + "-shm"));
  // The writer switches such a file back to a rollback journal.
  { TableWriter writer(file.path()); }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open_v2(file.path().c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* mode = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "PRAGMA journal_mode", -1, &mode, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(mode), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(mode, 0)), "delete");
  sqlite3_finalize(mode);
  sqlite3_close(db);
}

}  // namespace
}  // namespace spread::tables
