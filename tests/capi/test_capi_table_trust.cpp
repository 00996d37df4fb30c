// Tables no one can quietly change, and what spread_open found in them: a run deleted together with its
// line of the table's list of runs is refused (the list's checksum no longer matches); a table whose runs
// carry no checked list is refused unless the caller opts in to legacy files, which the handle then says;
// a table whose landing data was deleted still opens, and the handle says its landing grids were flown at
// open. Real files written by the library's writer, changed with SQLite as an editor would.
#include <sqlite3.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "spread/spread.h"
#include "tests/capi/capi_test_files.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace {

using spread::testing::temp_path;

void exec_sql(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* err = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err);
  const std::string message = err ? err : "";
  sqlite3_free(err);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << message;
}

struct Opened {
  spread_status status = SPREAD_ERROR_INTERNAL;
  std::string detail;
  uint32_t flags = 0;
  double working_width_m = NAN;  // can at 650 rpm, between the 600 and 700 rpm rows
};

Opened open_and_predict(const std::string& path, uint32_t open_flags = 0u) {
  Opened out;
  spread_tables* tables = nullptr;
  out.status = spread_open_with_flags(path.c_str(), open_flags, nullptr, &tables);
  if (out.status != SPREAD_OK) {
    out.detail = spread_last_error_detail();
    EXPECT_EQ(tables, nullptr);
    return out;
  }
  EXPECT_EQ(spread_table_flags(tables, &out.flags), SPREAD_OK);
  spread_prediction_def def = spread_prediction_def_default();
  def.material = "can";
  def.rpm = 650.0;
  spread_prediction result{};
  EXPECT_EQ(spread_predict(tables, &def, &result, nullptr, 0), SPREAD_OK) << spread_last_error_detail();
  out.working_width_m = result.working_width_to_and_fro_m;
  spread_close(tables);
  return out;
}

// The list's line of one run, as the writer stores it ("material\trpm\tchecksum\n").
std::string manifest_line(const std::string& path, const std::string& material, double rpm) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* query = nullptr;
  sqlite3_prepare_v2(db, "SELECT checksum FROM runs WHERE material = ? AND rpm = ?", -1, &query, nullptr);
  sqlite3_bind_text(query, 1, material.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(query, 2, rpm);
  std::string line;
  if (sqlite3_step(query) == SQLITE_ROW) {
    char rpm_text[40];
    std::snprintf(rpm_text, sizeof rpm_text, "%.17g", rpm);
    line = material + "\t" + rpm_text + "\t" + reinterpret_cast<const char*>(sqlite3_column_text(query, 0)) + "\n";
  }
  sqlite3_finalize(query);
  sqlite3_close(db);
  return line;
}

TEST(CapiTableTrust, ARunDeletedWithItsLineOfTheListIsRefused) {
  const std::string path = temp_path("trust_deleted_run.sqlite");
  spread::testing::write_synthetic_table(path);
  const Opened whole = open_and_predict(path);
  ASSERT_EQ(whole.status, SPREAD_OK) << whole.detail;
  EXPECT_EQ(whole.flags & SPREAD_TABLE_RUNS_UNCHECKED, 0u);

  // The 700 rpm row and its line of the list deleted: the list matches the runs left, but not its checksum.
  const std::string line = manifest_line(path, "can", 700.0);
  ASSERT_FALSE(line.empty());
  exec_sql(path, "DELETE FROM runs WHERE material = 'can' AND rpm = 700; UPDATE meta SET value = replace(value, '" +
                     line + "', '') WHERE key = 'runs_manifest';");
  const Opened edited = open_and_predict(path);
  EXPECT_EQ(edited.status, SPREAD_ERROR_FILE_CORRUPT);
  EXPECT_NE(edited.detail.find("does not match its checksum"), std::string::npos) << edited.detail;

  // ... and the checksum deleted too: a table whose runs carry no checked list, refused as a legacy file
  // with the opt-in named; opened with it, the handle says its runs went unchecked, and the prediction
  // between the rows left is not the whole table's.
  exec_sql(path, "DELETE FROM meta WHERE key = 'runs_manifest_checksum';");
  const Opened unchecked = open_and_predict(path);
  EXPECT_EQ(unchecked.status, SPREAD_ERROR_FILE_WRONG_VERSION);
  EXPECT_NE(unchecked.detail.find("SPREAD_OPEN_LEGACY_FILES"), std::string::npos) << unchecked.detail;
  EXPECT_NE(unchecked.detail.find("without its checksum"), std::string::npos) << unchecked.detail;
  const Opened legacy = open_and_predict(path, SPREAD_OPEN_LEGACY_FILES);
  ASSERT_EQ(legacy.status, SPREAD_OK) << legacy.detail;
  EXPECT_NE(legacy.flags & SPREAD_TABLE_RUNS_UNCHECKED, 0u);
  EXPECT_NE(legacy.working_width_m, whole.working_width_m);

  // The whole list gone: the same refusal, naming what is missing.
  exec_sql(path, "DELETE FROM meta WHERE key = 'runs_manifest';");
  const Opened no_list = open_and_predict(path);
  EXPECT_EQ(no_list.status, SPREAD_ERROR_FILE_WRONG_VERSION);
  EXPECT_NE(no_list.detail.find("`runs_manifest` missing"), std::string::npos) << no_list.detail;
  EXPECT_EQ(open_and_predict(path, SPREAD_OPEN_LEGACY_FILES).status, SPREAD_OK);
}

