#include "libspread/io/tables/table_rows.hpp"

#include "libspread/io/tables/machine_schema.hpp"
#include "libspread/io/tables/material_schema.hpp"
#include "libspread/io/tables/row_checksum.hpp"

namespace spread::tables::detail {

[[noreturn]] void raise(TableErrorKind kind, const std::string& path, const std::string& problem) {
  throw TableError(kind, path + ": " + problem);
}

// A REAL column of a record. The schema says NOT NULL, but a hand-edited file may not: a NULL (which is
// also what SQLite stores for a bound NaN) is a missing value, not 0.
double required_double(const Statement& query, int column, Connection& db, const std::string& field) {
  if (query.column_is_null(column)) raise(TableErrorKind::kCorrupt, db.path(), field + " is missing (NULL)");
  return query.column_double(column);
}

// After the values passed their plausibility check (which names the field), the row's checksum says
// whether they are the values that were written (row_checksum.hpp).
void verify_checksum(Connection& db, const std::string& row, const std::string& stored, const std::string& computed) {
  if (stored != computed) {
    raise(TableErrorKind::kCorrupt, db.path(),
          row + ": checksum mismatch (stored " + (stored.empty() ? std::string("nothing") : stored) + ", content gives " +
              computed + "): the row was changed or damaged after it was written; rebuild the table with lookup_builder");
  }
}

std::optional<Machine> read_machine_row(Connection& db) {
  std::string columns;
  for (const MachineColumn& c : kMachineColumns) columns += std::string(columns.empty() ? "" : ", ") + std::string(c.name);
  Statement query(db, "SELECT " + columns + ", checksum FROM machine WHERE id = 1");
  if (!query.step()) return std::nullopt;
  Machine m;
  int column = 0;
  for (const MachineColumn& c : kMachineColumns) {
    switch (c.kind) {
      case MachineColumn::Kind::kText: m.*c.text = query.column_text(column); break;
      case MachineColumn::Kind::kReal: m.*c.real = required_double(query, column, db, "machine." + std::string(c.name)); break;
      case MachineColumn::Kind::kInteger: m.*c.integer = static_cast<int>(query.column_int(column)); break;
    }
    ++column;
  }
  const std::string problem = machine_problem(m);
  if (!problem.empty()) raise(TableErrorKind::kCorrupt, db.path(), "the `machine` row has an impossible value: " + problem);
  verify_checksum(db, "the `machine` row", query.column_text(8), machine_checksum(m));
  return m;
}

std::vector<Material> read_material_rows(Connection& db) {
  std::string columns = "name";
  for (const MaterialQuantity& q : kMaterialQuantities) columns += ", " + std::string(q.name);
  Statement query(db, "SELECT " + columns + ", checksum FROM materials ORDER BY name");
  std::vector<Material> materials;
  while (query.step()) {
    Material m;
    m.name = query.column_text(0);
    const std::string at = "materials." + m.name + ".";
    int column = 1;
    for (const MaterialQuantity& q : kMaterialQuantities) {
      m.*q.member = required_double(query, column++, db, at + std::string(q.name));
    }
    const std::string problem = material_problem(m);
    if (!problem.empty()) raise(TableErrorKind::kCorrupt, db.path(), "impossible material value: " + problem);
    verify_checksum(db, "material \"" + m.name + "\"", query.column_text(column), material_checksum(m));
    materials.push_back(std::move(m));
  }
  return materials;
}

}  // namespace spread::tables::detail
