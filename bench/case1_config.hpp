#pragma once
// Seed Case 1 (Table 1: R 0.29 m, cone 0.157 rad, 2 vanes 0.036 m high, inlet r 0.0145 m at 0.1 m,
// 0.11 kg/s, 500 rpm, μ 0.35) as the disc benchmarks run it: bench/bench_dem.cpp and the side-by-side
// run against LIGGGHTS (bench/peers/liggghts_case1/ours_case1_cpu.cpp) share this one definition.
#include <cmath>

#include "libspread/dem/simulate.hpp"

namespace spread::bench {

inline dem::SimulationConfig case1_config(double duration_s) {
  dem::SimulationConfig c;
  dem::Material granule;  // scenes/case1.toml's granule (only μ is in the seed)
  granule.name = "case1 granule";
  granule.density_kg_m3 = 1800;
  granule.young_modulus_pa = 5e7;
  granule.poisson_ratio = 0.25;
  granule.restitution = 0.5;
  granule.friction = 0.35;
  dem::Material disc = granule;
  disc.name = "disc";
  disc.rigid = true;
  c.materials = {granule, disc};
  c.disc.radius_m = 0.29;
  c.disc.cone_angle_rad = 0.157;
  c.disc.z_apex_m = -0.29 * std::tan(0.157);
  c.disc.vane_count = 2;
  c.disc.vane_height_m = 0.036;
  c.disc.mesh_size_m = 0.005;  // ξ the peer comparison (bench/peers) used; scenes/case1.toml now uses R/100
  c.rpm = 500;
  c.disc_height_m = 0.28;
  c.inlet.radius_m = 0.0145;
  c.inlet.mass_rate_kg_s = 0.11;
  c.inlet.diameter_mean_m = 3.2e-3;
  c.inlet.diameter_sd_m = 0.6e-3;
  c.inlet.release_speed_m_s = 0.5;
  const double surface = c.disc.z_apex_m + std::tan(0.157) * 0.1;
  c.inlet.centre_m = Vec3(0.1 * std::cos(1.0), 0.1 * std::sin(1.0), surface + 0.05);
  c.engine.contact_steps = 15;
  c.engine.threads = 1;
  c.duration_s = duration_s;
  c.flight_effects = flight::kDrag;  // the monolithic reference integrates drag + gravity only
  c.flight_threads = 1;
  return c;
}

}  // namespace spread::bench
