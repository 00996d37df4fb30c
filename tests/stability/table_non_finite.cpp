// NaN and Inf in a launch table: a run whose samples hold a NaN or Inf (put there by SQL, as a
// damaged or hand-edited file would), and non-finite or missing numbers in the machine, material and
// run rows. Through the C API each must be refused with a clear status — the file is corrupt
// (SPREAD_ERROR_FILE_CORRUPT), or the prediction is refused with a status other than
// SPREAD_ERROR_INTERNAL — or handled so that no NaN reaches a prediction.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "libspread/io/tables/sample_codec.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "spread/spread.h"
#include "tests/stability/stability_table.hpp"

namespace spread::stability {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Runs `sql` with `value` bound to ?1 (SQLite stores a bound NaN as NULL).
void execute(const std::string& path, const std::string& sql, double value) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* statement = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
  sqlite3_bind_double(statement, 1, value);
  EXPECT_EQ(sqlite3_step(statement), SQLITE_DONE) << sqlite3_errmsg(db);
  sqlite3_finalize(statement);
  sqlite3_close(db);
}

// Replaces float `field` of sample `index` in every run's BLOB with `value`.
void poison_samples(const std::string& path, int field, float value, std::size_t index = 0) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* select = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT rowid, samples FROM runs", -1, &select, nullptr), SQLITE_OK);
  std::vector<std::pair<sqlite3_int64, std::vector<std::uint8_t>>> blobs;
  while (sqlite3_step(select) == SQLITE_ROW) {
    const auto* bytes = static_cast<const std::uint8_t*>(sqlite3_column_blob(select, 1));
    const int size = sqlite3_column_bytes(select, 1);
    blobs.emplace_back(sqlite3_column_int64(select, 0), std::vector<std::uint8_t>(bytes, bytes + size));
  }
  sqlite3_finalize(select);
  ASSERT_FALSE(blobs.empty());
  for (auto& [rowid, blob] : blobs) {
    std::vector<tables::LaunchSample> samples = tables::decode_samples(blob);
    ASSERT_LT(index, samples.size());
    float* fields = &samples[index].x_m;  // kSampleFloats consecutive floats, in the layout's order
    static_assert(sizeof(tables::LaunchSample) == tables::kSampleFloats * sizeof(float));
    fields[field] = value;
    const std::vector<std::uint8_t> encoded = tables::encode_samples(samples);
    sqlite3_stmt* update = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db, "UPDATE runs SET samples = ?1 WHERE rowid = ?2", -1, &update, nullptr), SQLITE_OK);
    sqlite3_bind_blob(update, 1, encoded.data(), static_cast<int>(encoded.size()), SQLITE_TRANSIENT);
    sqlite3_bind_int64(update, 2, rowid);
    EXPECT_EQ(sqlite3_step(update), SQLITE_DONE);
    sqlite3_finalize(update);
  }
  sqlite3_close(db);
}

// The acceptance rule of this file, applied to one damaged table.
void expect_refused_or_finite(const std::string& path, const std::string& what) {
  SCOPED_TRACE(what);
  spread_tables* tables = nullptr;
  const spread_status open_status = spread_open(path.c_str(), &tables);
  if (open_status != SPREAD_OK) {
    EXPECT_EQ(open_status, SPREAD_ERROR_FILE_CORRUPT) << spread_status_str(open_status);
    EXPECT_EQ(tables, nullptr);
    return;
  }
  int32_t count = 0;
  ASSERT_EQ(spread_material_count(tables, &count), SPREAD_OK);
  for (int32_t i = 0; i < count; ++i) {
    const char* name = nullptr;
    double low = 0.0;
    double high = 0.0;
    ASSERT_EQ(spread_material_name(tables, i, &name), SPREAD_OK);
    const spread_status range = spread_material_rpm_range(tables, i, &low, &high);
    if (range != SPREAD_OK) continue;
    for (double rpm : {low, 0.5 * (low + high), high}) {
      spread_prediction_def def = spread_prediction_def_default();
      def.material = name;
      def.rpm = rpm;
      spread_prediction result{};
      std::vector<double> trays(4096);
      const spread_status status = spread_predict(tables, &def, &result, trays.data(), trays.size());
      EXPECT_NE(status, SPREAD_ERROR_INTERNAL) << "a damaged record reached the flight code (rpm " << rpm << ")";
      if (status != SPREAD_OK) continue;
      EXPECT_TRUE(std::isfinite(result.throw_width_m)) << "rpm " << rpm;
      EXPECT_TRUE(std::isfinite(result.mean_radius_m)) << "rpm " << rpm;
      EXPECT_TRUE(std::isfinite(result.radial_width_m)) << "rpm " << rpm;
      EXPECT_TRUE(result.lost_mass_fraction >= 0.0 && result.lost_mass_fraction <= 1.0) << result.lost_mass_fraction;
      for (int k = 0; k < result.tray_count; ++k) ASSERT_TRUE(std::isfinite(trays[static_cast<std::size_t>(k)])) << k;
    }
  }
  spread_close(tables);
}

