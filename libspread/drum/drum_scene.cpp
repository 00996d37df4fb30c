// TOML → DrumScene. Errors name the file and the key: "drum.toml: drum.radius_m: must be > 0".
#include "libspread/drum/drum_scene.hpp"

#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

namespace spread::drum {

namespace {

// One TOML table read with typed getters; keys not read are reported as unknown (a typo must not be
// silently ignored).
class Table {
 public:
  Table(const toml::table* t, std::string path, std::string source) : t_(t), path_(std::move(path)), src_(std::move(source)) {}
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw std::invalid_argument(src_ + ": " + path_ + "." + key + ": " + problem);
  }
  const toml::node* get(const std::string& key) {
    used_.insert(key);
    return t_ ? t_->get(key) : nullptr;
  }
  bool has(const std::string& key) const { return t_ && t_->contains(key); }
  double number(const std::string& key, double fallback) {
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (const auto* f = n->as_floating_point()) {
      if (!std::isfinite(f->get())) fail(key, "must be finite");
      return f->get();
    }
    if (const auto* i = n->as_integer()) return static_cast<double>(i->get());
    fail(key, "expected a number");
  }
  std::string string(const std::string& key, const std::string& fallback) {
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (const auto* s = n->as_string()) return s->get();
    fail(key, "expected a string");
  }
  bool boolean(const std::string& key, bool fallback) {
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (const auto* b = n->as_boolean()) return b->get();
    fail(key, "expected true or false");
  }
  void check_unknown() const {
    if (!t_) return;
    for (auto&& [k, v] : *t_)
      if (!used_.count(std::string(k.str()))) fail(std::string(k.str()), "unknown key");
  }

 private:
  const toml::table* t_;
  std::string path_, src_;
  std::set<std::string> used_;
};

void apply_override(toml::table& root, const std::string& assignment, const std::string& source) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) throw std::invalid_argument(source + ": --set " + assignment + ": expected key=value");
  const std::string key = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    parsed = toml::parse("v = \"" + value + "\"");
  }
  toml::table* t = &root;
  std::stringstream ss(key);
  std::string part, last;
  std::vector<std::string> parts;
  while (std::getline(ss, part, '.')) parts.push_back(part);
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    if (!t->contains(parts[i])) t->insert(parts[i], toml::table{});
    t = (*t)[parts[i]].as_table();
    if (!t) throw std::invalid_argument(source + ": --set " + key + ": " + parts[i] + " is not a table");
  }
  t->insert_or_assign(parts.back(), *parsed.get("v"));
}

}  // namespace

