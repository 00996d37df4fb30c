#pragma once
// Writes a launch-table file (docs/design.md §4, docs/table-format.md). One run per transaction, so an
// interrupted build loses at most the run in progress. Never touches a file that is not ours: an
// existing file that is not SQLite, or whose application_id differs, is refused (TableError kNotOurs)
// and left byte-identical; a file of another format version is refused (kWrongVersion), a damaged or
// truncated one (PRAGMA quick_check fails) too (kCorrupt), both also left byte-identical.
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/io/tables/landing_data.hpp"
#include "libspread/io/tables/table_format.hpp"
#include "libspread/io/tables/writer_lock.hpp"  // TableBusyError: another process holds the writer lock

namespace spread::tables {

// write_run() of a (material, rpm) that is already stored, without the replace flag.
class RunExistsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class TableWriter {
 public:
  // Creates the file with the current schema, or opens an existing table file of ours for writing.
  // Takes the file's writer lock first (TableBusyError when another process holds it). A rollback
  // journal left by a writer that stopped mid-transaction is rolled back (recovered_interrupted_write());
  // a WAL-mode file is switched back to a rollback journal, so readers never need -wal/-shm files.
  explicit TableWriter(const std::string& path);
  ~TableWriter();
  TableWriter(TableWriter&&) noexcept;
  TableWriter& operator=(TableWriter&&) noexcept;

  const std::string& path() const;
  bool recovered_interrupted_write() const;

  // What the file holds already (for a builder that must not mix rows of different scenes).
  std::optional<Machine> stored_machine();
  std::vector<Material> stored_materials();
  struct StoredRun {
    std::string material;
    double rpm = 0.0;
    std::string source;
    std::string inputs_hash;
  };
  std::vector<StoredRun> stored_runs();

  // The single machine row (replaced when written again). std::invalid_argument naming the field when
  // machine_problem() finds a value the reader would refuse (NaN/Inf, radius <= 0, ...).
  void write_machine(const Machine& machine);
  // Inserts or updates each material by name; std::invalid_argument (nothing written) when
  // material_problem() objects to any of them.
  void write_materials(const std::vector<Material>& materials);
  // Replaces the blend's `blend_components` rows; std::invalid_argument (nothing written) when
  // stored_blend_problem() objects or a component's material row has not been written.
  void write_blend(const Blend& blend);
  void write_meta(const std::string& key, const std::string& value);
  std::optional<std::string> stored_meta(const std::string& key);
  void erase_meta(const std::string& key);

  // Replaces the whole content of this file with that of the table file at `source` (SQLite's online
  // backup: page by page, one transaction), which must be a table of ours of this format version that
  // passes quick_check (TableError otherwise, this file unchanged). For a builder that writes into a
  // copy of a table and puts the copy in its place only when done.
  void copy_from(const std::string& source);
  // Every row of every table removed (the schema stays): a table built from scratch in this file.
  void clear();

  bool has_run(const std::string& material, double rpm);
  // Throws RunExistsError if the run exists and replace is false; std::invalid_argument for a run
  // without samples, with a value run_values_problem() objects to (a NaN/Inf sample field, diameter or
  // mass <= 0, rpm <= 0, ...; the message names the sample and field), or whose material has not been
  // written.
  void write_run(const Run& run, bool replace = false);

  // Lists the runs the file holds now, with the list's checksum (runs_manifest.hpp): write_run keeps the
  // list so; this lists the runs of a table written before the list was checked. True when the stored
  // list changed.
  bool list_runs();

  // Inserts or replaces the material's landing data (landing_data.hpp). One transaction.
  void write_landing_data(const LandingData& landing);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Current UTC time as ISO 8601, e.g. "2024-05-01T12:34:56Z" (for Run::created_utc).
std::string utc_now_iso8601();

}  // namespace spread::tables
