// Built only by the test architecture.dem_context_field_left_out_fails_the_build (never part of a program):
// the pair pass's context initialised by name with one field (near_held) left out. It must not compile:
// -Werror=missing-field-initializers (cmake/SpreadWarnings.cmake) makes the omission an error, so a field
// added to PairPassArrays without its line in DemEngine::pair_pass_arrays fails the build.
#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/pair_pass_context.hpp"

namespace spread::dem {

pairs::PairPassArrays<HertzThornton> context_without_near_held() {
  return pairs::PairPassArrays<HertzThornton>{
      .x = nullptr, .y = nullptr, .z = nullptr, .vx = nullptr, .vy = nullptr, .vz = nullptr,
      .wx = nullptr, .wy = nullptr, .wz = nullptr, .radius = nullptr, .mass = nullptr, .inertia = nullptr,
      .material = nullptr, .active = nullptr, .pair_start = nullptr, .partner = nullptr,
      .history = nullptr, .held = nullptr, .pair_force = nullptr, .pair_torque_i = nullptr,
      .pair_torque_j = nullptr, .sums = nullptr, .fx = nullptr, .fy = nullptr, .fz = nullptr,
      .tx = nullptr, .ty = nullptr, .tz = nullptr, .params = nullptr, .coeffs = nullptr,
      .material_count = 0, .period_m = 0.0, .dt_s = 0.0, .kick_dt_s = 0.0,
      .gravity_m_s2 = {0.0, 0.0, 0.0}, .inv_mass = nullptr, .inv_inertia = nullptr,
      .kick_v = {nullptr, nullptr, nullptr}, .kick_w = {nullptr, nullptr, nullptr},
      .near_start = nullptr, .near_pairs = nullptr, .near_first = nullptr, .near_second = nullptr,
      .touch_rows = nullptr, .law_rows = nullptr,
      .drift_dt_s = 0.0, .drift_clears_sums = false, .position = {nullptr, nullptr, nullptr},
      .x0 = nullptr, .y0 = nullptr, .z0 = nullptr};
}

}  // namespace spread::dem
