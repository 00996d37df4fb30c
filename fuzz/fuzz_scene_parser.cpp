// Fuzz harness: the TOML scene parser with --set overrides (libspread/io/scene).
// Input: TOML text, optionally followed by a line "#--set" and one override "key=value" per line.
// Contract checked: parse_scene either returns a scene or throws SceneError — never another exception,
// never a crash — and an accepted scene has finite numbers and answers its queries.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/fuzz_input.hpp"
#include "libspread/io/scene/scene.hpp"

namespace {

constexpr const char* kHarness = "fuzz_scene_parser";
constexpr std::string_view kOverrideMarker = "\n#--set\n";

void check_finite(double value, const char* what) {
  if (!std::isfinite(value)) spread::fuzz::fail(kHarness, std::string("accepted scene has non-finite ") + what);
}

void check_scene(const spread::scene::Scene& s) {
  check_finite(s.machine.disc_radius_m, "machine.disc_radius_m");
  check_finite(s.machine.rpm, "machine.rpm");
  check_finite(s.inlet.mass_flow_kg_s, "inlet.mass_flow_kg_s");
  check_finite(s.air.density_kg_m3, "air.density_kg_m3");
  check_finite(s.air.wind_m_s[0], "air.wind_m_s[0]");
  check_finite(s.air.wind_m_s[1], "air.wind_m_s[1]");
  check_finite(s.numerics.duration_s, "numerics.duration_s");
  check_finite(s.numerics.dt_contact_s, "numerics.dt_contact_s");
  for (const auto& m : s.materials) {
    check_finite(m.density_kg_m3, "materials.density_kg_m3");
    check_finite(m.diameter_mean_m, "materials.diameter_mean_m");
    check_finite(m.youngs_modulus_pa, "materials.youngs_modulus_pa");
  }
  for (double rpm : s.sweep_rpms()) check_finite(rpm, "sweep.rpm");
  for (const auto* m : s.sweep_materials()) {
    if (m == nullptr) spread::fuzz::fail(kHarness, "sweep_materials() returned a null material");
  }
  (void)s.hash();
  (void)spread::effect::to_string(s.effects);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  std::string text = input;
  std::vector<std::string> overrides;
  if (const std::size_t marker = input.find(kOverrideMarker); marker != std::string::npos) {
    text = input.substr(0, marker);
    std::size_t start = marker + kOverrideMarker.size();
    while (start < input.size()) {
      std::size_t end = input.find('\n', start);
      if (end == std::string::npos) end = input.size();
      overrides.push_back(input.substr(start, end - start));
      start = end + 1;
    }
  }
  try {
    const spread::scene::Scene scene = spread::scene::parse_scene(text, "fuzz.toml", overrides);
    check_scene(scene);
  } catch (const spread::scene::SceneError&) {
    // The documented refusal.
  }
  return 0;
}
