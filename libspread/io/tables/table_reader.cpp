#include "libspread/io/tables/table_reader.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "libspread/io/tables/blend_rows.hpp"
#include "libspread/io/tables/landing_data.hpp"
#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/run_schema.hpp"
#include "libspread/io/tables/runs_manifest.hpp"
#include "libspread/io/tables/sample_codec.hpp"
#include "libspread/io/tables/sqlite_connection.hpp"
#include "libspread/io/tables/table_file.hpp"
#include "libspread/io/tables/table_rows.hpp"
#include "libspread/io/tables/table_schema.hpp"

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

std::vector<std::string> columns_of(sqlite3* db, const char* table) {
  std::vector<std::string> out;
  sqlite3_stmt* query = nullptr;
  if (sqlite3_prepare_v2(db, (std::string("PRAGMA table_info(") + table + ")").c_str(), -1, &query, nullptr) != SQLITE_OK) {
    return out;
  }
  while (sqlite3_step(query) == SQLITE_ROW) out.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(query, 1)));
  sqlite3_finalize(query);
  return out;
}

// Every file has the first four; landing_data only once a writer stored some (landing_data.hpp);
// blend_components every file of version 3 on (a version-2 file has no blends).
constexpr const char* kTables[] = {"machine", "materials", "runs", "meta", detail::kLandingDataTable,
                                   detail::kBlendComponentsTable};
constexpr std::size_t kRequiredTables = 4;
constexpr std::size_t kBlendTableIndex = 5;

// The columns each table must have: those of the schema this build writes (table_schema.hpp), read once
// from an in-memory database made with it, so the check follows the schema without a list of its own.
const std::vector<std::vector<std::string>>& schema_columns() {
  static const std::vector<std::vector<std::string>> columns = [] {
    std::vector<std::vector<std::string>> out;
    sqlite3* db = nullptr;
    if (sqlite3_open_v2(":memory:", &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) == SQLITE_OK &&
        sqlite3_exec(db, detail::kSchemaSql, nullptr, nullptr, nullptr) == SQLITE_OK &&
        sqlite3_exec(db, detail::kLandingDataSql, nullptr, nullptr, nullptr) == SQLITE_OK) {
      for (const char* table : kTables) out.push_back(columns_of(db, table));
    }
    sqlite3_close(db);
    return out;
  }();
  return columns;
}

