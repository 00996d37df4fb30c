#pragma once
// Where the launch samples of one (material, rpm) run come from. The sweep loop asks a RunSource for
// each run it has to make, the DEM source (dem_run.hpp) is one branch of make_run_source().
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::lookup {

// Makes the complete runs (samples and provenance) of one material at one rpm: its one run, or a blend's
// run per component (named tables::blend_component_name, each with the blend's inputs hash).
using RunSource = std::function<std::vector<tables::Run>(const scene::Material& material, double rpm)>;

// The source named by scene.sweep.source. Throws SourceUnavailableError for a source this build
// cannot run, before anything is written. threads_per_run: DEM and flight threads of one DEM run
// (0 = the scene's numerics.threads); the analytic source ignores it. The scene must outlive the source.
RunSource make_run_source(const scene::Scene& scene, int threads_per_run = 0);

class SourceUnavailableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A blend's analytic runs: each component's own analytic run (the analytic model has no granule
// interaction, so the components do not meet), renamed as its row and carrying the blend's inputs hash.
std::vector<tables::Run> analytic_blend_runs(const scene::Scene& scene, const scene::Material& blend, double rpm);

// Run made by the analytic (Patterson & Reece) launch model; provenance filled in from the scene.
tables::Run analytic_run(const scene::Scene& scene, const scene::Material& material, double rpm);

}  // namespace spread::lookup