TEST(TableNonFinite, UndamagedTablePredicts) {
  spread_tables* tables = nullptr;
  ASSERT_EQ(spread_open(stability_table_path().c_str(), &tables), SPREAD_OK);
  spread_close(tables);
  expect_refused_or_finite(stability_table_path(), "undamaged");
}

// The reader refuses the damaged file as corrupt with a message naming the record and field, and so
// spread_open says SPREAD_ERROR_FILE_CORRUPT: nothing of it reaches a prediction.
void expect_corrupt(const std::string& path, const std::string& what, const std::vector<std::string>& named) {
  SCOPED_TRACE(what);
  spread_tables* tables = nullptr;
  EXPECT_EQ(spread_open(path.c_str(), &tables), SPREAD_ERROR_FILE_CORRUPT);
  EXPECT_EQ(tables, nullptr);
  spread_close(tables);
  try {
    (void)tables::read_table_file(path);
    ADD_FAILURE() << "read_table_file accepted it";
  } catch (const tables::TableError& e) {
    EXPECT_EQ(e.kind(), tables::TableErrorKind::kCorrupt) << e.what();
    for (const std::string& word : named) EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}

constexpr const char* kSampleFieldNames[] = {"x_m",     "y_m",     "z_m",     "t_s",     "vx_norm",    "vy_norm",
                                             "vz_norm", "wx_norm", "wy_norm", "wz_norm", "diameter_m", "mass_kg"};

// Was a known issue: x, y, v, ω, diameter → SPREAD_ERROR_INTERNAL from spread_predict, mass = NaN/Inf →
// SPREAD_OK with NaN trays.
TEST(TableNonFinite, NanOrInfInAnySampleField) {
  for (int field = 0; field < tables::kSampleFloats; ++field) {
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                      -std::numeric_limits<float>::infinity()}) {
      const std::string name = kSampleFieldNames[field];
      const std::string path = copy_of_table("sample_" + std::to_string(field) + ".sqlite");
      poison_samples(path, field, bad);
      expect_corrupt(path, "sample 0 " + name + " = " + std::to_string(bad), {"sample 0 " + name, "Urea"});
    }
  }
}

// Finite but impossible sample values (a zero or negative diameter or mass). Was a known issue (INTERNAL).
TEST(TableNonFinite, ZeroOrNegativeDiameterAndMass) {
  for (int field : {10, 11}) {
    for (float bad : {0.0f, -1e-3f}) {
      const std::string name = kSampleFieldNames[field];
      const std::string path = copy_of_table("sample_sign_" + std::to_string(field) + ".sqlite");
      poison_samples(path, field, bad);
      expect_corrupt(path, name + " = " + std::to_string(bad), {"sample 0 " + name, "> 0"});
    }
  }
}

