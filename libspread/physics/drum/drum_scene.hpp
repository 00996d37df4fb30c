#pragma once
// The rotating-drum scene (seed 001): a horizontal drum turning about its axis, partly filled with one
// or two particle species. Frame of the drum module: the drum axis is z (the engine's rotation axis),
// gravity points along −y, the cross-section is the x–y plane, the drum turns counter-clockwise seen from
// +z (the bed is lifted on the +x side). TOML format in docs/drum.md.
#include <cmath>
#include <string>
#include <vector>

#include "libspread/physics/dem/engine.hpp"

namespace spread::drum {

enum class AxialBoundary {
  kFrictionlessWalls,  // static, frictionless end walls: stands in for a periodic axis (thin "2D" drums)
  kWalls,              // end walls turning with the drum, with the wall friction
  kPeriodic,           // no end walls: periodic along z with period length_m (length_m >= 3 d_max)
};

// The drum mantle the bed touches.
enum class DrumWall {
  kAnalyticCylinder,  // smooth cylinder of radius R, particle–wall friction contact.friction_wall
  kRoughParticles,    // seed 001's rough wall: a layer of fixed beads lining the mantle, turning with it,
                      // contacts as particle–particle with the wall friction (dem/sphere_wall.hpp)
};

struct Species {
  double diameter_m = 0.004;
  double density_kg_m3 = 2500.0;
  double number_fraction = 1.0;  // share of the particle count (two species: the rest is species 1)
};

struct DrumScene {
  std::string source_name = "drum";
  double radius_m = 0.05;             // inner radius R
  double length_m = 0.01;             // axial length L
  AxialBoundary axial = AxialBoundary::kFrictionlessWalls;
  DrumWall wall = DrumWall::kAnalyticCylinder;
  double wall_bead_diameter_m = 0.0;  // rough wall: bead diameter; 0 = number-weighted mean species diameter
  double angular_velocity_rad_s = 0.0;  // ω (from rpm or froude = ω²R/g)
  double fill_fraction = 0.35;        // bed volume (incl. voids) / drum volume
  double bed_solid_fraction = 0.6;    // solids in the bed volume, to turn the fill into a particle count
  std::vector<Species> species;       // one or two
  dem::ContactLaw law = dem::kLinearSpringDashpotLaw;
  double normal_stiffness_n_m = 2000.0;  // linear k_n
  double tangential_ratio = 2.0 / 7.0;   // linear k_t/k_n
  double youngs_modulus_pa = 5e7;        // Hertz
  double poisson_ratio = 0.25;
  double restitution = 0.5;
  double friction_particle = 0.5;        // particle–particle μ
  double friction_wall = 0.8;            // particle–drum μ
  double rolling_friction = 0.0;         // μ_r (0: the rolling-resistance effect is off)
  dem::Integrator integrator = dem::Integrator::kGear5;
  double contact_steps = 15.0;           // N_c (seed: at least 10)
  double dt_s = 0.0;                     // 0: t_c/N_c
  double settle_max_s = 1.0;             // settling stops at rest or after this time
  double rest_energy_ratio = 1e-5;       // at rest: KE < ratio · N m g d (mean particle, one diameter)
  double rotate_s = 2.0;                 // rotation time after settling
  double measure_from_s = 1.0;           // measurements averaged over [measure_from_s, rotate_s] of rotation
  double sample_every_s = 0.02;
  int threads = 1;
  std::string output_directory;          // empty: no files
  bool energy_csv = true;                // kinetic-energy history (seed Fig. 4.4)
  bool particles_csv = true;             // final particle positions, velocities, species
};

inline double froude_number(const DrumScene& s) {
  return s.angular_velocity_rad_s * s.angular_velocity_rad_s * s.radius_m / kStandardGravity_m_s2;
}
// Rough wall: the bead diameter used (wall_bead_diameter_m, or the mean species diameter); 0 otherwise.
double bead_diameter_m(const DrumScene& s);
// Radius of the space free for the bed: R, or R − d_b inside a bead lining (the bead tips). Packing,
// fill and the measurements use it; the Froude number keeps the mantle radius R.
inline double free_radius_m(const DrumScene& s) { return s.radius_m - bead_diameter_m(s); }

inline double omega_from_froude(double froude, double radius_m) {
  return std::sqrt(froude * kStandardGravity_m_s2 / radius_m);
}

// Parses a drum scene; errors are scene::SceneError "file: key: problem" (libspread/io/scene/scene.hpp).
// `overrides` are "section.key=value" assignments applied before validation (as `--set` in the CLI).
DrumScene load_drum_scene(const std::string& path, const std::vector<std::string>& overrides = {});
DrumScene parse_drum_scene(const std::string& toml_text, const std::string& source_name,
                           const std::vector<std::string>& overrides = {});
// True when the file has a [drum] table (used by `spread simulate` to route drum scenes here).
bool is_drum_scene_file(const std::string& path);
// Checks the values (each key's range, then the relations between keys); throws scene::SceneError
// "source: key: problem".
void validate(const DrumScene& s);

}  // namespace spread::drum
