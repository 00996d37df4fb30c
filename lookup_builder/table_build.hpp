#pragma once
// The sweep of lookup_builder: materials × rpm of a scene into one table file, one run per
// transaction. Finished runs are skipped on a rerun unless `rebuild` is set, so an interrupted build
// resumes where it stopped.
#include <ostream>
#include <string>

#include "libspread/scene/scene.hpp"

namespace spread::lookup {

struct BuildOptions {
  std::string output_path;          // empty = scene.sweep.output
  bool rebuild = false;             // redo runs that already exist
  std::ostream* progress = nullptr; // one line per run (stderr in the executable); nullptr = silent
};

struct BuildSummary {
  std::string output_path;
  int runs_written = 0;
  int runs_skipped = 0;
};

// Throws SourceUnavailableError (source not available), tables::TableError (output file not ours,
// wrong version, I/O), std::invalid_argument (the launch model cannot run this scene).
BuildSummary build_tables(const scene::Scene& scene, const BuildOptions& options);

}  // namespace spread::lookup
