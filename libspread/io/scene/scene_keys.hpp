#pragma once
// The keys of the spreader scene's sections, one row each (scene_key.hpp): [machine], [inlet],
// [simulate], [air], [numerics], [sweep], [outputs], [field]. The materials' rows are the material schema
// (libspread/io/tables/material_schema.hpp), [effects] is the effect registry. docs/scene-format.md lists
// the same rows in the same order (ParameterSchema.DocsListEverySectionKey).
#include <array>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/scene/scene_key.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::scene {

// The spellings of the enumerated keys; to_string() gives the first of each value.
inline constexpr std::array<ChoiceName, 3> kDiscModelNames{{{"analytic", static_cast<int>(DiscModel::kAnalytic)},
                                                            {"mesh", static_cast<int>(DiscModel::kMesh)},
                                                            {"stl", static_cast<int>(DiscModel::kStl)}}};
inline constexpr std::array<ChoiceName, 2> kIntegratorNames{
    {{"symplectic_euler", static_cast<int>(Integrator::kSymplecticEuler)},
     {"velocity_verlet", static_cast<int>(Integrator::kVelocityVerlet)}}};
inline constexpr std::array<ChoiceName, 3> kContactModelNames{
    {{"hertz_thornton", static_cast<int>(ContactModel::kHertzThornton)},
     {"hertz_mindlin", static_cast<int>(ContactModel::kHertzThornton)},  // the older name, kept as an alias
     {"linear", static_cast<int>(ContactModel::kLinear)}}};
inline constexpr std::array<ChoiceName, 2> kFlightSchemeNames{
    {{"dopri5", static_cast<int>(FlightScheme::kDopri5)}, {"rk4", static_cast<int>(FlightScheme::kRk4)}}};
inline constexpr std::array<ChoiceName, 2> kLaunchSourceNames{
    {{"analytic", static_cast<int>(LaunchSource::kAnalytic)}, {"dem", static_cast<int>(LaunchSource::kDem)}}};
inline constexpr std::array<ChoiceName, 2> kSpinModelNames{
    {{"rolling", static_cast<int>(SpinModel::kRolling)}, {"sliding", static_cast<int>(SpinModel::kSliding)}}};

namespace scene_keys_detail {
// Upper bounds: the table file's plausibility limits, so that a scene the builder accepts always gives a
// table the reader and the predictor accept.
using L = tables::PlausibleLimits;
}  // namespace scene_keys_detail

inline constexpr std::array<Key<Machine>, 17> kMachineKeys{{
    {"name", &Machine::name, "–", kAnyValue, 0, "the machine's name in tables and reports"},
    {"disc_radius_m", &Machine::disc_radius_m, "m", positive_at_most(scene_keys_detail::L::kMaxDiscRadius_m), 0,
     "R, horizontal rim radius"},
    {"disc_height_m", &Machine::disc_height_m, "m", positive_at_most(scene_keys_detail::L::kMaxDiscHeight_m), 0,
     "rim above ground"},
    {"disc_count", &Machine::disc_count, "–", closed(1, 2), 0, "number of discs"},
    {"disc_spacing_m", &Machine::disc_spacing_m, "m", closed(0.0, scene_keys_detail::L::kMaxDiscSpacing_m), 0,
     "centre to centre, lateral"},
    {"rotation_sense", &Machine::rotation_sense, "–", closed(-1, 1), 0,
     "+1: left disc counter-clockwise seen from above (right disc mirrored); −1 clockwise"},
    {"cone_angle_rad", &Machine::cone_angle_rad, "rad", closed(0.0, 1.2), 0, "surface rises outward at this angle"},
    {"vane_count", &Machine::vane_count, "–", closed(0, 64), 0, "vanes per disc"},
    {"vane_start_radius_m", &Machine::vane_start_radius_m, "m", kNonNegative, 0, "inner vane end"},
    {"vane_end_radius_m", &Machine::vane_end_radius_m, "m", kNonNegative, 0, "outer vane end"},
    {"vane_height_m", &Machine::vane_height_m, "m", kNonNegative, 0, "vane height"},
    {"vane_pitch_rad", &Machine::vane_pitch_rad, "rad", closed(-1.2, 1.2), 0, "0 = radial"},
    {"disc_model", choice<&Machine::disc_model>(kDiscModelNames), "–", kAnyValue, 0, "the disc's walls"},
    {"mesh_size_m", &Machine::mesh_size_m, "m", kNonNegative, 0, "ξ, mesh size for `\"mesh\"`", {},
     RunInput::kAlways, [](const Machine& m) { return m.disc_model == DiscModel::kMesh; }},
    {"stl_path", &Machine::stl_path, "–", kAnyValue, 0, "`\"stl\"` only (required there, an error otherwise)", {},
     RunInput::kAlways, [](const Machine& m) { return m.disc_model == DiscModel::kStl; }},
    {"stl_scale", &Machine::stl_scale, "–", kPositive, 0, "STL coordinates × `stl_scale` = metres", {},
     RunInput::kAlways, [](const Machine& m) { return m.disc_model == DiscModel::kStl; }},
    {"rpm", &Machine::rpm, "rev/min", positive_at_most(scene_keys_detail::L::kMaxRpm), 0,
     "disc speed of a `simulate` run", {}, RunInput::kNone},
}};

