// lookup_builder SCENE [--output FILE] [--set key=value]... [--rebuild] [--jobs N] [--threads N]
// Builds the launch-table file of a scene's machine: every material × rpm of [sweep].
// Under `mpirun -np N` (a build with MPI) the runs are spread over the ranks; rank 0 writes the file.
// Exit codes: 0 done; 1 a run failed (the runs finished before it are kept); 2 refused before anything
// was computed (bad scene or overrides, output file not ours or built from another scene); 3 another
// process is writing the output file.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "libspread/io/tables/table_format.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "lookup_builder/run_source.hpp"
#include "lookup_builder/table_build.hpp"

#if defined(SPREAD_HAVE_MPI)
#include <mpi.h>

#include "lookup_builder/mpi_sweep.hpp"
#endif

namespace {

// Started by mpirun/srun? Only then is MPI initialised: a plain `lookup_builder ...` never starts MPI's
// runtime (Open MPI's singleton start is slow and refuses root without the environment variables).
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lookup_builder: build launch tables (SQLite) for a machine from a scene (libspread " SPREAD_VERSION_STRING
               ")"};
  app.set_version_flag("--version", SPREAD_VERSION_STRING);
  std::string scene_path;
  std::string output;
  std::vector<std::string> overrides;
  bool rebuild = false;
  int jobs = 1;
  int threads = 0;
  app.add_option("scene", scene_path, "scene file (TOML), see docs/scene-format.md")->required();
  app.add_option("--output,-o", output, "table file to create or extend (default: sweep.output of the scene)");
  app.add_option("--set", overrides, "override a scene value: dotted.key=value (repeatable)");
  app.add_flag("--rebuild", rebuild,
               "redo runs that already exist; a file built from another scene is replaced once the new table is "
               "complete");
  app.add_option("--jobs,-j", jobs, "runs computed at once on threads (without MPI); default 1")
      ->check(CLI::Range(1, 1024));
  app.add_option("--threads", threads,
                 "DEM threads per run (default: numerics.threads with --jobs 1, else 1; 1 under MPI)")
      ->check(CLI::Range(0, 1024));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }

  int rank = 0;
  int ranks = 1;
#if defined(SPREAD_HAVE_MPI)
  const bool use_mpi = launched_by_mpi();
  if (use_mpi) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  }
  struct Finalize {
    bool on;
    ~Finalize() {
      if (on) MPI_Finalize();
    }
  } finalize{use_mpi};
#endif

  try {
    const spread::scene::Scene scene = spread::scene::load_scene_file(scene_path, overrides);
    spread::lookup::BuildOptions options;
    options.output_path = output;
    options.rebuild = rebuild;
    options.progress = rank == 0 ? &std::cerr : nullptr;
    options.terminal = ::isatty(::fileno(stderr)) != 0;
    options.jobs = jobs;
    options.threads_per_run = threads;
    spread::lookup::BuildSummary summary;
#if defined(SPREAD_HAVE_MPI)
    if (ranks > 1) {
      summary = spread::lookup::build_tables_mpi(scene, options);
    } else {
      summary = spread::lookup::build_tables(scene, options);
    }
#else
    summary = spread::lookup::build_tables(scene, options);
#endif
    if (rank == 0) {
      std::cerr << "lookup_builder: " << summary.output_path << ": " << summary.runs_written << " runs written, "
                << summary.runs_skipped << " skipped";
      if (ranks > 1) std::cerr << " (" << ranks << " MPI ranks)";
      std::cerr << "\n";
    }
    return 0;
  } catch (const spread::scene::SceneError& e) {
    std::cerr << "lookup_builder: error: " << e.what() << "\n";
    return 2;
  } catch (const spread::lookup::SourceUnavailableError& e) {
    std::cerr << "lookup_builder: error: " << e.what() << "\n";
    return 2;
  } catch (const spread::lookup::BuildConflictError& e) {
    std::cerr << "lookup_builder: error: " << e.what() << "\n";
    return 2;
  } catch (const spread::tables::TableBusyError& e) {
    std::cerr << "lookup_builder: error: " << e.what() << "\n";
    return 3;
  } catch (const spread::tables::TableError& e) {
    std::cerr << "lookup_builder: error: " << e.what() << "\n";
    return e.kind() == spread::tables::TableErrorKind::kIo ? 1 : 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "lookup_builder: error: " << scene_path << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "lookup_builder: error: " << e.what() << "\n";
    return 1;
  }
}
