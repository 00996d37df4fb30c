#pragma once
// Reads a whole launch-table file into memory. Opens read-only (SQLITE_OPEN_READONLY), checks
// application_id, user_version and PRAGMA quick_check, and validates every record; every failure is a
// TableError whose kind() names the class of problem (missing, not ours, corrupt, wrong version, empty).
#include <string>
#include <vector>

#include "libspread/io/tables/landing_data.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::tables {

struct TableContents {
  Machine machine;
  std::vector<Material> materials;   // sorted by name
  std::vector<Run> runs;             // sorted by (material, rpm)
  // Landing data stored with the rows (landing_data.hpp), by material: the reader of it judges whether it
  // is current for them.
  std::vector<LandingData> landing_data;
};

TableContents read_table_file(const std::string& path);

}  // namespace spread::tables