// Every table and every column of the schema present: a damaged schema (a dropped table or column) is a
// damaged file, named, not an I/O error of the first query that trips over it.
void require_tables(Connection& db, std::int64_t version) {
  const std::vector<std::vector<std::string>>& expected = schema_columns();
  for (std::size_t t = 0; t < std::size(kTables); ++t) {
    const char* table = kTables[t];
    Statement query(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
    query.bind(1, std::string(table));
    if (!query.step()) {
      if (t >= kRequiredTables && !(t == kBlendTableIndex && version >= 3)) continue;
      raise(TableErrorKind::kCorrupt, db.path(), std::string("table `") + table + "` is missing");
    }
    if (t >= expected.size()) continue;
    const std::vector<std::string> present = columns_of(db.handle(), table);
    for (const std::string& column : expected[t]) {
      if (std::find(present.begin(), present.end(), column) == present.end()) {
        raise(TableErrorKind::kCorrupt, db.path(), std::string("table `") + table + "` has no column `" + column + "`");
      }
    }
  }
}

// The runs' sample count as the file declares it, bounded by what its size can hold: the pool's one
// reservation, so a damaged count cannot ask for more memory than the file's bytes could fill.
std::size_t declared_sample_count(Connection& db, std::int64_t file_bytes) {
  // TOTAL, not SUM: a real number, which no damaged count can make overflow.
  Statement total(db, "SELECT TOTAL(sample_count) FROM runs WHERE sample_count > 0");
  if (!total.step()) return 0;
  const double declared = total.column_double(0);
  const double most = static_cast<double>(file_bytes / static_cast<std::int64_t>(kSampleBytes));
  return static_cast<std::size_t>(declared >= 0.0 ? std::min(declared, most) : 0.0);
}

// pool: nullptr, each run's samples in its own vector; otherwise appended to `pool`, with `offsets` the
// start of each run's and, at the end, the total.
std::vector<Run> read_runs(Connection& db, std::pmr::vector<LaunchSample>* pool, std::vector<std::size_t>* offsets) {
  // The columns of kRunColumns in their order, then the checksum.
  std::string columns;
  for (const RunColumn& column : kRunColumns) columns += std::string(column.name) + ", ";
  Statement query(db, "SELECT " + columns + "checksum FROM runs ORDER BY material, rpm");
  constexpr int kChecksumColumn = static_cast<int>(kRunColumns.size());
  static_assert(kRunColumns[0].name == "material" && kRunColumns[1].name == "rpm",
                "the rows' names in messages need the material and the rpm first");
  std::vector<Run> runs;
  while (query.step()) {
    Run run;
    // Named by material and rpm once those are read (they come first): "run Urea @ 600.000000 rpm: ".
    std::string which = "run ";
    std::int64_t sample_count = 0, record_bytes = 0;
    std::string layout;
    std::span<const std::uint8_t> blob;
    std::span<const LaunchSample> samples;
    for (int c = 0; c < kChecksumColumn; ++c) {
      const RunColumn& column = kRunColumns[static_cast<std::size_t>(c)];
      switch (column.kind) {
        case RunColumn::Kind::kText: run.*column.text = query.column_text(c); break;
        case RunColumn::Kind::kReal:
          run.*column.real = required_double(query, c, db, which + std::string(column.name));
          break;
        case RunColumn::Kind::kInteger: run.*column.integer = query.column_int(c); break;
        case RunColumn::Kind::kSampleCount: sample_count = query.column_int(c); break;
        case RunColumn::Kind::kRecordLayout: layout = query.column_text(c); break;
        case RunColumn::Kind::kRecordBytes: record_bytes = query.column_int(c); break;
        case RunColumn::Kind::kSamples: {
          blob = query.column_blob_view(c);
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
          if (pool != nullptr) {
            offsets->push_back(pool->size());
            pool->resize(pool->size() + static_cast<std::size_t>(sample_count));
            const std::span<LaunchSample> into = std::span(*pool).last(static_cast<std::size_t>(sample_count));
            decode_samples_into(blob, into);
            samples = into;
          } else {
            run.samples = decode_samples(blob);
            samples = run.samples;
          }
          break;
        }
      }
      if (column.text == &Run::material) which = "run " + run.material + ": ";
      if (column.real == &Run::rpm) which = "run " + run.material + " @ " + std::to_string(run.rpm) + " rpm: ";
    }
    std::string problem = run_record_problem(run);
    if (problem.empty()) problem = samples_problem(samples);
    if (!problem.empty()) raise(TableErrorKind::kCorrupt, db.path(), which + "impossible value: " + problem);
    verify_checksum(db, which.substr(0, which.size() - 2), query.column_text(kChecksumColumn),
                    run_checksum(run, sample_count, blob, layout, record_bytes));
    runs.push_back(std::move(run));
  }
  if (pool != nullptr) offsets->push_back(pool->size());
  return runs;
}

}  // namespace

