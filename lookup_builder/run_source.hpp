#pragma once
// Where the launch samples of one (material, rpm) run come from. The sweep loop asks a RunSource for
// each run it has to make, so adding the DEM source is adding a branch in make_run_source().
#include <functional>
#include <stdexcept>
#include <string>

#include "libspread/scene/scene.hpp"
#include "libspread/tables/table_format.hpp"

namespace spread::lookup {

// Makes the complete run (samples and provenance) for one material at one rpm.
using RunSource = std::function<tables::Run(const scene::Material& material, double rpm)>;

// The source named by scene.sweep.source. Throws SourceUnavailableError for a source this build
// cannot run yet (`dem`), before anything is written.
RunSource make_run_source(const scene::Scene& scene);

class SourceUnavailableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Run made by the analytic (Patterson & Reece) launch model; provenance filled in from the scene.
tables::Run analytic_run(const scene::Scene& scene, const scene::Material& material, double rpm);

}  // namespace spread::lookup
