#pragma once
// The monolithic reference of seed Sect. 3.1, kept for measuring what the partitioned scheme saves
// (Eq. 49): launched granules stay in the DEM time loop at the contact step Δt_c under gravity and drag
// until they land, instead of flying in the flight module at their own, much larger step. Runs beside
// dem::simulate as a dem::RunExtension; the DEM engine knows nothing of it.
#include <cstdint>
#include <vector>

#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/simulate.hpp"

namespace spread::accuracy {

// Launched granules in flight at Δt_c: after every DEM step the new launches join, each granule takes
// one symplectic Euler step (as the DEM itself) under gravity and the drag of Eq. 27 in still air, and
// those at or below the ground land. After the run's duration the on-disc granules are dropped and the
// engine steps on until every launched granule has landed or the simulated time reaches give_up_at_s.
class MonolithicFlight final : public dem::RunExtension {
 public:
  MonolithicFlight(double ground_z_m, const flight::Air& air, double give_up_at_s)
      : ground_z_m_(ground_z_m), air_(air), give_up_at_s_(give_up_at_s) {}

  void after_step(const dem::DemEngine& engine) override;
  void after_duration(dem::DemEngine& engine) override;

  const std::vector<Vec3>& landings() const { return landings_; }
  std::uint64_t flight_particle_steps() const { return flight_particle_steps_; }  // granule-steps in flight
  double flight_s() const { return flight_s_; }                                   // wall time of the flight

 private:
  double ground_z_m_;
  flight::Air air_;
  double give_up_at_s_;
  std::size_t joined_ = 0;  // launches taken from the engine so far
  // Granules in flight (flat arrays): position, velocity, diameter, mass.
  std::vector<double> x_, y_, z_, vx_, vy_, vz_, d_, m_;
  std::vector<Vec3> landings_;
  std::uint64_t flight_particle_steps_ = 0;
  double flight_s_ = 0.0;
};

struct MonolithicResult {
  dem::SimulationResult run;      // the disc run (its module_time_s has "monolithic_flight" too)
  std::vector<Vec3> landings;     // where the launched granules landed, in the order they landed
  std::uint64_t flight_particle_steps = 0;
};

// Eq. 49 from a partitioned run (dem::simulate with fly on): T_c the mean time a launched granule spent
// on the disc, T_f its mean flight time, N_fc = Δt_f/Δt_c with Δt_f = T_f over the mean flight steps per
// granule, and the predicted saving of the partitioned scheme C_r = (1 − 1/N_fc) / (1 + T_c/T_f).
// NaN when nothing launched.
struct PartitionSaving {
  double t_c_s = 0.0;
  double t_f_s = 0.0;
  double n_fc = 0.0;
  double c_r = 0.0;
};
PartitionSaving predicted_saving(const dem::SimulationResult& partitioned);

// dem::simulate(config) with the MonolithicFlight beside it; the ground is z = −config.disc_height_m, and
// granules still in the air 30 s after config.duration_s are left there (none reach that on a spreader).
MonolithicResult simulate_monolithic(const dem::SimulationConfig& config);

}  // namespace spread::accuracy
