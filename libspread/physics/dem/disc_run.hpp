#pragma once
// One run on the spinning disc (seed Sect. 3.1, the DEM part of the partitioned scheme): the disc's
// walls, the engine with the particle radius range of the inlet's diameter law, the launch collector
// and the inlet, all from a SimulationConfig, and the step that feeds the inlet before each engine
// step. dem::simulate, lookup_builder's DEM source and the tests run the disc through it, so a given
// stop time gives the same launches in all of them.
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/inlet.hpp"
#include "libspread/physics/dem/simulate.hpp"

namespace spread::dem {

// The collector's floor, this far below the disc's apex (cfg.disc.z_apex_m). The collector removes a
// particle once it is outside the cylinder; one that has passed through the disc instead (a tunnelling
// contact, a gap in a mesh) stays inside it and would fall in the DEM loop for ever. The disc surface
// spans only |tan α| R (a few centimetres) about the apex, so nothing still on the disc or its vanes
// is 0.5 m below it: a particle there has fallen through, and is removed and counted in
// EngineStats::lost. It should not happen.
inline constexpr double kFallenBelowApex_m = 0.5;

// The collector of a disc run: the cylinder about the disc axis of radius cfg.collector_radius_m (0: the
// disc radius), with the floor kFallenBelowApex_m below the apex.
Collector disc_collector(const SimulationConfig& cfg);

// cfg.engine with the radius range of the inlet's diameter law, [d_min/2, d_max/2]
// (inlet_diameter_range_m: the lognormal's truncation, or the sieve analysis's intervals with mass).
EngineParams disc_engine_params(const SimulationConfig& cfg);

class DiscRun {
 public:
  // The disc of `cfg` turning at cfg.rpm, the engine with disc_engine_params(cfg), disc_collector(cfg)
  // and the inlet. Throws std::invalid_argument as DemEngine and Inlet do.
  explicit DiscRun(const SimulationConfig& cfg);
  // The same with the engine parameters given (granules placed by hand: the radius range is theirs).
  DiscRun(const SimulationConfig& cfg, const EngineParams& engine_params);

  // True while t_s is more than half a step ahead: the step loop runs `while (run.before(T)) run.step();`
  // and stops at the step nearest T, whatever rounding the sum of the steps carries.
  bool before(double t_s) const { return engine_.time_s() + 0.5 * engine_.dt_s() < t_s; }
  // The inlet releases the particles due now, then the engine takes one step.
  void step();

  DemEngine& engine() { return engine_; }
  const DemEngine& engine() const { return engine_; }
  const Inlet& inlet() const { return inlet_; }
  double inlet_s() const { return inlet_s_; }  // wall time spent releasing particles

 private:
  DemEngine engine_;
  Inlet inlet_;
  double inlet_s_ = 0.0;
};

}  // namespace spread::dem
