#include "libspread/io/tables/table_writer.hpp"

#include <sqlite3.h>

#include <ctime>
#include <utility>

#include "libspread/io/tables/blend_rows.hpp"
#include "libspread/io/tables/material_schema.hpp"
#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/run_schema.hpp"
#include "libspread/io/tables/runs_manifest.hpp"
#include "libspread/io/tables/sample_codec.hpp"
#include "libspread/io/tables/sqlite_connection.hpp"
#include "libspread/io/tables/table_file.hpp"
#include "libspread/io/tables/table_rows.hpp"
#include "libspread/io/tables/machine_schema.hpp"
#include "libspread/io/tables/table_schema.hpp"
#include "libspread/io/tables/writer_lock.hpp"

namespace spread::tables {

using detail::Connection;
using detail::Statement;

namespace {

// Checks an existing non-empty file before anything opens it for writing: it must be SQLite, ours and
// of this format version. Read-only, so a refused file stays byte-identical.
void check_existing_file_is_ours(const std::string& path, const detail::TableFileInfo& file) {
  if (!file.sqlite) {
    throw TableError(TableErrorKind::kNotOurs, path + ": exists and is not an SQLite file; refusing to write into it");
  }
  if (file.application_id != kApplicationId) {
    throw TableError(TableErrorKind::kNotOurs, path + ": exists and is not a libspread table (application_id " +
                                                   std::to_string(file.application_id) + "); refusing to write into it");
  }
  if (file.user_version != kFormatVersion) {
    throw TableError(TableErrorKind::kWrongVersion, path + ": table format version " + std::to_string(file.user_version) +
                                                        ", this build writes version " +
                                                        std::to_string(kFormatVersion) + "; refusing to write");
  }
  // A truncated or damaged file still has a valid header; writing into it could make it worse. Check
  // the whole file (read-only) before a resumed build appends to it.
  std::string verdict;
  try {
    Connection probe(path, Connection::Mode::kReadOnly);
    Statement check(probe, "PRAGMA quick_check(1)");
    verdict = check.step() ? check.column_text(0) : std::string("no result");
  } catch (const TableError& e) {
    throw TableError(TableErrorKind::kCorrupt, path + ": damaged table file (" + e.what() + "); refusing to write into it");
  }
  if (verdict != "ok") {
    throw TableError(TableErrorKind::kCorrupt,
                     path + ": damaged table file (PRAGMA quick_check: " + verdict + "); refusing to write into it");
  }
}

// The list of the runs the file holds and its checksum (runs_manifest.hpp), inside the caller's
// transaction; true when they changed.
bool store_runs_list(Connection& db) {
  const std::string manifest = detail::runs_manifest(db);
  const std::pair<const char*, std::string> entries[] = {{detail::kRunsManifestKey, manifest},
                                                         {detail::kRunsManifestChecksumKey, detail::manifest_checksum(manifest)}};
  bool changed = false;
  for (const auto& [key, value] : entries) {
    Statement stored(db, "SELECT value FROM meta WHERE key = ?");
    stored.bind(1, std::string(key));
    if (stored.step() && stored.column_text(0) == value) continue;
    Statement upsert(db, "INSERT OR REPLACE INTO meta (key, value) VALUES (?, ?)");
    upsert.bind(1, std::string(key));
    upsert.bind(2, value);
    upsert.step();
    changed = true;
  }
  return changed;
}

// Commits on success, rolls back when an exception leaves the scope.
class Transaction {
 public:
  explicit Transaction(Connection& connection) : connection_(connection) { connection_.exec("BEGIN IMMEDIATE"); }
  ~Transaction() {
    if (!committed_) {
      try {
        connection_.exec("ROLLBACK");
      } catch (...) {  // NOLINT: a destructor must not throw; the original error is what matters
      }
    }
  }
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit() {
    connection_.exec("COMMIT");
    committed_ = true;
  }

