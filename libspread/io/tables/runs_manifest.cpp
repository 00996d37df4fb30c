#include "libspread/io/tables/runs_manifest.hpp"

#include <cstdio>
#include <map>
#include <sstream>

#include "libspread/io/tables/row_checksum.hpp"

namespace spread::tables::detail {

namespace {

// (material, rpm text) → checksum, from the manifest's lines.
std::map<std::pair<std::string, std::string>, std::string> entries(const std::string& manifest) {
  std::map<std::pair<std::string, std::string>, std::string> out;
  std::istringstream lines(manifest);
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t a = line.find('\t');
    const std::size_t b = a == std::string::npos ? a : line.find('\t', a + 1);
    if (b == std::string::npos) {
      out[{line, ""}] = "";  // a damaged line: never equal to a run's
      continue;
    }
    out[{line.substr(0, a), line.substr(a + 1, b - a - 1)}] = line.substr(b + 1);
  }
  return out;
}

std::string label(const std::pair<std::string, std::string>& run) { return "run " + run.first + " @ " + run.second + " rpm"; }

}  // namespace

std::string runs_manifest(Connection& db) {
  Statement query(db, "SELECT material, rpm, checksum FROM runs ORDER BY material, rpm");
  std::string out;
  while (query.step()) {
    char rpm[40];
    std::snprintf(rpm, sizeof rpm, "%.17g", query.column_double(1));
    out += query.column_text(0) + "\t" + rpm + "\t" + query.column_text(2) + "\n";
  }
  return out;
}

std::string manifest_checksum(const std::string& manifest) {
  Crc64 crc;
  crc.text(manifest);
  return crc.hex();
}

std::string manifest_problem(const std::string& stored, const std::string& actual) {
  if (stored == actual) return "";
  const auto listed = entries(stored);
  const auto found = entries(actual);
  for (const auto& [run, checksum] : listed) {
    const auto it = found.find(run);
    if (it == found.end()) return label(run) + " is in the table's list of runs but not in `runs` (deleted?)";
    if (it->second != checksum) return label(run) + " is not the run the table's list of runs names (replaced?)";
  }
  for (const auto& [run, checksum] : found) {
    if (listed.find(run) == listed.end()) return label(run) + " is in `runs` but not in the table's list of runs (added?)";
  }
  return "the table's list of runs is damaged";
}

}  // namespace spread::tables::detail
