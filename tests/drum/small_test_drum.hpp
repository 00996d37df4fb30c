#pragma once
// The small thin test drum shared by the drum suites: scenes/drum.toml's drum (R 0.04 m, L 9 mm,
// frictionless end walls, 4 mm beads, linear k_n 1000 N/m, fill 0.35) without its output table, so a
// test writes nothing. Each suite states what it changes as `--set` overrides (applied in order, the
// last assignment of a key wins).
#include <string>
#include <vector>

#include "libspread/physics/drum/drum_scene.hpp"

namespace spread::testing {

inline constexpr const char* kSmallTestDrum = R"(
[drum]
radius_m = 0.04
length_m = 0.009
froude = 0.02
fill_fraction = 0.35
[contact]
model = "linear"
normal_stiffness_n_m = 1000.0
restitution = 0.5
friction_particle = 0.5
friction_wall = 0.8
[[species]]
diameter_m = 0.004
density_kg_m3 = 2500.0
[numerics]
integrator = "velocity_verlet"
contact_steps = 12
rotate_s = 1.5
measure_from_s = 0.75
)";

inline drum::DrumScene small_test_drum(const std::vector<std::string>& overrides = {}) {
  return drum::parse_drum_scene(kSmallTestDrum, "small_test_drum.toml", overrides);
}

}  // namespace spread::testing
