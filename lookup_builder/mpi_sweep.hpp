#pragma once
// The sweep over MPI ranks (docs/design.md §8): `mpirun -np N lookup_builder SCENE ...`. Rank 0 is the
// only process that opens the table file; it hands out runs one at a time (so fast and slow runs
// balance), computes runs itself on a second thread, and writes every finished run — its own and the
// ones workers send back as serialised Run buffers (run_message.hpp) — in its own transaction.
// Compiled only when the build has MPI (SPREAD_HAVE_MPI).
#include "lookup_builder/table_build.hpp"

namespace spread::lookup {

// Call between MPI_Init_thread (at least MPI_THREAD_FUNNELED) and MPI_Finalize, on every rank, with
// the same scene. Rank 0 returns the summary and throws what build_tables() throws; a worker returns an
// empty summary (it reports its failures to rank 0, which throws).
BuildSummary build_tables_mpi(const scene::Scene& scene, const BuildOptions& options);

}  // namespace spread::lookup
