#include "libspread/io/tables/table_reader.hpp"

#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/sample_codec.hpp"
#include "libspread/io/tables/sqlite_connection.hpp"
#include "libspread/io/tables/table_file.hpp"
#include "libspread/io/tables/table_rows.hpp"

namespace spread::tables {

using detail::Connection;
using detail::Statement;

namespace {

using detail::raise;
using detail::required_double;
using detail::verify_checksum;

// SQLite opens any file without complaint; the first read of the header is where garbage shows.
std::int64_t read_application_id(Connection& db) {
  try {
    return db.pragma_int("application_id");
  } catch (const TableError& e) {
    if (e.kind() == TableErrorKind::kNotOurs) raise(TableErrorKind::kNotOurs, db.path(), "not an SQLite file");
    throw;
  }
}

void run_quick_check(Connection& db) {
  Statement check(db, "PRAGMA quick_check(1)");
  if (!check.step()) raise(TableErrorKind::kCorrupt, db.path(), "PRAGMA quick_check returned nothing");
  const std::string verdict = check.column_text(0);
  if (verdict != "ok") raise(TableErrorKind::kCorrupt, db.path(), "PRAGMA quick_check: " + verdict);
}

void require_tables(Connection& db) {
  for (const char* table : {"machine", "materials", "runs", "meta"}) {
    Statement query(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
    query.bind(1, std::string(table));
    if (!query.step()) raise(TableErrorKind::kCorrupt, db.path(), std::string("table `") + table + "` is missing");
  }
}

std::vector<Run> read_runs(Connection& db) {
  Statement query(db,
                  "SELECT material, rpm, source, sample_count, record_layout, record_bytes, samples, scene_hash, "
                  "scene_text, effects, dt_contact_s, dt_flight_s, particle_count, software_version, created_utc, "
                  "stats_json, convergence_json, inputs_hash, checksum FROM runs ORDER BY material, rpm");
  std::vector<Run> runs;
  while (query.step()) {
    Run run;
    run.material = query.column_text(0);
    run.rpm = required_double(query, 1, db, "run " + run.material + ": rpm");
    run.source = query.column_text(2);
    const std::int64_t sample_count = query.column_int(3);
    const std::string layout = query.column_text(4);
    const std::int64_t record_bytes = query.column_int(5);
    const std::vector<std::uint8_t> blob = query.column_blob(6);
    const std::string which = "run " + run.material + " @ " + std::to_string(run.rpm) + " rpm: ";
    if (layout != kSampleLayout) {
      raise(TableErrorKind::kCorrupt, db.path(), which + "record layout \"" + layout + "\" differs from \"" +
                                                     kSampleLayout + "\"");
    }
    if (record_bytes != static_cast<std::int64_t>(kSampleBytes)) {
      raise(TableErrorKind::kCorrupt, db.path(), which + "record size " + std::to_string(record_bytes) +
                                                     " bytes, expected " + std::to_string(kSampleBytes));
    }
    if (sample_count <= 0 || blob.size() != static_cast<std::size_t>(sample_count) * kSampleBytes) {
      raise(TableErrorKind::kCorrupt, db.path(),
            which + "sample BLOB has " + std::to_string(blob.size()) + " bytes, expected sample_count " +
                std::to_string(sample_count) + " x " + std::to_string(kSampleBytes));
    }
    run.samples = decode_samples(blob);
    run.scene_hash = query.column_text(7);
    run.scene_text = query.column_text(8);
    run.effects = query.column_text(9);
    run.dt_contact_s = required_double(query, 10, db, which + "dt_contact_s");
    run.dt_flight_s = required_double(query, 11, db, which + "dt_flight_s");
    run.particle_count = query.column_int(12);
    run.software_version = query.column_text(13);
    run.created_utc = query.column_text(14);
    run.stats_json = query.column_text(15);
    run.convergence_json = query.column_text(16);
    run.inputs_hash = query.column_text(17);
    const std::string problem = run_values_problem(run);
    if (!problem.empty()) raise(TableErrorKind::kCorrupt, db.path(), which + "impossible value: " + problem);
    verify_checksum(db, which.substr(0, which.size() - 2), query.column_text(18),
                    run_checksum(run, blob, layout, record_bytes));
    runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace

TableContents read_table_file(const std::string& path) {
  const detail::TableFileInfo file = detail::inspect_table_file(path, /*allow_missing=*/false);
  if (file.empty) raise(TableErrorKind::kNotOurs, path, "empty file (0 bytes), not a table file");
  if (file.wal && file.wal_has_content) {
    raise(TableErrorKind::kIo, path,
          "the file is in WAL mode and its write-ahead log (" + path +
              "-wal) holds changes not yet written back; open it once read-write (rerun lookup_builder on it) first");
  }
  // A WAL file with an empty log reads the same as any other, but a plain read-only open would create
  // -wal/-shm files (and fail in a read-only directory): open it as immutable.
  Connection db(path, file.wal ? Connection::Mode::kReadOnlyImmutable : Connection::Mode::kReadOnly);
  const std::int64_t application_id = read_application_id(db);
  if (application_id != kApplicationId) {
    raise(TableErrorKind::kNotOurs, path,
          "SQLite file but not a libspread table (application_id " + std::to_string(application_id) + ", expected " +
              std::to_string(kApplicationId) + ")");
  }
  run_quick_check(db);
  const std::int64_t version = db.pragma_int("user_version");
  if (version != kFormatVersion) {
    raise(TableErrorKind::kWrongVersion, path,
          "table format version " + std::to_string(version) + ", this build reads version " +
              std::to_string(kFormatVersion));
  }
  require_tables(db);
  TableContents contents;
  const std::optional<Machine> machine = detail::read_machine_row(db);
  if (!machine) raise(TableErrorKind::kCorrupt, path, "the `machine` row is missing");
  contents.machine = *machine;
  contents.materials = detail::read_material_rows(db);
  contents.runs = read_runs(db);
  if (contents.runs.empty()) raise(TableErrorKind::kEmpty, path, "no runs (the table has no launch data)");
  for (const Run& run : contents.runs) {
    bool known = false;
    for (const Material& m : contents.materials) known = known || m.name == run.material;
    if (!known) raise(TableErrorKind::kCorrupt, path, "run material \"" + run.material + "\" is not in `materials`");
  }
  return contents;
}

}  // namespace spread::tables
