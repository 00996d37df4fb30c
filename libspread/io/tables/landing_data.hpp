#pragma once
// Landing data: what a reader derives from one material's rows at length (the predictor's landing grid and
// quantile cells, libspread/analysis/predict/landing_data_codec.hpp), stored beside the rows by the writer
// so that opening a table reads it instead of flying it (docs/table-format.md, "landing_data").
//
// The table layer does not interpret it. The deriving code names what it was derived from (source_key: a
// digest of the rows' values) and how (model: its own version and numerical settings); a reader uses a
// row only when both equal what it would derive now, and otherwise derives afresh. The row has a
// checksum of its own; a damaged row is TableError kCorrupt, naming it.
#include <cstdint>
#include <string>
#include <vector>

namespace spread::tables {

struct LandingData {
  std::string material;
  std::string model;               // how the bytes were derived (the deriving code's tag)
  std::string source_key;          // what they were derived from (the deriving code's digest of the rows)
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

// Every row, its checksum verified; empty when the file has no landing_data table.
std::vector<LandingData> read_landing_data(Connection& db);

// Inserts or replaces the material's row (creates the table if needed).
void write_landing_data(Connection& db, const LandingData& landing);

}  // namespace detail
}  // namespace spread::tables
