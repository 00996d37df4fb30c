#pragma once
// The sweep of lookup_builder: materials × rpm of a scene into one table file, one run per
// transaction. Finished runs are skipped on a rerun unless `rebuild` is set, so an interrupted build
// resumes where it stopped. Runs are independent: they are computed sequentially, on threads
// (`jobs`), or on MPI ranks (mpi_sweep.hpp); only the writer (this process / rank 0) touches the file,
// and a run's content never depends on where or in which order it was computed.
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_format.hpp"
#include "lookup_builder/run_cost.hpp"

namespace spread::lookup {

// The output file holds rows this scene would have written differently (another machine, a changed
// material, runs from other inputs or another source): refused, the file untouched, unless --rebuild.
class BuildConflictError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct BuildOptions {
  std::string output_path;          // empty = scene.sweep.output
  // Redo runs that already exist. When the file was built from another scene, build a new table beside
  // it and replace the file only once every run is written.
  bool rebuild = false;
  std::ostream* progress = nullptr; // stderr in the executable; nullptr = silent
  bool terminal = false;            // progress is a terminal: one updating line instead of a log
  int jobs = 1;                     // runs computed at once (threads); >= 1
  int threads_per_run = 0;          // DEM threads of one run; 0 = numerics.threads (jobs 1) or 1 (jobs > 1)
};

struct BuildSummary {
  std::string output_path;
  int runs_written = 0;
  int runs_skipped = 0;
};

// One (material, rpm) of the sweep; `index` is its place in the full, deterministic list.
struct SweepJob {
  const scene::Material* material = nullptr;
  double rpm = 0.0;
  int index = 0;
  std::string label() const;  // "Urea @ 550 rpm"
};
// Materials in sweep order, rpm rows within each: the same list in every process of an MPI build.
std::vector<SweepJob> sweep_jobs(const scene::Scene& scene);

// The writing side of a sweep: checks the table (refusing one that is not ours before anything is
// computed) and locks it; writes into a staging copy beside it (FILE.building, resumed after a killed
// build); records machine and materials; knows which runs are pending; writes each finished run in its
// own transaction and reports progress; finish() renames the staging file over the table (or, with
// nothing to do, removes it and leaves the table byte-identical).
class SweepWriter {
 public:
  SweepWriter(const scene::Scene& scene, const BuildOptions& options);
  ~SweepWriter();
  const std::vector<SweepJob>& pending() const { return pending_; }
  void started(const SweepJob& job);
  void finished(const SweepJob& job, const std::vector<tables::Run>& runs, const RunCost& cost);
  void failed(const SweepJob& job, const std::string& message);
  BuildSummary finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<SweepJob> pending_;
};

// Throws SourceUnavailableError (source not available), BuildConflictError (the file holds another
// scene's rows), tables::TableBusyError (another writer holds the file), tables::TableError (output
// file not ours, wrong version, I/O), std::invalid_argument (the launch model cannot run this scene), and
// std::runtime_error when a run failed (runs finished before it are kept).
BuildSummary build_tables(const scene::Scene& scene, const BuildOptions& options);

}  // namespace spread::lookup
