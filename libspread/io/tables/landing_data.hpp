#pragma once
// Landing data: what a reader derives from one material's rows at length (the predictor's landing grid and
// quantile cells, libspread/analysis/predict/landing_data_codec.hpp), stored beside the rows by the writer
// so that opening a table reads it instead of flying it (docs/table-format.md, "landing_data").
//
// The table layer does not interpret the bytes. It keys each row by what the data was derived from — the
// machine row, the material row and the material's runs, through their row checksums (row_checksum.hpp) —
// and by a model tag naming how (the deriving code's own version and numerical settings). A row whose key
// no longer matches the rows it was derived from (a run rewritten, added or deleted since) is stale: the
// reader leaves it out and the predictor derives afresh. The row has a checksum of its own; a damaged row
// is TableError kCorrupt, naming it.
#include <cstdint>
#include <string>
#include <vector>


namespace spread::tables {

struct LandingData {
  std::string material;
  std::string model;               // how the bytes were derived (the deriving code's tag)
  std::vector<std::uint8_t> data;  // opaque here
};

namespace detail {

class Connection;  // sqlite_connection.hpp

inline constexpr const char* kLandingDataTable = "landing_data";
// Created by the writer the first time it stores landing data (tables written before it have none; the
// table is optional for readers).
inline constexpr const char* kLandingDataSql = R"sql(
CREATE TABLE IF NOT EXISTS landing_data (
  material TEXT NOT NULL UNIQUE,
  model TEXT NOT NULL,
  source_key TEXT NOT NULL,
  data BLOB NOT NULL,
  checksum TEXT NOT NULL
);
)sql";

// CRC-64/XZ (hex) of the machine row's checksum, the material row's checksum and each of the material's
// runs (rpm and row checksum, by rpm): what a landing_data row of that material was derived from.
std::string landing_source_key(Connection& db, const std::string& material);

// The current rows (key equal to landing_source_key of the rows as they are), their checksums verified;
// empty when the file has no landing_data table.
std::vector<LandingData> read_landing_data(Connection& db);

// Inserts or replaces the material's row, keyed by the rows as they are now (creates the table if needed).
void write_landing_data(Connection& db, const LandingData& landing);

}  // namespace detail
}  // namespace spread::tables
