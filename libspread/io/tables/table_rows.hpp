#pragma once
// Reading the machine and material rows of a table file, shared by the reader and the writer (internal
// header): every value is checked for plausibility (table_format.hpp) and then against the row's
// checksum (row_checksum.hpp); a failure is TableError kCorrupt naming the row and field.
#include <optional>
#include <string>
#include <vector>

#include "libspread/io/tables/sqlite_connection.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::tables::detail {

[[noreturn]] void raise(TableErrorKind kind, const std::string& path, const std::string& problem);
// A REAL column; NULL (also what SQLite stores for a bound NaN) is a missing value, not 0.
double required_double(const Statement& query, int column, Connection& db, const std::string& field);
void verify_checksum(Connection& db, const std::string& row, const std::string& stored, const std::string& computed);

std::optional<Machine> read_machine_row(Connection& db);   // nullopt: no machine row yet
std::vector<Material> read_material_rows(Connection& db);  // sorted by name

}  // namespace spread::tables::detail
