#pragma once
// The schema's text as the tests read it: a file's text, and one CREATE TABLE statement's columns.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "libspread/io/tables/table_schema.hpp"

namespace spread::tables {

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The column names (and, with types, "name TYPE") of one CREATE TABLE statement.
inline std::vector<std::string> create_columns(const std::string& table, bool with_types) {
  const std::string sql = detail::kSchemaSql;
  const std::size_t begin = sql.find("CREATE TABLE " + table + " (");
  EXPECT_NE(begin, std::string::npos) << table;
  std::istringstream body(sql.substr(begin, sql.find(");", begin) - begin));
  std::vector<std::string> out;
  std::string line;
  std::getline(body, line);  // "CREATE TABLE ..."
  while (std::getline(body, line)) {
    std::istringstream words(line);
    std::string name, type;
    words >> name >> type;
    if (name.empty() || name == "UNIQUE") continue;
    out.push_back(with_types ? name + " " + type : name);
  }
  return out;
}

// The first cells of the rows of the docs' column table under `heading` (up to the next heading), in order.
inline std::vector<std::string> doc_table_rows(const std::string& doc, const std::string& heading) {
  const std::size_t section = doc.find(heading);
  EXPECT_NE(section, std::string::npos) << heading;
  if (section == std::string::npos) return {};
  std::istringstream lines(doc.substr(section, doc.find("\n### ", section + 1) - section));
  std::vector<std::string> rows;
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("| `", 0) == 0) rows.push_back(line.substr(3, line.find('`', 3) - 3));
  }
  return rows;
}

}  // namespace spread::tables