TableContents read_table_file(const std::string& path, std::pmr::memory_resource* sample_memory,
                              const ReadOptions& options) {
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
  if (version < kOldestReadableVersion || version > kFormatVersion) {
    raise(TableErrorKind::kWrongVersion, path,
          "table format version " + std::to_string(version) + ", this build reads versions " +
              std::to_string(kOldestReadableVersion) + " to " + std::to_string(kFormatVersion));
  }
  require_tables(db, version);
  // The pool's memory given at construction: a vector's allocator does not follow an assignment.
  TableContents contents{.format_version = static_cast<std::int32_t>(version),
                         .machine = {},
                         .materials = {},
                         .runs = {},
                         .landing_data = {},
                         .blends = {},
                         .pooled_samples = std::pmr::vector<LaunchSample>(
                             sample_memory != nullptr ? sample_memory : std::pmr::get_default_resource()),
                         .pooled_offset = {},
                         .drop_point_turn_validated_rad = {},
                         .runs_listed = true};
  const std::optional<Machine> machine = detail::read_machine_row(db);
  if (!machine) raise(TableErrorKind::kCorrupt, path, "the `machine` row is missing");
  contents.machine = *machine;
  contents.materials = detail::read_material_rows(db);
  if (sample_memory != nullptr) {
    contents.pooled_samples.reserve(declared_sample_count(db, file.bytes));
    contents.runs = read_runs(db, &contents.pooled_samples, &contents.pooled_offset);
  } else {
    contents.runs = read_runs(db, nullptr, nullptr);
  }
  {
    // Runs deleted or added outside the writer: the list of runs, itself checked by its checksum, names
    // them. A table with runs and no checked list is a legacy table (written before the list was checked)
    // or one whose list went with its runs; only a caller who accepts legacy tables reads it.
    const auto meta = [&](const char* key) -> std::optional<std::string> {
      Statement query(db, "SELECT value FROM meta WHERE key = ?");
      query.bind(1, std::string(key));
      if (!query.step()) return std::nullopt;
      return query.column_text(0);
    };
    const std::optional<std::string> manifest = meta(detail::kRunsManifestKey);
    const std::optional<std::string> checksum = meta(detail::kRunsManifestChecksumKey);
    if (manifest && checksum && *checksum != detail::manifest_checksum(*manifest)) {
      raise(TableErrorKind::kCorrupt, path,
            "the table's list of runs (meta `runs_manifest`) does not match its checksum (edited outside the writer?)");
    }
    if (manifest) {
      const std::string problem = detail::manifest_problem(*manifest, detail::runs_manifest(db));
      if (!problem.empty()) raise(TableErrorKind::kCorrupt, path, problem);
    }
    if (!contents.runs.empty() && !(manifest && checksum)) {
      if (!options.legacy_files) {
        raise(TableErrorKind::kWrongVersion, path,
              std::string("runs without a checked list of them (meta `runs_manifest` ") +
                  (manifest ? "without its checksum" : "missing") +
                  "): a table written before libspread 0.6, or one whose runs were deleted with their list; rebuild "
                  "it with lookup_builder (which lists its runs), or open it as a legacy file to read its runs "
                  "unchecked (C API: SPREAD_OPEN_LEGACY_FILES)");
      }
      contents.runs_listed = false;
    }
  }
  {
    Statement validated(db, std::string("SELECT value FROM meta WHERE key = '") + kDropPointTurnValidatedKey + "'");
    if (validated.step()) {
      const std::string text = validated.column_text(0);
      const std::optional<std::array<double, 2>> range_deg = parse_drop_point_turn_validated(text);
      if (!range_deg) {
        raise(TableErrorKind::kCorrupt, path, std::string("meta `") + kDropPointTurnValidatedKey + "` is '" + text +
                                                  "': expected 'low,high' degrees with -180 <= low <= 0 <= high <= 180");
      }
      constexpr double kRadPerDeg = 0.017453292519943295;
      contents.drop_point_turn_validated_rad = std::array<double, 2>{(*range_deg)[0] * kRadPerDeg, (*range_deg)[1] * kRadPerDeg};
    }
  }
  contents.landing_data = detail::read_landing_data(db);
  contents.blends = detail::read_blend_rows(db, contents.materials);
  if (contents.runs.empty()) raise(TableErrorKind::kEmpty, path, "no runs (the table has no launch data)");
  for (const Run& run : contents.runs) {
    bool known = false;
    for (const Material& m : contents.materials) known = known || m.name == run.material;
    if (!known) raise(TableErrorKind::kCorrupt, path, "run material \"" + run.material + "\" is not in `materials`");
  }
  return contents;
}

std::string drop_point_turn_validated_text(const std::array<double, 2>& range_deg) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g,%.17g", range_deg[0], range_deg[1]);
  return text;
}

std::optional<std::array<double, 2>> parse_drop_point_turn_validated(const std::string& text) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos) return std::nullopt;
  std::array<double, 2> range{};
  const std::string parts[2] = {text.substr(0, comma), text.substr(comma + 1)};
  for (int i = 0; i < 2; ++i) {
    const char* begin = parts[i].c_str();
    char* end = nullptr;
    range[static_cast<std::size_t>(i)] = std::strtod(begin, &end);
    if (end == begin || *end != '\0') return std::nullopt;
  }
  if (!(range[0] >= -180.0 && range[0] <= 0.0 && range[1] >= 0.0 && range[1] <= 180.0)) return std::nullopt;
  return range;
}

}  // namespace spread::tables
