#include "libspread/io/tables/landing_data.hpp"

#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/sqlite_connection.hpp"
#include "libspread/io/tables/table_rows.hpp"

namespace spread::tables::detail {

namespace {

bool has_landing_table(Connection& db) {
  Statement query(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
  query.bind(1, std::string(kLandingDataTable));
  return query.step();
}

}  // namespace

std::vector<LandingData> read_landing_data(Connection& db) {
  std::vector<LandingData> out;
  if (!has_landing_table(db)) return out;
  Statement query(db, "SELECT material, model, source_key, data, checksum FROM landing_data ORDER BY material");
  while (query.step()) {
    LandingData landing;
    landing.material = query.column_text(0);
    landing.model = query.column_text(1);
    landing.source_key = query.column_text(2);
    landing.data = query.column_blob(3);
    verify_checksum(db, "landing data " + landing.material, query.column_text(4), landing_data_checksum(landing));
    out.push_back(std::move(landing));
  }
  return out;
}

void write_landing_data(Connection& db, const LandingData& landing) {
  db.exec(kLandingDataSql);
  Statement upsert(db,
                   "INSERT OR REPLACE INTO landing_data (material, model, source_key, data, checksum) "
                   "VALUES (?, ?, ?, ?, ?)");
  upsert.bind(1, landing.material);
  upsert.bind(2, landing.model);
  upsert.bind(3, landing.source_key);
  upsert.bind_blob(4, landing.data);
  upsert.bind(5, landing_data_checksum(landing));
  upsert.step();
}

}  // namespace spread::tables::detail
