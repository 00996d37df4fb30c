#pragma once
// The drum run (seed 001 Sect. 4): grid placement, settling under gravity until the kinetic energy is
// negligible (its history is the seed's Fig. 4.4), then rotation of the drum wall with the settled state
// as the start (as in the seed), sampling the bed measurements and labelling the flow regime.
#include <string>
#include <vector>

#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/drum/drum_packing.hpp"
#include "libspread/physics/drum/drum_scene.hpp"
#include "libspread/physics/drum/measurements.hpp"

namespace spread::drum {

// The engine for a drum scene turning at `omega_rad_s` (materials, pair overrides, walls, numerics).
// Materials: one per species, then the drum wall, then the end walls.
dem::DemEngine make_drum_engine(const DrumScene& s, double omega_rad_s);

struct EnergySample {
  std::string phase;  // "settle" or "rotate"
  double time_s = 0.0;
  double kinetic_energy_j = 0.0;
};

struct DrumResult {
  std::size_t particles = 0;
  double dt_s = 0.0;
  double contact_time_s = 0.0;
  double froude = 0.0;
  double settle_time_s = 0.0;
  bool settled = false;
  double rest_threshold_j = 0.0;         // KE below this counts as rest
  std::vector<EnergySample> energy;
  std::vector<Snapshot> snapshots;       // rotation phase, every sample_every_s
  RegimeEvidence evidence;               // over [measure_from_s, rotate_s]
  std::uint64_t particle_steps = 0;
  double wall_s = 0.0;
  dem::ParticleArrays final_particles;
  std::vector<std::string> files;        // written outputs
};

DrumResult run_drum(const DrumScene& s);

void write_energy_csv(const std::vector<EnergySample>& e, const std::string& path);
void write_particles_csv(const dem::ParticleArrays& p, const std::string& path);

}  // namespace spread::drum
