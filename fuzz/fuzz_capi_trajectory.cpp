// Fuzz harness: spread_trajectory() with fuzzed definition fields (no table). As in fuzz_capi_predict,
// a flag bit per field chooses raw bytes or a plausible range. Checked: documented statuses only, and
// a landing that is finite, on the ground plane, at a non-negative time.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/capi_invariants.hpp"
#include "fuzz/fuzz_input.hpp"
#include "spread/spread.h"

namespace {

constexpr const char* kHarness = "fuzz_capi_trajectory";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  spread::fuzz::FuzzInput in(data, size);
  const auto raw = in.take<std::uint16_t>();
  const auto pick = [&](int bit) { return (raw >> bit) & 1u; };
  // Plausible: a granule of 0.1–10 mm, 100–5000 kg/m³, launched from up to 2.5 m at up to ±64 m/s
  // with up to ±3200 rad/s of spin, in air of up to twice sea-level density.
  const auto scaled = [&](int bit, double low, double high) {
    return pick(bit) ? in.take_raw_double() : low + (high - low) * (in.take<std::uint16_t>() / 65535.0);
  };
  spread_trajectory_def def = spread_trajectory_def_default();
  def.diameter_m = scaled(0, 1e-4, 1e-2);
  def.density_kg_m3 = scaled(1, 100.0, 5000.0);
  for (double& x : def.position_m) x = scaled(2, -1.0, 1.0);
  def.position_m[2] = scaled(3, 0.0, 2.5);
  for (double& v : def.velocity_m_s) v = scaled(4, -64.0, 64.0);
  for (double& w : def.spin_rad_s) w = scaled(5, -3200.0, 3200.0);
  def.ground_z_m = scaled(6, -0.5, 0.5);
  def.air_density_kg_m3 = scaled(7, 0.0, 2.5);
  def.air_viscosity_pa_s = scaled(8, 1e-6, 1e-3);
  for (double& w : def.wind_m_s) w = scaled(9, -30.0, 30.0);
  def.effects = pick(10) ? in.take<std::uint32_t>() : in.take<std::uint8_t>() & SPREAD_EFFECT_ALL;
  if (pick(11)) def.struct_size = in.take<std::uint32_t>();

  spread_landing landing{};
  const spread_status status = spread_trajectory(&def, &landing);
  spread::fuzz::check_status(kHarness, status, "spread_trajectory");
  if (status != SPREAD_OK) return 0;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(landing.position_m[i]) || !std::isfinite(landing.velocity_m_s[i]) ||
        !std::isfinite(landing.spin_rad_s[i])) {
      spread::fuzz::fail(kHarness, "landing state not finite");
    }
  }
  if (!(landing.flight_time_s >= 0.0) || !std::isfinite(landing.flight_time_s)) spread::fuzz::fail(kHarness, "bad flight time");
  const double tolerance = 1e-6 * (1.0 + std::abs(def.ground_z_m));  // root finding to ~µm
  if (std::abs(landing.position_m[2] - def.ground_z_m) > tolerance) {
    spread::fuzz::fail(kHarness, "landed at z = " + std::to_string(landing.position_m[2]) + ", ground at " +
                                     std::to_string(def.ground_z_m));
  }
  return 0;
}
