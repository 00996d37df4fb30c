// The `runs` table's one schema (libspread/io/tables/run_schema.hpp): the CREATE statement, the docs' column
// table and the docs' checksum order list its rows in its order; the writer, reader, checksum and MPI message
// walk the rows themselves, so a value set in any field travels through all of them. (A `Run` member without
// a row fails the build: the static_assert in run_schema.hpp.)
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/run_schema.hpp"
#include "libspread/io/tables/sample_codec.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_schema.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "lookup_builder/run_message.hpp"
#include "schema_text.hpp"
#include "table_fixtures.hpp"
#include "tests/support/temp_path.hpp"

namespace spread::tables {
namespace {

std::vector<std::string> schema_columns(bool with_types) {
  std::vector<std::string> out;
  for (const RunColumn& c : kRunColumns) {
    out.push_back(with_types ? std::string(c.name) + " " + std::string(c.sql_type()) : std::string(c.name));
  }
  out.push_back(with_types ? "checksum TEXT" : "checksum");
  return out;
}

TEST(RunSchema, TheCreateStatementIsTheSchemas) {
  EXPECT_EQ(create_columns("runs", true), schema_columns(true));
}

TEST(RunSchema, TheDocsListTheSchemasColumnsInItsOrder) {
  const std::string doc = read_text(std::string(SPREAD_SOURCE_DIR) + "/docs/table-format.md");
  // The column table of `runs`: its rows' first cells, in order.
  EXPECT_EQ(doc_table_rows(doc, "### `runs`"), schema_columns(false));
  // The checksum's order.
  const std::size_t order = doc.find("\n| runs | ");
  ASSERT_NE(order, std::string::npos);
  const std::string listed = doc.substr(order + 10, doc.find('\n', order + 1) - order - 10);
  std::string expected;
  for (const RunColumn& c : kRunColumns) expected += (expected.empty() ? "`" : ", `") + std::string(c.name) + "`";
  EXPECT_EQ(listed, expected + " |");
}

// Every field set to a value of its own survives the file (writer, reader, checksum) and the MPI message.
TEST(RunSchema, EveryFieldTravelsThroughTheFileAndTheMessage) {
  tables::Run run = spread::testing::sample_run("A", 600.0, 10);
  int k = 0;
  for (const RunColumn& c : kRunColumns) {
    ++k;
    if (c.kind == RunColumn::Kind::kText && c.text != &Run::material) {
      run.*c.text = c.name == "stats_json" ? "{\"k\":" + std::to_string(k) + "}"
                                           : std::string(c.name) + "-" + std::to_string(k);
    }
    if (c.kind == RunColumn::Kind::kReal && c.real != &Run::rpm) run.*c.real = 1e-6 * k;
    if (c.kind == RunColumn::Kind::kInteger) run.*c.integer = 1000 + k;
  }
  const auto same = [](const tables::Run& a, const tables::Run& b, const char* where) {
    for (const RunColumn& c : kRunColumns) {
      if (c.kind == RunColumn::Kind::kText) {
        EXPECT_EQ(a.*c.text, b.*c.text) << where << " " << c.name;
      } else if (c.kind == RunColumn::Kind::kReal) {
        EXPECT_EQ(a.*c.real, b.*c.real) << where << " " << c.name;
      } else if (c.kind == RunColumn::Kind::kInteger) {
        EXPECT_EQ(a.*c.integer, b.*c.integer) << where << " " << c.name;
      }
    }
    ASSERT_EQ(a.samples.size(), b.samples.size()) << where;
    EXPECT_EQ(encode_samples(a.samples), encode_samples(b.samples)) << where;
  };
  same(lookup::deserialise_run(lookup::serialise_run(run)), run, "MPI message");

  spread::testing::TempPath file("run_schema");
  {
    TableWriter writer(file.path());
    writer.write_machine(spread::testing::sample_machine());
    writer.write_materials({spread::testing::sample_material("A", 0.4)});
    writer.write_run(run);
  }
  const TableContents back = read_table_file(file.path());
  ASSERT_EQ(back.runs.size(), 1u);
  same(back.runs[0], run, "file");
  // Each field is in the checksum: changing any one changes it.
  const std::vector<std::uint8_t> blob = encode_samples(run.samples);
  const auto checksum = [&](const tables::Run& r) {
    return run_checksum(r, static_cast<std::int64_t>(r.samples.size()), blob, kSampleLayout,
                        static_cast<std::int64_t>(kSampleBytes));
  };
  for (const RunColumn& c : kRunColumns) {
    tables::Run changed = run;
    if (c.kind == RunColumn::Kind::kText) (changed.*c.text) += "x";
    if (c.kind == RunColumn::Kind::kReal) changed.*c.real += 1.0;
    if (c.kind == RunColumn::Kind::kInteger) changed.*c.integer += 1;
    if (c.text != nullptr || c.real != nullptr || c.integer != nullptr) {
      EXPECT_NE(checksum(changed), checksum(run)) << c.name;
    }
  }
}

}  // namespace
}  // namespace spread::tables
