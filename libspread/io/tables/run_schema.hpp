#pragma once
// One row per column of the `runs` table, in the table's column order, which is also the order of the row
// checksum's values and of lookup_builder's MPI message (docs/table-format.md). The name is the column, the
// `Run` member and the docs' row. The writer's INSERT, the reader's SELECT, the checksum and the MPI codec
// all walk these rows, so a column is added here once; tests/tables/test_run_schema.cpp checks the CREATE
// statement and the docs' tables against them, and the static_assert below fails the build when `Run`
// gains a member without a row.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "libspread/io/tables/table_format.hpp"

namespace spread::tables {

struct RunColumn {
  enum class Kind {
    kText,         // a Run string member (TEXT)
    kReal,         // a Run double member (REAL)
    kInteger,      // a Run int64 member (INTEGER)
    kSampleCount,  // the four columns of the launch samples (Run::samples): their count (INTEGER),
    kRecordLayout, // the record layout string (TEXT, kSampleLayout),
    kRecordBytes,  // the bytes per record (INTEGER, kSampleBytes)
    kSamples,      // and the records themselves (BLOB, sample_codec.hpp); the MPI message carries only these
  };
  std::string_view name;
  Kind kind;
  std::string Run::* text = nullptr;
  double Run::* real = nullptr;
  std::int64_t Run::* integer = nullptr;
  // kText: what an empty value is stored (and checksummed) as — "{}" for an empty JSON object; "" keeps it.
  std::string_view stored_empty = {};
  std::string_view sql_type() const {
    switch (kind) {
      case Kind::kText:
      case Kind::kRecordLayout: return "TEXT";
      case Kind::kReal: return "REAL";
      case Kind::kInteger:
      case Kind::kSampleCount:
      case Kind::kRecordBytes: return "INTEGER";
      case Kind::kSamples: return "BLOB";
    }
    return "";
  }
  // A text column's value as stored.
  std::string_view stored_text(const Run& run) const {
    const std::string& value = run.*text;
    return value.empty() && !stored_empty.empty() ? stored_empty : std::string_view(value);
  }
};

inline constexpr std::array<RunColumn, 18> kRunColumns{{
    {"material", RunColumn::Kind::kText, &Run::material},
    {"rpm", RunColumn::Kind::kReal, nullptr, &Run::rpm},
    {"source", RunColumn::Kind::kText, &Run::source},
    {"sample_count", RunColumn::Kind::kSampleCount},
    {"record_layout", RunColumn::Kind::kRecordLayout},
    {"record_bytes", RunColumn::Kind::kRecordBytes},
    {"samples", RunColumn::Kind::kSamples},
    {"scene_hash", RunColumn::Kind::kText, &Run::scene_hash},
    {"inputs_hash", RunColumn::Kind::kText, &Run::inputs_hash},
    {"scene_text", RunColumn::Kind::kText, &Run::scene_text},
    {"effects", RunColumn::Kind::kText, &Run::effects},
    {"dt_contact_s", RunColumn::Kind::kReal, nullptr, &Run::dt_contact_s},
    {"dt_flight_s", RunColumn::Kind::kReal, nullptr, &Run::dt_flight_s},
    {"particle_count", RunColumn::Kind::kInteger, nullptr, nullptr, &Run::particle_count},
    {"software_version", RunColumn::Kind::kText, &Run::software_version},
    {"created_utc", RunColumn::Kind::kText, &Run::created_utc},
    {"stats_json", RunColumn::Kind::kText, &Run::stats_json, nullptr, nullptr, "{}"},
    {"convergence_json", RunColumn::Kind::kText, &Run::convergence_json, nullptr, nullptr, "[]"},
}};

namespace run_schema_detail {
// Run's size from the rows: its members are all 8-byte aligned (strings, doubles, int64, the samples'
// vector), so there is no padding to account for.
constexpr std::size_t run_bytes_from_columns() {
  std::size_t bytes = sizeof(std::vector<LaunchSample>);
  for (const RunColumn& c : kRunColumns) {
    if (c.kind == RunColumn::Kind::kText) bytes += sizeof(std::string);
    if (c.kind == RunColumn::Kind::kReal) bytes += sizeof(double);
    if (c.kind == RunColumn::Kind::kInteger) bytes += sizeof(std::int64_t);
  }
  return bytes;
}
// Each row names the member its kind needs, and no member twice.
constexpr bool columns_are_well_formed() {
  for (std::size_t a = 0; a < kRunColumns.size(); ++a) {
    const RunColumn& c = kRunColumns[a];
    if ((c.kind == RunColumn::Kind::kText) != (c.text != nullptr)) return false;
    if ((c.kind == RunColumn::Kind::kReal) != (c.real != nullptr)) return false;
    if ((c.kind == RunColumn::Kind::kInteger) != (c.integer != nullptr)) return false;
    for (std::size_t b = 0; b < a; ++b) {
      const RunColumn& d = kRunColumns[b];
      if ((c.text != nullptr && c.text == d.text) || (c.real != nullptr && c.real == d.real) ||
          (c.integer != nullptr && c.integer == d.integer) || c.name == d.name) {
        return false;
      }
    }
  }
  return true;
}
}  // namespace run_schema_detail
static_assert(run_schema_detail::columns_are_well_formed(),
              "kRunColumns: a row without the member its kind needs, or a member or name listed twice");
static_assert(sizeof(Run) == run_schema_detail::run_bytes_from_columns(),
              "tables::Run has a member that kRunColumns does not list (or lists one it lacks): add its row, "
              "its column to kSchemaSql, and its line to docs/table-format.md");

}  // namespace spread::tables
