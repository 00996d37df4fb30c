#include "libspread/io/tables/landing_data.hpp"

#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/sqlite_connection.hpp"
#include "libspread/io/tables/table_rows.hpp"

namespace spread::tables::detail {

namespace {

std::string row_checksum(const std::string& material, const std::string& model, const std::string& source_key,
                         std::span<const std::uint8_t> data) {
  Crc64 crc;
  crc.text(material);
  crc.text(model);
  crc.text(source_key);
  crc.blob(data);
  return crc.hex();
}

bool has_landing_table(Connection& db) {
  Statement query(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
  query.bind(1, std::string(kLandingDataTable));
  return query.step();
}

}  // namespace

std::string landing_source_key(Connection& db, const std::string& material) {
  Crc64 crc;
  {
    Statement machine(db, "SELECT checksum FROM machine WHERE id = 1");
    crc.text(machine.step() ? machine.column_text(0) : std::string());
  }
  {
    Statement row(db, "SELECT checksum FROM materials WHERE name = ?");
    row.bind(1, material);
    crc.text(row.step() ? row.column_text(0) : std::string());
  }
  Statement runs(db, "SELECT rpm, checksum FROM runs WHERE material = ? ORDER BY rpm");
  runs.bind(1, material);
  while (runs.step()) {
    crc.real(runs.column_double(0));
    crc.text(runs.column_text(1));
  }
  return crc.hex();
}

std::vector<LandingData> read_landing_data(Connection& db) {
  std::vector<LandingData> out;
  if (!has_landing_table(db)) return out;
  Statement query(db, "SELECT material, model, source_key, data, checksum FROM landing_data ORDER BY material");
  while (query.step()) {
    LandingData landing;
    landing.material = query.column_text(0);
    landing.model = query.column_text(1);
    const std::string source_key = query.column_text(2);
    landing.data = query.column_blob(3);
    verify_checksum(db, "landing data " + landing.material, query.column_text(4),
                    row_checksum(landing.material, landing.model, source_key, landing.data));
    if (source_key != landing_source_key(db, landing.material)) continue;  // stale: derived from other rows
    out.push_back(std::move(landing));
  }
  return out;
}

void write_landing_data(Connection& db, const LandingData& landing) {
  db.exec(kLandingDataSql);
  const std::string source_key = landing_source_key(db, landing.material);
  Statement upsert(db,
                   "INSERT OR REPLACE INTO landing_data (material, model, source_key, data, checksum) "
                   "VALUES (?, ?, ?, ?, ?)");
  upsert.bind(1, landing.material);
  upsert.bind(2, landing.model);
  upsert.bind(3, source_key);
  upsert.bind_blob(4, landing.data);
  upsert.bind(5, row_checksum(landing.material, landing.model, source_key, landing.data));
  upsert.step();
}

}  // namespace spread::tables::detail
