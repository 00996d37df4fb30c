#pragma once
// The DEM launch source of lookup_builder: one (material, rpm) run simulated on the machine's disc
// (libspread/physics/dem) in batches until the predicted pattern's R̄ and ξ (seed Eqs. 51–52) settle — the
// convergence study of seed Fig. 8 made into a stopping rule — or a particle/time budget is reached.
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::lookup {

// One convergence check, after a batch: the statistics of every launch so far, flown to the ground.
struct ConvergencePoint {
  double simulated_s = 0.0;        // DEM time at the end of the batch
  std::int64_t launched = 0;       // granules that crossed the collector so far
  double mean_radius_m = 0.0;      // R̄ of the landings about the disc centre, Eq. 51
  double radial_width_m = 0.0;     // ξ, Eq. 52
  double change_mean_radius = 0.0; // |ΔR̄|/R̄ against the previous batch (1 when there is none)
  double change_radial_width = 0.0;
  // 95 % half-width of the working width from the launches so far (row_uncertainty.hpp), checked once
  // R̄ and ξ have converged when sweep.working_width_ci_m is set; NaN otherwise or without a width.
  double working_width_ci_m = std::numeric_limits<double>::quiet_NaN();
};

struct DemRunOptions {
  int threads = 0;  // DEM and flight threads of this run; 0 = the scene's numerics.threads
};

// Why the run stopped (stored in stats_json as "stop").
enum class DemStop { kConverged, kParticleBudget, kTimeBudget };
const char* to_string(DemStop stop);

// Runs the DEM for `material` at `rpm` with everything else from the scene. Launch samples are the
// launch states normalised as table_format.hpp says. The DEM frame already has the disc centre at the
// origin and the rim at z = 0 (dem/scene_config.cpp), which is the table's frame, so positions are
// stored as they are. Deterministic: same scene (seed) → bit-identical run, for any thread count.
// Throws std::invalid_argument (scene the DEM cannot run, naming the key) and std::runtime_error when
// no granule launched within the budget.
tables::Run dem_run(const scene::Scene& scene, const scene::Material& material, double rpm,
                    const DemRunOptions& options = {});

// A blend's DEM run at `rpm`: the mixed stream fed onto the disc (the components meet there), stopped by the
// same rules as dem_run on the stream's R̄ and ξ (the working-width rule is a single material's: not
// applied), then split by component: one run per component, named blend_component_name(), with that
// component's launches in launch order and the stream's provenance (its stats_json adds "blend",
// "blend_component" and "component_launched"). std::runtime_error when a component launched nothing.
std::vector<tables::Run> dem_blend_runs(const scene::Scene& scene, const scene::Material& blend, double rpm,
                                        const DemRunOptions& options = {});
// The split itself: sample i of `mixed` goes to component component_of_sample[i]'s run.
std::vector<tables::Run> split_blend_run(const tables::Run& mixed, std::span<const int> component_of_sample,
                                         const scene::Material& blend);

// convergence history as stored in Run::convergence_json (a JSON array of objects).
std::string convergence_to_json(const std::vector<ConvergencePoint>& history);

}  // namespace spread::lookup