inline constexpr std::array<Key<Inlet>, 6> kInletKeys{{
    {"radius_m", &Inlet::radius_m, "m", kPositive, 0, "inlet circle radius"},
    {"offset_m", &Inlet::offset_m, "m", kNonNegative, 0, "inlet centre from the disc centre"},
    {"angle_rad", &Inlet::angle_rad, "rad", kAnyValue, 0, "angle of the inlet centre from +x (counter-clockwise)"},
    {"drop_height_m", &Inlet::drop_height_m, "m", kNonNegative, 0, "release height above the disc surface"},
    {"mass_flow_kg_s", &Inlet::mass_flow_kg_s, "kg/s", kPositive, 0, "feed rate per disc"},
    {"validated_turn_deg", &Inlet::validated_turn_deg, "deg", kAnyValue, 0,
     "drop-point turns [low, high] checked against DEM rows (tools/drop_point_check.py)", {}, RunInput::kNone},
}};

inline constexpr std::array<Key<Scene>, 1> kSimulateKeys{{
    {"material", &Scene::simulate_material, "–", kAnyValue, 0, "material of a `simulate` run", {}, RunInput::kNone},
}};

inline constexpr std::array<Key<Products>, 1> kProductsKeys{{
    {"file", &Products::file, "–", kAnyValue, 0, "product library (TOML)", {}, RunInput::kNone},
}};
// The `[[materials]]` key that names a product of the library (the values it gives are the run's inputs).
inline constexpr std::string_view kMaterialProductKey = "product";

inline constexpr std::array<Key<Air>, 3> kAirKeys{{
    {"density_kg_m3", &Air::density_kg_m3, "kg/m³", kNonNegative, 0, "air density"},
    {"viscosity_pa_s", &Air::viscosity_pa_s, "Pa·s", kPositive, 0, "dynamic viscosity"},
    {"wind_m_s", &Air::wind_m_s, "m/s", kAnyValue, effect::kWind, "horizontal wind [vx, vy]"},
}};

inline constexpr std::array<Key<Numerics>, 11> kNumericsKeys{{
    {"seed", &Numerics::seed, "–", kNonNegative, 0, "RNG seed"},
    {"duration_s", &Numerics::duration_s, "s", kPositive, 0, "simulated time of a DEM run", {}, RunInput::kDem},
    {"dt_contact_s", &Numerics::dt_contact_s, "s", kNonNegative, 0, "DEM step", {}, RunInput::kDem},
    {"steps_per_contact", &Numerics::steps_per_contact, "–", {1.0, false, kInfinity, true}, 0, "N_c", {},
     RunInput::kDem},
    {"integrator", choice<&Numerics::integrator>(kIntegratorNames), "–", kAnyValue, 0, "DEM integrator", {},
     RunInput::kDem},
    {"contact_model", choice<&Numerics::contact_model>(kContactModelNames), "–", kAnyValue, 0, "DEM contact law", {},
     RunInput::kDem},
    {"flight_scheme", choice<&Numerics::flight_scheme>(kFlightSchemeNames), "–", kAnyValue, 0, "flight integrator",
     {}, RunInput::kDem},
    {"flight_dt_s", &Numerics::flight_dt_s, "s", kPositive, 0, "RK4 step, or first trial step of dopri5", {},
     RunInput::kDem},
    {"flight_tolerance", &Numerics::flight_tolerance, "–", {0.0, true, 1.0, true}, 0, "dopri5 relative tolerance",
     {}, RunInput::kDem},
    {"collector_radius_m", &Numerics::collector_radius_m, "m", kNonNegative, 0, "launch-off cylinder radius", {},
     RunInput::kDem},
    {"threads", &Numerics::threads, "–", kNonNegative, 0, "worker threads", {}, RunInput::kNone},
}};

