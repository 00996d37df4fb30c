#pragma once
// Full process (seed Sect. 3.1, partitioned): disc DEM at Δt_c until each particle crosses the
// collector, its launch state recorded; then every launched particle flies with the flight module at
// its own (much larger) step to the ground. Also the library entry a lookup_builder calls:
// "simulate this (machine, material, rpm) and give me the launch states".
#include <array>
#include <map>
#include <string>
#include <vector>

#include "libspread/physics/dem/disc_generator.hpp"
#include "libspread/physics/dem/energy_monitor.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/inlet.hpp"
#include "libspread/physics/flight/flight.hpp"

namespace spread::dem {

struct SimulationConfig {
  std::vector<Material> materials;     // [0] = the particle material, others walls
  std::vector<PairOverride> overrides;
  DiscGeometry disc;                   // in the disc frame; the disc centre is the origin
  double rpm = 500.0;                  // > 0 counter-clockwise seen from above, < 0 clockwise
  int disc_material = 1;
  double disc_height_m = 0.28;         // rim height above the ground: the ground is z = −height
  InletParams inlet;
  EngineParams engine;
  double duration_s = 0.4;             // simulated DEM time (particles still on the disc then are dropped)
  double collector_radius_m = 0.0;     // 0: the disc radius
  // Flight after launch.
  bool fly = true;
  flight::EffectSet flight_effects = flight::kDrag | flight::kMagnus | flight::kSpinDecay;
  flight::Air air;
  flight::Settings flight_settings;
  int flight_threads = 1;
  // Outputs (empty = none).
  std::string vtk_prefix;        // particles: <prefix>_<step>.vtk (vtk_writer.hpp)
  std::string vtk_walls_prefix;  // walls at the same steps: <prefix>_<step>.vtk; empty = none
  int vtk_every_steps = 0;
  // Energy and penetration diagnostics (energy_monitor.hpp): 0 = off (costs nothing); N > 0 = on, with a
  // time-series sample every N steps (the budget itself is kept every step).
  int energy_monitor_every_steps = 0;
};

struct LaunchSummary {
  double speed_mean = 0.0, speed_sd = 0.0;   // m/s
  double angle_from_tangent_deg_mean = 0.0;  // horizontal velocity from the tangent (+ = outwards)
  double elevation_deg_mean = 0.0;           // velocity above the horizontal
};

struct SimulationResult {
  std::vector<LaunchRecord> launches;
  std::vector<flight::Landing> landings;      // same order as launches (when flown)
  LaunchSummary launch;
  std::array<double, 12> sector_mass_fraction{};  // 30° sectors of the launch position, inertial, from +x
  double mean_radius_m = 0.0;                 // R̄, Eq. 51 (landings, from the disc centre)
  double radial_width_m = 0.0;                // ξ, Eq. 52
  std::uint64_t released = 0;
  std::uint64_t on_disc_at_end = 0;
  std::uint64_t lost = 0;
  std::uint64_t particle_steps = 0;           // on-disc particle-steps
  std::uint64_t flight_steps = 0;             // accepted flight steps
  double dt_contact_s = 0.0, contact_time_s = 0.0;
  double wall_time_s = 0.0;
  std::vector<std::string> effects;           // effects that ran
  std::map<std::string, double> module_time_s;
  EngineStats engine_stats;
  // Filled when config.energy_monitor_every_steps > 0.
  bool energy_monitored = false;
  EnergyReport energy;
  std::vector<EnergySample> energy_samples;
};

// What runs alongside the disc run of simulate() without being part of it (the monolithic cost
// reference of libspread/analysis/accuracy): called after every step of the run, and once when the simulated
// duration is over, before the results are read (it may step the engine on; the inlet has stopped).
class RunExtension {
 public:
  virtual ~RunExtension() = default;
  virtual void after_step(const DemEngine& engine) = 0;
  virtual void after_duration(DemEngine& engine) = 0;
};

// The full process: the disc run (disc_run.hpp) for config.duration_s, then the flight of every launch.
// Throws std::invalid_argument naming the bad value.
SimulationResult simulate(const SimulationConfig& config, RunExtension* extension = nullptr);

LaunchSummary summarise_launches(const std::vector<LaunchRecord>& launches, const Vec3& axis_point);
std::array<double, 12> sector_mass_fraction(const std::vector<LaunchRecord>& launches, const Vec3& axis_point);

// Writer of the launch records (VTK snapshots: vtk_writer.hpp).
void write_launch_csv(const std::vector<LaunchRecord>& launches, const std::string& path);

}  // namespace spread::dem
