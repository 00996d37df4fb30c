#pragma once
// Typical launches for the flight and particle-count studies: analytic launch samples of the scene's
// machine and material (libspread/physics/launch, the model the bundled tables are built with) turned into
// flight states exactly as the predictor does (left disc, disc centre at the origin, disc at its
// stored height above the ground z = 0).
#include <cstdint>
#include <vector>

#include "libspread/analysis/accuracy/accuracy.hpp"
#include "libspread/physics/flight/flight.hpp"
#include "libspread/io/scene/scene.hpp"

namespace spread::accuracy::detail {

struct LaunchSet {
  std::vector<flight::Granule> granules;
  std::vector<flight::State> launches;
  std::vector<double> mass_kg;
  flight::Air air;
  flight::EffectSet effects = flight::kDrag | flight::kMagnus | flight::kSpinDecay;
};

scene::Scene load_study_scene(const StudyOptions& options);
const scene::Material& study_material(const scene::Scene& scene, const StudyOptions& options);

LaunchSet make_launch_set(const scene::Scene& scene, const scene::Material& material, double rpm, int count,
                          std::uint64_t seed);

}  // namespace spread::accuracy::detail