inline constexpr std::array<Key<Sweep>, 10> kSweepKeys{{
    {"rpm", &Sweep::rpm, "rev/min", positive_at_most(scene_keys_detail::L::kMaxRpm), 0, "table rows", {},
     RunInput::kNone},
    {"materials", &Sweep::materials, "–", kAnyValue, 0, "material names to build", {}, RunInput::kNone},
    {"source", choice<&Sweep::source>(kLaunchSourceNames), "–", kAnyValue, 0, "launch source"},
    {"samples_per_run", &Sweep::samples_per_run, "–", closed(1, 10'000'000), 0, "launch records per run"},
    {"output", &Sweep::output, "–", kAnyValue, 0, "table file", {}, RunInput::kNone},
    {"spin_model", choice<&Sweep::spin_model>(kSpinModelNames), "–", kAnyValue, 0, "analytic source: launch spin", {},
     RunInput::kAnalytic},
    {"batch_s", &Sweep::batch_s, "s", kPositive, 0, "DEM source: simulated time between convergence checks", {},
     RunInput::kDem},
    {"convergence_tolerance", &Sweep::convergence_tolerance, "–", kPositive, 0,
     "DEM source: stop when R̄ and ξ of the flown launches change by at most this (relative) between batches", {},
     RunInput::kDem},
    {"particle_budget", &Sweep::particle_budget, "–", kNonNegative, 0, "DEM source: stop after this many launches",
     {}, RunInput::kDem},
    {"working_width_ci_m", &Sweep::working_width_ci_m, "m", closed(0.0, 100.0), 0,
     "DEM source: besides converging, a run goes on until the 95 % interval of the working width predicted from "
     "its launches is within ± this",
     {}, RunInput::kDem},
}};

inline constexpr std::array<Key<Outputs>, 4> kOutputsKeys{{
    {"directory", &Outputs::directory, "–", kAnyValue, 0, "where output files go", {}, RunInput::kNone},
    {"vtk_every_steps", &Outputs::vtk_every_steps, "–", kNonNegative, 0, "VTK particle/wall files every N DEM steps",
     {}, RunInput::kNone},
    {"launch_csv", &Outputs::launch_csv, "–", kAnyValue, 0, "write the launch states as CSV", {}, RunInput::kNone},
    {"pattern_png", &Outputs::pattern_png, "–", kAnyValue, 0, "write the ground pattern PNG", {}, RunInput::kNone},
}};

inline constexpr std::array<Key<FieldRun>, 16> kFieldKeys{{
    {"boundary", &FieldRun::boundary, "–", kAnyValue, 0, "the field's boundary: GeoJSON Polygon", {}, RunInput::kNone},
    {"track", &FieldRun::track, "–", kAnyValue, 0, "a recorded track (CSV) driven instead of a plan", {},
     RunInput::kNone},
    {"material", &FieldRun::material, "–", kAnyValue, 0, "the material spread (\"\": the `[simulate]` material)", {},
     RunInput::kNone},
    {"rpm", &FieldRun::rpm, "rev/min", closed(0.0, scene_keys_detail::L::kMaxRpm), 0,
     "the field's disc speed (0: `machine.rpm`)", {}, RunInput::kNone},
    {"rate_kg_ha", &FieldRun::rate_kg_ha, "kg/ha", positive_at_most(3000.0), 0, "target rate", {}, RunInput::kNone},
    {"bout_width_m", &FieldRun::bout_width_m, "m", positive_at_most(100.0), 0,
     "bout width: the tramlines' spacing and the metered width", {}, RunInput::kNone},
    {"headland_passes", &FieldRun::headland_passes, "–", closed(0, 10), 0, "headland rounds of the plan", {},
     RunInput::kNone},
    {"reference_edge", &FieldRun::reference_edge, "–", closed(-1, 100000), 0,
     "tramlines parallel to this edge (vertex i to i + 1; −1: the longest)", {}, RunInput::kNone},
    {"wind_m_s", &FieldRun::wind_m_s, "m/s", closed(-30.0, 30.0), 0, "wind over the field [east, north]", {},
     RunInput::kNone},
    {"section_count", &FieldRun::section_count, "–", closed(1, 16), 0, "the machine's sections", {}, RunInput::kNone},
    {"section_control", &FieldRun::section_control, "–", kAnyValue, 0,
     "sections off over worked ground and beyond the boundary", {}, RunInput::kNone},
    {"border", &FieldRun::border, "–", kAnyValue, 0, "border mode on the outermost headland round", {},
     RunInput::kNone},
    {"speed_km_h", &FieldRun::speed_km_h, "km/h", positive_at_most(40.0), 0, "ground speed", {}, RunInput::kNone},
    {"look_ahead_s", &FieldRun::look_ahead_s, "s", closed(0.0, 10.0), 0, "section control's turn-on and turn-off time",
     {}, RunInput::kNone},
    {"gate_travel_s", &FieldRun::gate_travel_s, "s", closed(0.0, 10.0), 0,
     "a metering gate's time from shut to the field's flow", {}, RunInput::kNone},
    {"cell_m", &FieldRun::cell_m, "m", closed(0.1, 5.0), 0, "the rate grid's cell and the stamps' spacing", {},
     RunInput::kNone},
}};

}  // namespace spread::scene