// Removes the NOT NULL constraints of `table` from the schema (a hand-edited or foreign-written file),
// so a NULL can be stored where the reader expects a number.
void drop_not_null(const std::string& path, const std::string& table) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  const std::string sql = "PRAGMA writable_schema = ON; UPDATE sqlite_master SET sql = replace(sql, 'NOT NULL', '') "
                          "WHERE type = 'table' AND name = '" + table + "'; PRAGMA writable_schema = OFF;";
  char* error = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK) << (error ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

// One row of `table` (runs: the lowest rpm, as two runs with the same rpm would break UNIQUE).
std::string one_row(const std::string& table) {
  return table == "runs" ? " WHERE rowid = (SELECT min(rowid) FROM runs)" : "";
}

// Was a known issue: machine.disc_radius_m = Inf, materials.density_kg_m3 = ±Inf → INTERNAL. ±Inf is now
// corrupt naming the column; a NaN is stored by SQLite as NULL, which the schema's NOT NULL refuses — and
// in a file whose schema lost NOT NULL, the reader reports the value as missing.
TEST(TableNonFinite, NanInfOrMissingInMachineMaterialAndRunRows) {
  const std::vector<std::pair<std::string, std::string>> columns = {
      {"machine", "disc_radius_m"},     {"machine", "disc_height_m"},       {"machine", "disc_spacing_m"},
      {"machine", "cone_angle_rad"},    {"materials", "density_kg_m3"},     {"materials", "diameter_mean_m"},
      {"materials", "diameter_sd_m"},   {"materials", "friction_wall"},     {"materials", "youngs_modulus_pa"},
      {"runs", "rpm"},
  };
  int n = 0;
  for (const auto& [table, column] : columns) {
    for (double bad : {kInf, -kInf}) {
      const std::string path = copy_of_table("row_" + std::to_string(n++) + ".sqlite");
      execute(path, "UPDATE " + table + " SET " + column + " = ?1" + one_row(table), bad);
      expect_corrupt(path, table + "." + column + " = " + std::to_string(bad), {column, "inf"});
    }
    const std::string path = copy_of_table("row_" + std::to_string(n++) + ".sqlite");
    drop_not_null(path, table);
    execute(path, "UPDATE " + table + " SET " + column + " = ?1" + one_row(table), kNaN);  // stored as NULL
    expect_corrupt(path, table + "." + column + " = NaN (NULL)", {column, "missing (NULL)"});
  }
  // Finite but impossible machine and material values.
  for (const auto& [table, column, value] : std::vector<std::tuple<std::string, std::string, double>>{
           {"machine", "disc_radius_m", 0.0}, {"machine", "disc_height_m", -0.5}, {"machine", "cone_angle_rad", 2.0},
           {"materials", "density_kg_m3", 0.0}, {"materials", "diameter_mean_m", -1e-3},
           {"materials", "restitution", 1.5}, {"runs", "rpm", -450.0}}) {
    const std::string path = copy_of_table("row_" + std::to_string(n++) + ".sqlite");
    execute(path, "UPDATE " + table + " SET " + column + " = ?1" + one_row(table), value);
    expect_corrupt(path, table + "." + column + " = " + std::to_string(value), {column});
  }
}

// Was a known issue: TableWriter wrote a NaN sample without complaint. It now refuses with
// std::invalid_argument naming the sample and field, and writes nothing of that run.
TEST(TableNonFinite, WriterWithNanSample) {
  const std::string path = (temp_directory().path() / "writer_nan.sqlite").string();
  tables::TableContents contents = tables::read_table_file(stability_table_path());
  tables::TableWriter writer(path);
  writer.write_machine(contents.machine);
  writer.write_materials(contents.materials);
  tables::Run run = contents.runs.at(0);
  run.samples.at(1).vx_norm = std::numeric_limits<float>::quiet_NaN();
  try {
    writer.write_run(run);
    ADD_FAILURE() << "the writer wrote a NaN sample";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sample 1 vx_norm"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(writer.has_run(run.material, run.rpm));
  run = contents.runs.at(0);
  run.samples.at(2).mass_kg = 0.0f;
  EXPECT_THROW(writer.write_run(run), std::invalid_argument);
  run = contents.runs.at(0);
  run.rpm = kInf;
  EXPECT_THROW(writer.write_run(run), std::invalid_argument);
  // Machine and material rows likewise.
  tables::Machine machine = contents.machine;
  machine.disc_radius_m = kNaN;
  try {
    writer.write_machine(machine);
    ADD_FAILURE() << "the writer wrote a NaN disc radius";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("disc_radius_m"), std::string::npos) << e.what();
  }
  std::vector<tables::Material> materials = contents.materials;
  materials.at(0).density_kg_m3 = -kInf;
  try {
    writer.write_materials(materials);
    ADD_FAILURE() << "the writer wrote an infinite density";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("density_kg_m3"), std::string::npos) << e.what();
  }
  // The valid rows still write and read back.
  writer.write_run(contents.runs.at(0));
  EXPECT_EQ(tables::read_table_file(path).runs.size(), 1u);
}

}  // namespace
}  // namespace spread::stability
