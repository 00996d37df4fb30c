#pragma once
// The keys of a drum scene's sections, one row each (libspread/io/scene/scene_key.hpp): [drum], [contact],
// [[species]], [numerics], [output]. The contact section's material quantities take the material schema's
// names and ranges; the drum's first spellings are their aliases. docs/drum.md's scene block names every
// row (DrumScene.DocsNameEveryKey). The disc speed (rpm or froude, one of the two) is read beside the rows.
#include <array>

#include "libspread/physics/drum/drum_scene.hpp"
#include "libspread/io/scene/scene_key.hpp"

namespace spread::drum {

using scene::ChoiceName;
using scene::Key;
using scene::kNonNegative;
using scene::kPositive;
using scene::material_key;

inline constexpr std::array<ChoiceName, 3> kAxialNames{
    {{"frictionless_walls", static_cast<int>(AxialBoundary::kFrictionlessWalls)},
     {"walls", static_cast<int>(AxialBoundary::kWalls)},
     {"periodic", static_cast<int>(AxialBoundary::kPeriodic)}}};
inline constexpr std::array<ChoiceName, 2> kWallNames{
    {{"analytic_cylinder", static_cast<int>(DrumWall::kAnalyticCylinder)},
     {"rough_particles", static_cast<int>(DrumWall::kRoughParticles)}}};
// "hertz" is the older spelling of "hertz_thornton" (Hertz normal, Thornton tangential), kept as an alias.
inline constexpr int kLinearLaw = 0, kHertzLaw = 1;
inline constexpr std::array<ChoiceName, 3> kContactModelNames{
    {{"linear", kLinearLaw}, {"hertz_thornton", kHertzLaw}, {"hertz", kHertzLaw}}};
inline constexpr std::array<ChoiceName, 5> kIntegratorNames{
    {{"symplectic_euler", static_cast<int>(dem::Integrator::kSymplecticEuler)},
     {"velocity_verlet", static_cast<int>(dem::Integrator::kVelocityVerlet)},
     {"gear4", static_cast<int>(dem::Integrator::kGear4)},
     {"gear5", static_cast<int>(dem::Integrator::kGear5)},
     {"gear6", static_cast<int>(dem::Integrator::kGear6)}}};

inline constexpr scene::Choice<DrumScene> kContactModel{
    kContactModelNames, [](const DrumScene& s) { return s.law == dem::kHertzThorntonLaw ? kHertzLaw : kLinearLaw; },
    [](DrumScene& s, int v) { s.law = v == kHertzLaw ? dem::kHertzThorntonLaw : dem::kLinearSpringDashpotLaw; }};

inline constexpr std::array<Key<DrumScene>, 7> kDrumKeys{{
    {"radius_m", &DrumScene::radius_m, "m", kPositive, 0, "inner radius R"},
    {"length_m", &DrumScene::length_m, "m", kPositive, 0, "axial length L"},
    {"axial", scene::choice<&DrumScene::axial>(kAxialNames), "–", scene::kAnyValue, 0, "the drum's axial ends"},
    {"wall", scene::choice<&DrumScene::wall>(kWallNames), "–", scene::kAnyValue, 0, "the drum mantle"},
    {"wall_bead_diameter_m", &DrumScene::wall_bead_diameter_m, "m", kNonNegative, 0,
     "rough wall: bead diameter (0: the mean species diameter)"},
    {"fill_fraction", &DrumScene::fill_fraction, "–", {0.0, true, 0.95, true}, 0,
     "bed volume (incl. voids) / drum volume"},
    {"bed_solid_fraction", &DrumScene::bed_solid_fraction, "–", {0.1, true, 0.74, false}, 0,
     "solids in the bed volume"},
}};

inline constexpr std::array<Key<DrumScene>, 9> kContactKeys{{
    {"model", kContactModel, "–", scene::kAnyValue, 0, "contact law"},
    {"normal_stiffness_n_m", &DrumScene::normal_stiffness_n_m, "N/m", kPositive, 0, "linear law: k_n"},
    {"tangential_ratio", &DrumScene::tangential_ratio, "–", kNonNegative, 0, "linear law: k_t/k_n"},
    material_key("youngs_modulus_pa", &DrumScene::youngs_modulus_pa, "Hertz law: Young's modulus", "young_modulus_pa"),
    material_key("poisson_ratio", &DrumScene::poisson_ratio, "Hertz law: Poisson's ratio"),
    material_key("restitution", &DrumScene::restitution, "coefficient of restitution (normal)"),
    material_key("friction_particle", &DrumScene::friction_particle, "particle–particle sliding friction", "friction"),
    material_key("friction_wall", &DrumScene::friction_wall, "particle–drum (mantle or bead) sliding friction",
                 "wall_friction"),
    material_key("rolling_friction", &DrumScene::rolling_friction, "rolling resistance coefficient μ_r (0: off)"),
}};

inline constexpr std::array<Key<Species>, 3> kSpeciesKeys{{
    {"diameter_m", &Species::diameter_m, "m", kPositive, 0, "particle diameter"},
    material_key("density_kg_m3", &Species::density_kg_m3, "particle density"),
    {"number_fraction", &Species::number_fraction, "–", {0.0, true, 1.0, false}, 0, "share of the particle count"},
}};

inline constexpr std::array<Key<DrumScene>, 9> kNumericsKeys{{
    {"integrator", scene::choice<&DrumScene::integrator>(kIntegratorNames), "–", scene::kAnyValue, 0,
     "integrator"},
    {"contact_steps", &DrumScene::contact_steps, "–", {5.0, false, scene::kInfinity, true}, 0,
     "N_c, steps per contact time (the seed resolves a contact in >= 10)"},
    {"dt_s", &DrumScene::dt_s, "s", kNonNegative, 0, "time step (0: t_c/N_c)"},
    {"settle_max_s", &DrumScene::settle_max_s, "s", kPositive, 0, "settling stops at rest or after this time"},
    {"rest_energy_ratio", &DrumScene::rest_energy_ratio, "–", kPositive, 0, "at rest: KE < ratio · N m g d"},
    {"rotate_s", &DrumScene::rotate_s, "s", kNonNegative, 0, "rotation time after settling"},
    {"measure_from_s", &DrumScene::measure_from_s, "s", kNonNegative, 0, "measurements from this time of rotation on"},
    {"sample_every_s", &DrumScene::sample_every_s, "s", kPositive, 0, "sampling interval"},
    {"threads", &DrumScene::threads, "–", {1.0, false, scene::kInfinity, true}, 0, "worker threads"},
}};

inline constexpr std::array<Key<DrumScene>, 3> kOutputKeys{{
    {"directory", &DrumScene::output_directory, "–", scene::kAnyValue, 0, "where files go (empty: no files)"},
    {"energy_csv", &DrumScene::energy_csv, "–", scene::kAnyValue, 0, "kinetic-energy history"},
    {"particles_csv", &DrumScene::particles_csv, "–", scene::kAnyValue, 0, "final particle states"},
}};

}  // namespace spread::drum
