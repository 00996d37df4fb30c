// TOML → DrumScene, through the scene module's TOML document and key rows (libspread/io/scene/scene_key.hpp):
// the same reading, overrides and errors as the spreader's scenes — SceneError "drum.toml: drum.radius_m:
// must be > 0, got -1". The contact section's material quantities carry the material schema's names
// (friction_particle, friction_wall, youngs_modulus_pa); the drum's first spellings stay accepted aliases.
#include "libspread/physics/drum/drum_scene.hpp"
#include "libspread/physics/drum/drum_scene_keys.hpp"

#include <array>
#include <fstream>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/scene/toml_document.hpp"

namespace spread::drum {

namespace {

using scene::Key;

template <typename Owner, std::size_t N>
void read_section(scene::TomlSection s, Owner& owner, const std::array<Key<Owner>, N>& keys) {
  scene::read_keys<Owner>(s, owner, keys);
  s.finish();
}

// The drum has no effect list (rolling resistance acts when rolling_friction > 0): no key is tied to one.
constexpr effect::EffectSet kNoEffectList = effect::kAll;

}  // namespace

DrumScene parse_drum_scene(const std::string& text, const std::string& source, const std::vector<std::string>& overrides) {
  const scene::TomlDocument doc(text, source, overrides);
  DrumScene s;
  s.source_name = source;
  if (!doc.has("drum")) throw scene::SceneError(source + ": drum: missing [drum] table");
  doc.check_top_level_keys({"drum", "contact", "species", "numerics", "output"});

  scene::TomlSection drum = doc.section("drum");
  scene::read_keys<DrumScene>(drum, s, kDrumKeys);
  if (drum.present("wall_bead_diameter_m") && s.wall != DrumWall::kRoughParticles)
    drum.fail("wall_bead_diameter_m", "only used with wall = \"rough_particles\"");
  const bool has_rpm = drum.present("rpm"), has_froude = drum.present("froude");
  if (has_rpm && has_froude) drum.fail("froude", "give either rpm or froude, not both");
  if (!has_rpm && !has_froude) drum.fail("rpm", "missing: give rpm or froude (Fr = ω²R/g)");
  const double rpm = drum.number("rpm").value_or(0.0), froude = drum.number("froude").value_or(0.0);
  if (has_rpm && !(rpm >= 0.0)) drum.fail("rpm", "must be >= 0, got " + scene::format_number(rpm));
  if (has_froude && !(froude >= 0.0)) drum.fail("froude", "must be >= 0, got " + scene::format_number(froude));
  drum.finish();
  scene::check_keys<DrumScene>(source, "drum", s, kDrumKeys, kNoEffectList);  // R > 0 before ω from Fr
  s.angular_velocity_rad_s = has_rpm ? rpm * 2.0 * kPi / 60.0 : omega_from_froude(froude, s.radius_m);

  read_section(doc.section("contact"), s, kContactKeys);
  const std::vector<scene::TomlSection> species = doc.array_of_tables("species");
  for (const scene::TomlSection& table : species) {
    Species x;
    x.number_fraction = species.size() == 1 ? 1.0 : 0.5;
    read_section(table, x, kSpeciesKeys);
    s.species.push_back(x);
  }
  if (s.species.empty()) s.species.push_back(Species{});
  read_section(doc.section("numerics"), s, kNumericsKeys);
  read_section(doc.section("output"), s, kOutputKeys);
  validate(s);
  return s;
}

void validate(const DrumScene& s) {
  auto bad = [&](const std::string& key, const std::string& problem) {
    throw scene::SceneError(s.source_name + ": " + key + ": " + problem);
  };
  scene::check_keys<DrumScene>(s.source_name, "drum", s, kDrumKeys, kNoEffectList);
  scene::check_keys<DrumScene>(s.source_name, "contact", s, kContactKeys, kNoEffectList);
  scene::check_keys<DrumScene>(s.source_name, "numerics", s, kNumericsKeys, kNoEffectList);
  if (s.species.empty() || s.species.size() > 2) bad("species", "one or two [[species]] tables are needed");
  double share = 0.0;
  for (std::size_t i = 0; i < s.species.size(); ++i) {
    const auto& x = s.species[i];
    const std::string path = "species[" + std::to_string(i) + "]";
    scene::check_keys<Species>(s.source_name, path, x, kSpeciesKeys, kNoEffectList);
    if (!(x.diameter_m < s.radius_m)) bad(path + ".diameter_m", "must be smaller than drum.radius_m");
    if (!(x.diameter_m <= s.length_m)) bad(path + ".diameter_m", "must be <= drum.length_m (a particle must fit between the end walls)");
    share += x.number_fraction;
  }
  if (std::abs(share - 1.0) > 1e-9) bad("species", "number_fraction values must add up to 1");
  if (s.wall == DrumWall::kRoughParticles) {
    const double db = bead_diameter_m(s);
    if (!(db <= 0.25 * s.radius_m)) bad("drum.wall_bead_diameter_m", "must be <= drum.radius_m / 4 (the beads line the mantle)");
    if (!(db <= s.length_m)) bad("drum.wall_bead_diameter_m", "must be <= drum.length_m (one ring of beads must fit)");
    for (std::size_t i = 0; i < s.species.size(); ++i)
      if (!(s.species[i].diameter_m < free_radius_m(s)))
        bad("species[" + std::to_string(i) + "].diameter_m", "must be smaller than the radius inside the bead lining (drum.radius_m − bead diameter)");
  }
  if (!(s.measure_from_s <= s.rotate_s)) bad("numerics.measure_from_s", "must be in [0, rotate_s]");
}

double bead_diameter_m(const DrumScene& s) {
  if (s.wall != DrumWall::kRoughParticles) return 0.0;
  if (s.wall_bead_diameter_m > 0.0) return s.wall_bead_diameter_m;
  double mean = 0.0;
  for (const auto& x : s.species) mean += x.number_fraction * x.diameter_m;
  return mean;
}

DrumScene load_drum_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_drum_scene(scene::read_scene_text(path), path, overrides);
}

bool is_drum_scene_file(const std::string& path) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const auto b = line.find_first_not_of(" \t");
    if (b != std::string::npos && line.compare(b, 6, "[drum]") == 0) return true;
  }
  return false;
}

}  // namespace spread::drum