// The writer lists the runs of a legacy table when asked (what lookup_builder does with every table it
// leaves); the table then opens without the opt-in.
TEST(CapiTableTrust, ALegacyTableListedByTheWriterOpens) {
  const std::string path = temp_path("trust_legacy.sqlite");
  spread::testing::write_synthetic_table(path);
  exec_sql(path, "DELETE FROM meta WHERE key IN ('runs_manifest', 'runs_manifest_checksum');");
  ASSERT_EQ(open_and_predict(path).status, SPREAD_ERROR_FILE_WRONG_VERSION);
  {
    spread::tables::TableWriter writer(path);
    EXPECT_TRUE(writer.list_runs());
    EXPECT_FALSE(writer.list_runs());  // nothing more to list
  }
  const Opened listed = open_and_predict(path);
  EXPECT_EQ(listed.status, SPREAD_OK) << listed.detail;
  EXPECT_EQ(listed.flags & SPREAD_TABLE_RUNS_UNCHECKED, 0u);
}

TEST(CapiTableTrust, UnknownOpenFlagsAreRefused) {
  const std::string path = temp_path("trust_flags.sqlite");
  spread::testing::write_synthetic_table(path);
  spread_tables* tables = nullptr;
  EXPECT_EQ(spread_open_with_flags(path.c_str(), 0x2u, nullptr, &tables), SPREAD_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(tables, nullptr);
  EXPECT_NE(std::string(spread_last_error_detail()).find("spread_open_with_flags: flags 0x2"), std::string::npos)
      << spread_last_error_detail();
  uint32_t flags = 0;
  EXPECT_EQ(spread_table_flags(nullptr, &flags), SPREAD_ERROR_NULL_POINTER);
}

// A table with runs that fly drag alone (the product's tables), with its landing data stored as
// lookup_builder stores it.
std::string write_table_with_landing_data(const std::string& name) {
  const std::string path = temp_path(name);
  auto contents = spread::testing::synthetic_contents();
  for (auto& run : contents.runs) run.stats_json = R"({"flight_effects":"drag"})";
  std::filesystem::remove(path);
  spread::tables::TableWriter writer(path);
  writer.write_machine(contents.machine);
  writer.write_materials(contents.materials);
  for (const auto& run : contents.runs) writer.write_run(run);
  const spread::predict::Predictor predictor(spread::tables::read_table_file(path));
  for (const auto& landing : predictor.derived_landing_data()) writer.write_landing_data(landing);
  return path;
}

TEST(CapiTableTrust, DeletedLandingDataIsReportedNotJustSlow) {
  const std::string path = write_table_with_landing_data("trust_landing.sqlite");
  const Opened stored = open_and_predict(path);
  ASSERT_EQ(stored.status, SPREAD_OK) << stored.detail;
  EXPECT_EQ(stored.flags & SPREAD_TABLE_LANDING_DATA_DERIVED, 0u);

  exec_sql(path, "DELETE FROM landing_data;");
  const Opened emptied = open_and_predict(path);
  ASSERT_EQ(emptied.status, SPREAD_OK) << emptied.detail;
  EXPECT_NE(emptied.flags & SPREAD_TABLE_LANDING_DATA_DERIVED, 0u);
  EXPECT_EQ(emptied.working_width_m, stored.working_width_m);  // flown at open to the same grid

  exec_sql(path, "DROP TABLE landing_data;");
  const Opened dropped = open_and_predict(path);
  ASSERT_EQ(dropped.status, SPREAD_OK) << dropped.detail;
  EXPECT_NE(dropped.flags & SPREAD_TABLE_LANDING_DATA_DERIVED, 0u);
}

}  // namespace