DrumScene parse_drum_scene(const std::string& text, const std::string& source, const std::vector<std::string>& overrides) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << source << ": line " << e.source().begin.line << ": " << e.description();
    throw std::invalid_argument(os.str());
  }
  for (const auto& o : overrides) apply_override(root, o, source);
  DrumScene s;
  s.source_name = source;
  if (!root.get_as<toml::table>("drum")) throw std::invalid_argument(source + ": drum: missing [drum] table");
  for (auto&& [k, v] : root) {
    const std::string key(k.str());
    if (key != "drum" && key != "contact" && key != "species" && key != "numerics" && key != "output")
      throw std::invalid_argument(source + ": " + key + ": unknown section");
  }
  Table drum(root.get_as<toml::table>("drum"), "drum", source);
  s.radius_m = drum.number("radius_m", s.radius_m);
  s.length_m = drum.number("length_m", s.length_m);
  const std::string axial = drum.string("axial", "frictionless_walls");
  if (axial == "frictionless_walls") s.axial = AxialBoundary::kFrictionlessWalls;
  else if (axial == "walls") s.axial = AxialBoundary::kWalls;
  else if (axial == "periodic") s.axial = AxialBoundary::kPeriodic;
  else drum.fail("axial", "expected \"frictionless_walls\", \"walls\" or \"periodic\", got \"" + axial + "\"");
  const std::string wall = drum.string("wall", "analytic_cylinder");
  if (wall == "analytic_cylinder") s.wall = DrumWall::kAnalyticCylinder;
  else if (wall == "rough_particles") s.wall = DrumWall::kRoughParticles;
  else drum.fail("wall", "expected \"analytic_cylinder\" or \"rough_particles\" (a layer of fixed beads), got \"" + wall + "\"");
  if (drum.has("wall_bead_diameter_m") && s.wall != DrumWall::kRoughParticles)
    drum.fail("wall_bead_diameter_m", "only used with wall = \"rough_particles\"");
  s.wall_bead_diameter_m = drum.number("wall_bead_diameter_m", s.wall_bead_diameter_m);
  const bool has_rpm = drum.has("rpm"), has_fr = drum.has("froude");
  if (has_rpm && has_fr) drum.fail("froude", "give either rpm or froude, not both");
  if (!has_rpm && !has_fr) drum.fail("rpm", "missing: give rpm or froude (Fr = ω²R/g)");
  const double rpm = drum.number("rpm", 0.0), fr = drum.number("froude", 0.0);
  if (has_rpm && !(rpm >= 0.0)) drum.fail("rpm", "must be >= 0");
  if (has_fr && !(fr >= 0.0)) drum.fail("froude", "must be >= 0");
  s.fill_fraction = drum.number("fill_fraction", s.fill_fraction);
  s.bed_solid_fraction = drum.number("bed_solid_fraction", s.bed_solid_fraction);
  drum.check_unknown();
  if (!(s.radius_m > 0.0)) throw std::invalid_argument(source + ": drum.radius_m: must be > 0");
  s.angular_velocity_rad_s = has_rpm ? rpm * 2.0 * kPi / 60.0 : omega_from_froude(fr, s.radius_m);

  Table contact(root.get_as<toml::table>("contact"), "contact", source);
  const std::string model = contact.string("model", "linear");
  // "hertz" is the older spelling of "hertz_thornton" (Hertz normal, Thornton tangential), kept as an alias.
  if (model == "linear") s.law = dem::kLinearSpringDashpotLaw;
  else if (model == "hertz_thornton" || model == "hertz") s.law = dem::kHertzThorntonLaw;
  else contact.fail("model", "expected \"linear\" (spring–dashpot, seed 001) or \"hertz_thornton\" (alias \"hertz\"), got \"" + model + "\"");
  s.normal_stiffness_n_m = contact.number("normal_stiffness_n_m", s.normal_stiffness_n_m);
  s.tangential_ratio = contact.number("tangential_ratio", s.tangential_ratio);
  s.young_modulus_pa = contact.number("young_modulus_pa", s.young_modulus_pa);
  s.poisson_ratio = contact.number("poisson_ratio", s.poisson_ratio);
  s.restitution = contact.number("restitution", s.restitution);
  s.friction = contact.number("friction", s.friction);
  s.wall_friction = contact.number("wall_friction", s.wall_friction);
  s.rolling_friction = contact.number("rolling_friction", s.rolling_friction);
  contact.check_unknown();

  if (const auto* arr = root.get_as<toml::array>("species")) {
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const auto* t = arr->get(i)->as_table();
      const std::string path = "species[" + std::to_string(i) + "]";
      if (!t) throw std::invalid_argument(source + ": " + path + ": expected a table ([[species]])");
      Table sp(t, path, source);
      Species x;
      x.diameter_m = sp.number("diameter_m", x.diameter_m);
      x.density_kg_m3 = sp.number("density_kg_m3", x.density_kg_m3);
      x.number_fraction = sp.number("number_fraction", arr->size() == 1 ? 1.0 : 0.5);
      sp.check_unknown();
      s.species.push_back(x);
    }
  } else if (root.contains("species")) {
    throw std::invalid_argument(source + ": species: expected an array of tables ([[species]])");
  }
  if (s.species.empty()) s.species.push_back(Species{});

  Table num(root.get_as<toml::table>("numerics"), "numerics", source);
  const std::string integ = num.string("integrator", "gear5");
  if (integ == "symplectic_euler") s.integrator = dem::Integrator::kSymplecticEuler;
  else if (integ == "velocity_verlet") s.integrator = dem::Integrator::kVelocityVerlet;
  else if (integ == "gear4") s.integrator = dem::Integrator::kGear4;
  else if (integ == "gear5") s.integrator = dem::Integrator::kGear5;
  else if (integ == "gear6") s.integrator = dem::Integrator::kGear6;
  else num.fail("integrator", "expected symplectic_euler, velocity_verlet, gear4, gear5 or gear6, got \"" + integ + "\"");
  s.contact_steps = num.number("contact_steps", s.contact_steps);
  s.dt_s = num.number("dt_s", s.dt_s);
  s.settle_max_s = num.number("settle_max_s", s.settle_max_s);
  s.rest_energy_ratio = num.number("rest_energy_ratio", s.rest_energy_ratio);
  s.rotate_s = num.number("rotate_s", s.rotate_s);
  s.measure_from_s = num.number("measure_from_s", s.measure_from_s);
  s.sample_every_s = num.number("sample_every_s", s.sample_every_s);
  s.threads = static_cast<int>(num.number("threads", s.threads));
  num.check_unknown();

  Table out(root.get_as<toml::table>("output"), "output", source);
  s.output_directory = out.string("directory", "");
  s.energy_csv = out.boolean("energy_csv", s.energy_csv);
  s.particles_csv = out.boolean("particles_csv", s.particles_csv);
  out.check_unknown();
  validate(s);
  return s;
}

