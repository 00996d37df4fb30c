#pragma once
// Writes a launch-table file (DESIGN.md §4, docs/table-format.md). One run per transaction, so an
// interrupted build loses at most the run in progress. Never touches a file that is not ours: an
// existing file that is not SQLite, or whose application_id differs, is refused (TableError kNotOurs)
// and left byte-identical; a file of another format version is refused (kWrongVersion).
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/tables/table_format.hpp"

namespace spread::tables {

// write_run() of a (material, rpm) that is already stored, without the replace flag.
class RunExistsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class TableWriter {
 public:
  // Creates the file with the current schema, or opens an existing table file of ours for writing.
  explicit TableWriter(const std::string& path);
  ~TableWriter();
  TableWriter(TableWriter&&) noexcept;
  TableWriter& operator=(TableWriter&&) noexcept;

  const std::string& path() const;

  // The single machine row (replaced when written again).
  void write_machine(const Machine& machine);
  // Inserts or updates each material by name.
  void write_materials(const std::vector<Material>& materials);
  void write_meta(const std::string& key, const std::string& value);

  bool has_run(const std::string& material, double rpm);
  // Throws RunExistsError if the run exists and replace is false; std::invalid_argument for a run
  // without samples, or whose material has not been written.
  void write_run(const Run& run, bool replace = false);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Current UTC time as ISO 8601, e.g. "2024-05-01T12:34:56Z" (for Run::created_utc).
std::string utc_now_iso8601();

}  // namespace spread::tables
