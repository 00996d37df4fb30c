// Every TableErrorKind produced by a real file, and the reader leaves each file byte-identical.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "table_fixtures.hpp"
#include "tests/support/temp_path.hpp"

namespace spread::tables {
namespace {

using spread::testing::file_bytes;
using spread::testing::raw_exec;
using spread::testing::TempPath;

// Reads the file, expects a TableError of `kind` whose message names the file, and checks the file
// was not modified.
void expect_read_error(const std::string& path, TableErrorKind kind, const std::string& message_part = "") {
  const bool existed = std::filesystem::exists(path);
  const std::vector<char> before = existed ? file_bytes(path) : std::vector<char>{};
  try {
    read_table_file(path);
    ADD_FAILURE() << "read_table_file accepted " << path;
  } catch (const TableError& e) {
    EXPECT_EQ(e.kind(), kind) << e.what();
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    if (!message_part.empty()) {
      EXPECT_NE(what.find(message_part), std::string::npos) << what;
    }
  }
  EXPECT_EQ(std::filesystem::exists(path), existed);
  if (existed) {
    EXPECT_EQ(file_bytes(path), before) << "the reader modified " << path;
  }
  EXPECT_FALSE(std::filesystem::exists(path + "-journal"));
}

TEST(TableErrors, MissingFile) {
  TempPath file("missing");
  expect_read_error(file.path(), TableErrorKind::kMissing, "no such file");
}

TEST(TableErrors, GarbageBytesAreNotOurs) {
  TempPath file("garbage");
  std::vector<char> garbage(5000);
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<char>((i * 37 + 11) % 256);
  spread::testing::write_bytes(file.path(), garbage);
  expect_read_error(file.path(), TableErrorKind::kNotOurs, "not an SQLite file");
}

TEST(TableErrors, ForeignSqliteDatabaseIsNotOurs) {
  TempPath file("foreign");
  raw_exec(file.path(), "CREATE TABLE runs (x INTEGER); INSERT INTO runs VALUES (1);");
  expect_read_error(file.path(), TableErrorKind::kNotOurs, "application_id");
  // The writer refuses it too, and leaves it as it was.
  const std::vector<char> before = file_bytes(file.path());
  try {
    TableWriter writer(file.path());
    ADD_FAILURE() << "writer accepted a foreign database";
  } catch (const TableError& e) {
    EXPECT_EQ(e.kind(), TableErrorKind::kNotOurs);
  }
  EXPECT_EQ(file_bytes(file.path()), before);
}

TEST(TableErrors, BumpedUserVersionIsWrongVersion) {
  TempPath file("version");
  spread::testing::write_sample_table(file.path());
  raw_exec(file.path(), "PRAGMA user_version = " + std::to_string(kFormatVersion + 1));
  expect_read_error(file.path(), TableErrorKind::kWrongVersion, "version");
  const std::vector<char> before = file_bytes(file.path());
  try {
    TableWriter writer(file.path());
    ADD_FAILURE() << "writer accepted a file of another version";
  } catch (const TableError& e) {
    EXPECT_EQ(e.kind(), TableErrorKind::kWrongVersion);
  }
  EXPECT_EQ(file_bytes(file.path()), before);
}

TEST(TableErrors, TruncatedFileIsCorrupt) {
  TempPath file("truncated");
  spread::testing::write_sample_table(file.path(), 2000);  // several pages of BLOB overflow
  std::vector<char> bytes = file_bytes(file.path());
  ASSERT_GT(bytes.size(), 4u * 4096u);
  bytes.resize(bytes.size() / 2);
  spread::testing::write_bytes(file.path(), bytes);
  expect_read_error(file.path(), TableErrorKind::kCorrupt);
}

TEST(TableErrors, BlobOfWrongSizeIsCorrupt) {
  TempPath file("blob");
  spread::testing::write_sample_table(file.path());
  raw_exec(file.path(), "UPDATE runs SET samples = substr(samples, 1, 100) WHERE material = 'B'");
  expect_read_error(file.path(), TableErrorKind::kCorrupt, "BLOB");
}

TEST(TableErrors, DifferentRecordLayoutIsCorrupt) {
  TempPath file("layout");
  spread::testing::write_sample_table(file.path());
  raw_exec(file.path(), "UPDATE runs SET record_layout = 'x_m,y_m' WHERE material = 'A' AND rpm = 600");
  expect_read_error(file.path(), TableErrorKind::kCorrupt, "layout");
}

TEST(TableErrors, TableWithoutRunsIsEmpty) {
  TempPath file("empty");
  {
    TableWriter writer(file.path());
    writer.write_machine(spread::testing::sample_machine());
    writer.write_materials({spread::testing::sample_material("A", 0.4)});
  }
  expect_read_error(file.path(), TableErrorKind::kEmpty, "no runs");
}

// Physically impossible values: the reader says corrupt naming the record and field (docs/table-format.md,
// value rules); the writer refuses to write them at all.
TEST(TableErrors, ImpossibleValuesAreCorruptNamingTheField) {
  const std::vector<std::pair<std::string, std::string>> damage = {
      {"UPDATE machine SET disc_radius_m = 0", "machine.disc_radius_m = 0"},
      {"UPDATE machine SET disc_height_m = 9e999", "machine.disc_height_m = inf"},
      {"UPDATE materials SET density_kg_m3 = -9e999 WHERE name = 'B'", "materials.B.density_kg_m3 = -inf"},
      {"UPDATE materials SET poisson_ratio = 0.7 WHERE name = 'A'", "materials.A.poisson_ratio = 0.7"},
      {"UPDATE runs SET dt_flight_s = -1 WHERE material = 'A' AND rpm = 600", "dt_flight_s = -1"},
  };
  for (const auto& [sql, named] : damage) {
    TempPath file("impossible");
    spread::testing::write_sample_table(file.path());
    raw_exec(file.path(), sql);
    expect_read_error(file.path(), TableErrorKind::kCorrupt, named);
  }
}

TEST(TableErrors, WriterRefusesImpossibleValuesNamingTheField) {
  TempPath file("writer");
  TableWriter writer(file.path());
  Machine machine = spread::testing::sample_machine();
  machine.disc_radius_m = std::numeric_limits<double>::quiet_NaN();
  try {
    writer.write_machine(machine);
    ADD_FAILURE() << "wrote a NaN radius";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("machine.disc_radius_m = nan"), std::string::npos) << e.what();
  }
  writer.write_machine(spread::testing::sample_machine());
  Material material = spread::testing::sample_material("A", 0.4);
  material.diameter_mean_m = 0.0;
  EXPECT_THROW(writer.write_materials({spread::testing::sample_material("B", 0.4), material}), std::invalid_argument);
  writer.write_materials({spread::testing::sample_material("A", 0.4)});
  for (int field = 0; field < kSampleFloats; ++field) {
    spread::tables::Run run = spread::testing::sample_run("A", 450.0, 8);
    float* values = &run.samples.at(5).x_m;
    values[field] = field >= 10 ? -1.0f : std::numeric_limits<float>::infinity();
    try {
      writer.write_run(run);
      ADD_FAILURE() << "wrote field " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("sample 5 "), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(writer.has_run("A", 450.0));
  writer.write_run(spread::testing::sample_run("A", 450.0, 8));
  EXPECT_EQ(read_table_file(file.path()).runs.size(), 1u);
}

TEST(TableErrors, ZeroByteFileIsNotOurs) {
  TempPath file("zero");
  spread::testing::write_bytes(file.path(), {});
  expect_read_error(file.path(), TableErrorKind::kNotOurs);
}

TEST(TableErrors, KindsHaveNames) {
  for (TableErrorKind kind : {TableErrorKind::kMissing, TableErrorKind::kNotOurs, TableErrorKind::kCorrupt,
                              TableErrorKind::kWrongVersion, TableErrorKind::kEmpty, TableErrorKind::kIo}) {
    EXPECT_STRNE(to_string(kind), "unknown");
  }
}

}  // namespace
}  // namespace spread::tables
