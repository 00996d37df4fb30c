#pragma once
// Seed Case 1 as the disc benchmarks run it: scenes/case1.toml read through the scene reader (its flight
// scheme and tolerance included), with the three departures the benchmarks need: ξ 5 mm (the mesh of the
// LIGGGHTS comparison, docs/dem.md), one thread, and flight with drag only (the monolithic reference
// integrates drag + gravity only).
// bench/bench_dem.cpp and bench/peers/liggghts_case1/ours_case1_cpu.cpp share this one definition.
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/physics/dem/simulate.hpp"
#include "libspread/io/scene/scene.hpp"

namespace spread::bench {

inline dem::SimulationConfig case1_config(double duration_s) {
  const scene::Scene s =
      scene::load_scene_file(SPREAD_SOURCE_DIR "/scenes/case1.toml", {"machine.mesh_size_m=0.005", "numerics.threads=1"});
  dem::SimulationConfig c = dem::config_from_scene(s);
  c.duration_s = duration_s;
  c.flight_effects = flight::kDrag;
  return c;
}

}  // namespace spread::bench