void validate(const DrumScene& s) {
  auto bad = [&](const std::string& key, const std::string& problem) {
    throw std::invalid_argument(s.source_name + ": " + key + ": " + problem);
  };
  if (!(s.radius_m > 0.0)) bad("drum.radius_m", "must be > 0");
  if (!(s.length_m > 0.0)) bad("drum.length_m", "must be > 0");
  if (!(s.fill_fraction > 0.0 && s.fill_fraction < 0.95)) bad("drum.fill_fraction", "must be in (0, 0.95)");
  if (!(s.bed_solid_fraction > 0.1 && s.bed_solid_fraction <= 0.74)) bad("drum.bed_solid_fraction", "must be in (0.1, 0.74]");
  if (s.species.empty() || s.species.size() > 2) bad("species", "one or two [[species]] tables are needed");
  double share = 0.0;
  for (std::size_t i = 0; i < s.species.size(); ++i) {
    const auto& x = s.species[i];
    const std::string p = "species[" + std::to_string(i) + "].";
    if (!(x.diameter_m > 0.0)) bad(p + "diameter_m", "must be > 0");
    if (!(x.diameter_m < s.radius_m)) bad(p + "diameter_m", "must be smaller than drum.radius_m");
    if (!(x.diameter_m <= s.length_m)) bad(p + "diameter_m", "must be <= drum.length_m (a particle must fit between the end walls)");
    if (!(x.density_kg_m3 > 0.0)) bad(p + "density_kg_m3", "must be > 0");
    if (!(x.number_fraction > 0.0 && x.number_fraction <= 1.0)) bad(p + "number_fraction", "must be in (0, 1]");
    share += x.number_fraction;
  }
  if (std::abs(share - 1.0) > 1e-9) bad("species", "number_fraction values must add up to 1");
  if (s.wall == DrumWall::kRoughParticles) {
    if (!(s.wall_bead_diameter_m >= 0.0)) bad("drum.wall_bead_diameter_m", "must be > 0 (or 0: the mean species diameter)");
    const double db = bead_diameter_m(s);
    if (!(db <= 0.25 * s.radius_m)) bad("drum.wall_bead_diameter_m", "must be <= drum.radius_m / 4 (the beads line the mantle)");
    if (!(db <= s.length_m)) bad("drum.wall_bead_diameter_m", "must be <= drum.length_m (one ring of beads must fit)");
    for (std::size_t i = 0; i < s.species.size(); ++i)
      if (!(s.species[i].diameter_m < free_radius_m(s)))
        bad("species[" + std::to_string(i) + "].diameter_m", "must be smaller than the radius inside the bead lining (drum.radius_m − bead diameter)");
  }
  if (s.law.normal == dem::NormalModel::kLinear && !(s.normal_stiffness_n_m > 0.0))
    bad("contact.normal_stiffness_n_m", "must be > 0");
  if (!(s.tangential_ratio >= 0.0)) bad("contact.tangential_ratio", "must be >= 0");
  if (!(s.young_modulus_pa > 0.0)) bad("contact.young_modulus_pa", "must be > 0");
  if (!(s.restitution > 0.0 && s.restitution <= 1.0)) bad("contact.restitution", "must be in (0, 1]");
  if (!(s.friction >= 0.0)) bad("contact.friction", "must be >= 0");
  if (!(s.wall_friction >= 0.0)) bad("contact.wall_friction", "must be >= 0");
  if (!(s.rolling_friction >= 0.0)) bad("contact.rolling_friction", "must be >= 0");
  if (!(s.contact_steps >= 5.0)) bad("numerics.contact_steps", "must be >= 5 (the seed resolves a contact in >= 10 steps)");
  if (!(s.dt_s >= 0.0)) bad("numerics.dt_s", "must be >= 0");
  if (!(s.settle_max_s > 0.0)) bad("numerics.settle_max_s", "must be > 0");
  if (!(s.rest_energy_ratio > 0.0)) bad("numerics.rest_energy_ratio", "must be > 0");
  if (!(s.rotate_s >= 0.0)) bad("numerics.rotate_s", "must be >= 0");
  if (!(s.measure_from_s >= 0.0 && s.measure_from_s <= s.rotate_s)) bad("numerics.measure_from_s", "must be in [0, rotate_s]");
  if (!(s.sample_every_s > 0.0)) bad("numerics.sample_every_s", "must be > 0");
  if (s.threads < 1) bad("numerics.threads", "must be >= 1");
}

double bead_diameter_m(const DrumScene& s) {
  if (s.wall != DrumWall::kRoughParticles) return 0.0;
  if (s.wall_bead_diameter_m > 0.0) return s.wall_bead_diameter_m;
  double mean = 0.0;
  for (const auto& x : s.species) mean += x.number_fraction * x.diameter_m;
  return mean;
}

DrumScene load_drum_scene(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open the scene file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_drum_scene(ss.str(), path, overrides);
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