 private:
  Connection& connection_;
  bool committed_ = false;
};

}  // namespace

struct TableWriter::Impl {
  std::unique_ptr<WriterLock> lock;        // declared first: released last
  std::unique_ptr<Connection> connection;
  bool recovered = false;
};

TableWriter::TableWriter(const std::string& path) : impl_(std::make_unique<Impl>()) {
  detail::TableFileInfo file = detail::inspect_table_file(path, /*allow_missing=*/true);
  impl_->lock = std::make_unique<WriterLock>(path);
  if (file.exists && !file.empty) {
    if (file.hot_journal && file.sqlite && file.application_id == kApplicationId) {
      // A writer stopped inside a transaction: a read-write open rolls its journal back (SQLite's hot
      // journal recovery, sqlite.org/atomiccommit.html §4.1); the file is then as after its last commit.
      Connection recover(path, Connection::Mode::kReadWrite);
      recover.pragma_int("user_version");
      impl_->recovered = true;
      file = detail::inspect_table_file(path, /*allow_missing=*/false);  // the header as after the rollback
    }
    check_existing_file_is_ours(path, file);
    impl_->connection = std::make_unique<Connection>(path, Connection::Mode::kReadWrite);
    if (file.wal) impl_->connection->exec("PRAGMA journal_mode = DELETE");
    return;
  }
  impl_->connection = std::make_unique<Connection>(path, Connection::Mode::kReadWriteCreate);
  Connection& db = *impl_->connection;
  db.exec("PRAGMA journal_mode = DELETE");
  Transaction transaction(db);
  db.exec("PRAGMA application_id = " + std::to_string(kApplicationId));
  db.exec("PRAGMA user_version = " + std::to_string(kFormatVersion));
  db.exec(detail::kSchemaSql);
  transaction.commit();
}

TableWriter::~TableWriter() = default;
TableWriter::TableWriter(TableWriter&&) noexcept = default;
TableWriter& TableWriter::operator=(TableWriter&&) noexcept = default;

const std::string& TableWriter::path() const { return impl_->connection->path(); }
bool TableWriter::recovered_interrupted_write() const { return impl_->recovered; }

// Read with the reader's checks: a builder must not extend a file whose rows were damaged.
std::optional<Machine> TableWriter::stored_machine() { return detail::read_machine_row(*impl_->connection); }

std::vector<Material> TableWriter::stored_materials() { return detail::read_material_rows(*impl_->connection); }

std::vector<TableWriter::StoredRun> TableWriter::stored_runs() {
  Statement query(*impl_->connection, "SELECT material, rpm, source, inputs_hash FROM runs ORDER BY material, rpm");
  std::vector<StoredRun> out;
  while (query.step()) out.push_back({query.column_text(0), query.column_double(1), query.column_text(2), query.column_text(3)});
  return out;
}

void TableWriter::write_machine(const Machine& machine) {
  const std::string problem = machine_problem(machine);
  if (!problem.empty()) throw std::invalid_argument(path() + ": refusing to write " + problem);
  Connection& db = *impl_->connection;
  Transaction transaction(db);
  std::string columns = "id", values = "1";
  for (const MachineColumn& c : kMachineColumns) {
    columns += ", " + std::string(c.name);
    values += ", ?";
  }
  Statement insert(db, "INSERT OR REPLACE INTO machine (" + columns + ", checksum) VALUES (" + values + ", ?)");
  int parameter = 1;
  for (const MachineColumn& c : kMachineColumns) {
    switch (c.kind) {
      case MachineColumn::Kind::kText: insert.bind(parameter++, machine.*c.text); break;
      case MachineColumn::Kind::kReal: insert.bind(parameter++, machine.*c.real); break;
      case MachineColumn::Kind::kInteger: insert.bind(parameter++, static_cast<std::int64_t>(machine.*c.integer)); break;
    }
  }
  insert.bind(parameter, machine_checksum(machine));
  insert.step();
  transaction.commit();
}

void TableWriter::write_materials(const std::vector<Material>& materials) {
  for (const Material& m : materials) {
    const std::string problem = material_problem(m);
    if (!problem.empty()) throw std::invalid_argument(path() + ": refusing to write " + problem);
  }
  Connection& db = *impl_->connection;
  Transaction transaction(db);
  std::string columns = "name";
  std::string values = "?";
  std::string updates;
  for (const MaterialQuantity& q : kMaterialQuantities) {
    const std::string name(q.name);
    columns += ", " + name;
    values += ", ?";
    updates += name + " = excluded." + name + ", ";
  }
  Statement upsert(db, "INSERT INTO materials (" + columns + ", checksum) VALUES (" + values +
                           ", ?) ON CONFLICT (name) DO UPDATE SET " + updates + "checksum = excluded.checksum");
  for (const Material& m : materials) {
    upsert.reset();
    upsert.bind(1, m.name);
    int column = 2;
    for (const MaterialQuantity& q : kMaterialQuantities) upsert.bind(column++, m.*q.member);
    upsert.bind(column, material_checksum(m));
    upsert.step();
  }
  transaction.commit();
}

void TableWriter::write_blend(const Blend& blend) {
  const std::string problem = stored_blend_problem(blend);
  if (!problem.empty()) throw std::invalid_argument(path() + ": refusing to write " + problem);
  Connection& db = *impl_->connection;
  for (const BlendRowComponent& c : blend.components) {
    Statement known(db, "SELECT 1 FROM materials WHERE name = ?");
    known.bind(1, c.material);
    if (!known.step())
      throw std::invalid_argument(path() + ": blend " + blend.name + ": component material \"" + c.material +
                                  "\" has not been written");
  }
  Transaction transaction(db);
  detail::write_blend_rows(db, blend);
  transaction.commit();
}

void TableWriter::write_meta(const std::string& key, const std::string& value) {
  Connection& db = *impl_->connection;
  Statement upsert(db, "INSERT OR REPLACE INTO meta (key, value) VALUES (?, ?)");
  upsert.bind(1, key);
  upsert.bind(2, value);
  upsert.step();
}

std::optional<std::string> TableWriter::stored_meta(const std::string& key) {
  Statement query(*impl_->connection, "SELECT value FROM meta WHERE key = ?");
  query.bind(1, key);
  if (!query.step()) return std::nullopt;
  return query.column_text(0);
}

void TableWriter::erase_meta(const std::string& key) {
  Statement remove(*impl_->connection, "DELETE FROM meta WHERE key = ?");
  remove.bind(1, key);
  remove.step();
}

void TableWriter::copy_from(const std::string& source) {
  check_existing_file_is_ours(source, detail::inspect_table_file(source, /*allow_missing=*/false));
  Connection from(source, Connection::Mode::kReadOnly);
  sqlite3* to = impl_->connection->handle();
  sqlite3_backup* backup = sqlite3_backup_init(to, "main", from.handle(), "main");
  if (backup == nullptr) impl_->connection->fail(sqlite3_errcode(to), "copying " + source + " into it");
  const int stepped = sqlite3_backup_step(backup, -1);
  const int finished = sqlite3_backup_finish(backup);
  if (stepped != SQLITE_DONE) impl_->connection->fail(stepped, "copying " + source + " into it");
  if (finished != SQLITE_OK) impl_->connection->fail(finished, "copying " + source + " into it");
}

void TableWriter::clear() {
  Connection& db = *impl_->connection;
  Transaction transaction(db);
  db.exec(detail::kLandingDataSql);
  for (const char* table : {"runs", detail::kBlendComponentsTable, "materials", "machine", "meta", detail::kLandingDataTable}) {
    db.exec(std::string("DELETE FROM ") + table);
  }
  transaction.commit();
}

bool TableWriter::has_run(const std::string& material, double rpm) {
  Statement query(*impl_->connection, "SELECT 1 FROM runs WHERE material = ? AND rpm = ?");
  query.bind(1, material);
  query.bind(2, rpm);
  return query.step();
}

void TableWriter::write_run(const Run& run, bool replace) {
  if (run.samples.empty()) {
    throw std::invalid_argument(path() + ": run " + run.material + " @ " + std::to_string(run.rpm) +
                                " rpm has no samples");
  }
  const std::string problem = run_values_problem(run);
  if (!problem.empty()) {
    throw std::invalid_argument(path() + ": refusing to write run " + run.material + " @ " + std::to_string(run.rpm) +
                                " rpm: " + problem);
  }
  Connection& db = *impl_->connection;
  Transaction transaction(db);
  {
    Statement material(db, "SELECT 1 FROM materials WHERE name = ?");
    material.bind(1, run.material);
    if (!material.step()) {
      throw std::invalid_argument(path() + ": run for material \"" + run.material +
                                  "\", which is not in the materials table (write_materials first)");
    }
  }
  Statement existing(db, "SELECT 1 FROM runs WHERE material = ? AND rpm = ?");
  existing.bind(1, run.material);
  existing.bind(2, run.rpm);
  if (existing.step()) {
    if (!replace) {
      throw RunExistsError(path() + ": run " + run.material + " @ " + std::to_string(run.rpm) +
                           " rpm already exists (pass replace to rebuild it)");
    }
    Statement remove(db, "DELETE FROM runs WHERE material = ? AND rpm = ?");
    remove.bind(1, run.material);
    remove.bind(2, run.rpm);
    remove.step();
  }
  const std::vector<std::uint8_t> blob = encode_samples(run.samples);
  // The columns of kRunColumns in their order, then the checksum.
  std::string columns, values;
  for (const RunColumn& column : kRunColumns) {
    columns += std::string(column.name) + ", ";
    values += "?, ";
  }
  Statement insert(db, "INSERT INTO runs (" + columns + "checksum) VALUES (" + values + "?)");
  const auto sample_count = static_cast<std::int64_t>(run.samples.size());
  const auto record_bytes = static_cast<std::int64_t>(kSampleBytes);
  int parameter = 1;
  for (const RunColumn& column : kRunColumns) {
    switch (column.kind) {
      case RunColumn::Kind::kText: insert.bind(parameter, std::string(column.stored_text(run))); break;
      case RunColumn::Kind::kReal: insert.bind(parameter, run.*column.real); break;
      case RunColumn::Kind::kInteger: insert.bind(parameter, run.*column.integer); break;
      case RunColumn::Kind::kSampleCount: insert.bind(parameter, sample_count); break;
      case RunColumn::Kind::kRecordLayout: insert.bind(parameter, std::string(kSampleLayout)); break;
      case RunColumn::Kind::kRecordBytes: insert.bind(parameter, record_bytes); break;
      case RunColumn::Kind::kSamples: insert.bind_blob(parameter, blob); break;
    }
    ++parameter;
  }
  insert.bind(parameter, run_checksum(run, sample_count, blob, kSampleLayout, record_bytes));
  insert.step();
  store_runs_list(db);  // in the run's transaction
  transaction.commit();
}

bool TableWriter::list_runs() {
  Connection& db = *impl_->connection;
  Transaction transaction(db);  // the list and its checksum together
  const bool changed = store_runs_list(db);
  transaction.commit();
  return changed;
}

void TableWriter::write_landing_data(const LandingData& landing) {
  Connection& db = *impl_->connection;
  Transaction transaction(db);
  detail::write_landing_data(db, landing);
  transaction.commit();
}

std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace spread::tables
