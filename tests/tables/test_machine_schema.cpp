// The `machine` table's one schema (libspread/io/tables/machine_schema.hpp): the CREATE statement, the docs'
// column table and the docs' checksum order list its rows in its order; the writer, reader, checksum and
// lookup_builder's comparison walk the rows themselves, so a value set in any field travels through all of
// them. (A `Machine` member without a row fails the build: the static_asserts in machine_schema.hpp.)
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "libspread/io/tables/machine_schema.hpp"
#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "schema_text.hpp"
#include "table_fixtures.hpp"
#include "tests/support/temp_path.hpp"

namespace spread::tables {
namespace {

std::vector<std::string> machine_columns(bool with_types) {
  std::vector<std::string> out;
  for (const MachineColumn& c : kMachineColumns) {
    out.push_back(with_types ? std::string(c.name) + " " + std::string(c.sql_type()) : std::string(c.name));
  }
  out.push_back(with_types ? "checksum TEXT" : "checksum");
  return out;
}

TEST(MachineSchema, TheCreateStatementIsTheSchemas) {
  std::vector<std::string> expected{"id INTEGER"};
  for (const std::string& column : machine_columns(true)) expected.push_back(column);
  EXPECT_EQ(create_columns("machine", true), expected);
}

TEST(MachineSchema, TheDocsListTheSchemasColumnsInItsOrder) {
  const std::string doc = read_text(std::string(SPREAD_SOURCE_DIR) + "/docs/table-format.md");
  EXPECT_EQ(doc_table_rows(doc, "### `machine`"), machine_columns(false));
  const std::size_t order = doc.find("\n| machine | ");
  ASSERT_NE(order, std::string::npos);
  const std::string listed = doc.substr(order + 13, doc.find('\n', order + 1) - order - 13);
  std::string expected;
  for (const MachineColumn& c : kMachineColumns) expected += (expected.empty() ? "`" : ", `") + std::string(c.name) + "`";
  EXPECT_EQ(listed, expected + " |");
}

// Every field set to a value of its own (within the plausible ranges) survives the file: writer, reader
// and checksum; and each field changed alone changes the checksum.
TEST(MachineSchema, EveryFieldTravelsThroughTheFileAndTheChecksum) {
  Machine machine = spread::testing::sample_machine();
  int k = 0;
  for (const MachineColumn& c : kMachineColumns) {
    ++k;
    if (c.kind == MachineColumn::Kind::kText) machine.*c.text = std::string(c.name) + "-" + std::to_string(k);
    if (c.kind == MachineColumn::Kind::kReal) machine.*c.real += 1e-3 * k;
  }
  machine.vane_count = 7;
  machine.rotation_sense = -1;
  machine.disc_count = 1;
  ASSERT_EQ(machine_problem(machine), "");
  spread::testing::TempPath file("machine_schema");
  {
    TableWriter writer(file.path());
    writer.write_machine(machine);
    writer.write_materials({spread::testing::sample_material("A", 0.4)});
    writer.write_run(spread::testing::sample_run("A", 600.0, 10));
  }
  const Machine back = read_table_file(file.path()).machine;
  const std::string checksum = machine_checksum(machine);
  for (const MachineColumn& c : kMachineColumns) {
    Machine changed = machine;
    switch (c.kind) {
      case MachineColumn::Kind::kText:
        EXPECT_EQ(back.*c.text, machine.*c.text) << c.name;
        changed.*c.text += "x";
        break;
      case MachineColumn::Kind::kReal:
        EXPECT_EQ(back.*c.real, machine.*c.real) << c.name;
        changed.*c.real += 1e-9;
        break;
      case MachineColumn::Kind::kInteger:
        EXPECT_EQ(back.*c.integer, machine.*c.integer) << c.name;
        changed.*c.integer += 1;
        break;
    }
    EXPECT_NE(machine_checksum(changed), checksum) << c.name << " is not in the checksum";
  }
}

}  // namespace
}  // namespace spread::tables
