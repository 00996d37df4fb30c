#pragma once
// Forward model of a pattern calibration (docs/field-calibration.md, step 3): material parameters →
// transverse distribution over a tray test's trays, through the analytic Patterson–Reece launch model
// (libspread/physics/launch), granule flight (libspread/physics/flight) and the machine's two discs.
//
// The three parameters a technician can fit from one tray test:
//   friction_wall μ            sliding friction on disc and vanes (Material::friction_wall): sets the
//                              launch speed and direction (exit angle from the tangent atan(√(1+μ²)−μ)).
//   drag_diameter_factor k     the granule meets the air as a sphere k times its sieve diameter at the
//                              SAME mass (non-spherical, rough or dusty granules drag more than their
//                              sieve size says): flown with diameter k·d and density ρ/k³, so drag
//                              deceleration grows ~k² and the throw shortens.
//   launch_angle_offset δ      the whole launch state turned about the disc axis by δ in the disc's
//                              direction of rotation (δ > 0: the granules leave later): what a worn vane,
//                              a moved drop point or a vane-entry delay the model lacks do to the pattern.
// In the table these become an "aerodynamic-equivalent" material: diameters ×k, density ÷k³ (granule
// mass unchanged), friction μ; the offset is applied to the stored launch samples.
//
// Rows built by the DEM (source "dem") have no friction to refit: the DEM's launches come from its contact
// laws, not from a closed-form μ. For them the model starts from the table's own launch samples (the row
// nearest the tray test's rpm, its normalised samples scaled to that rpm) and fits a correction of the
// launch state that a worn vane, a different material batch or a drop-point setting would cause:
//   launch_speed_factor s          every launch velocity × s (direction kept): the throw's length.
//   launch_angle_offset δ          as above: the throw's direction about the disc axis.
//   launch_elevation_offset ε      each launch velocity turned upwards by ε in its own vertical plane
//                                  (horizontal direction and speed kept): the throw's length through its
//                                  flight time, separately from the speed.
// plus the drag diameter factor k (diameters of the samples ×k, density ÷k³). The calibrated rows are the
// transformed DEM samples of every row (calibrated_table.hpp): predict, the C API and the landing grid
// read them as any DEM row.
//
// Smoothness — the fit differentiates this model numerically, so it must be a smooth, deterministic
// function of the parameters: the launch samples are a fixed low-discrepancy set (same seed, same
// count: sample k keeps its feed point and diameter whatever the parameters); flights use fixed-step
// RK4 with the exact ground crossing (an adaptive step controller would make the landing points jump
// when it changes its step sequence); and each landing spreads its mass over the trays with a Gaussian
// kernel (sd kernel_sigma_m) instead of dropping it into one tray, so a landing crossing a tray edge
// moves mass continuously. The kernel is also a fair picture of the real scatter of a granule stream
// (bounce, shape) that the model's few hundred trajectories do not have.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "libspread/physics/flight/flight.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace spread::calibration {

struct PatternParameters {
  double friction_wall = 0.4;            // μ, dimensionless, [0, 2]
  double drag_diameter_factor = 1.0;     // k, dimensionless, [0.2, 5]
  double launch_angle_offset_rad = 0.0;  // δ, rad, |δ| <= π/2
  double launch_speed_factor = 1.0;      // s, dimensionless, [0.5, 2]
  double launch_elevation_offset_rad = 0.0;  // ε, rad, |ε| <= π/6
};

// The parameters in a fixed order (fit masks, correlation matrices, acceptance ranges).
inline constexpr std::size_t kPatternParameterCount = 5;
enum PatternParameterIndex : std::size_t { kFriction = 0, kDragDiameter, kAngleOffset, kLaunchSpeed, kElevationOffset };
std::array<double, kPatternParameterCount> as_array(const PatternParameters& parameters);
PatternParameters from_array(const std::array<double, kPatternParameterCount>& values);

// Everything fixed during a fit: the machine and inlet of the table's scene, the material as stored,
// the disc speed, the air.
struct PatternSetup {
  scene::Machine machine;             // full geometry (vanes) for the analytic launch model
  scene::Inlet inlet;
  scene::SpinModel spin_model = scene::SpinModel::kRolling;
  std::uint64_t seed = 1;             // of the launch samples (the table scene's numerics.seed)
  // Non-empty: the launch samples of the material's table row nearest `rpm` (a DEM row), corrected by the
  // parameters instead of the analytic model; `table_row_rpm` is that row's rpm.
  std::vector<tables::LaunchSample> table_samples;
  double table_row_rpm = 0.0;
  tables::Material material;          // as stored in the table
  double rpm = 0.0;                   // r/min
  double disc_height_m = 0.0;         // disc above the ground (the table's machine row)
  flight::Air air;                    // still air
  flight::EffectSet effects = flight::kDrag | flight::kMagnus | flight::kSpinDecay;
};

// From a table's contents: the scene of the material's run nearest in rpm (scene_of_run.hpp), the
// table's material row and disc height. When that run is not analytic (a DEM row) and `analytic_model` is
// false, its launch samples go into `table_samples`. Throws std::invalid_argument naming an unknown material (and
// listing the known ones), a material without runs or an rpm outside the range of the material's runs;
// scene::SceneError for an unreadable stored scene.
PatternSetup pattern_setup_from_table(const tables::TableContents& contents, const std::string& material,
                                      double rpm, bool analytic_model = false);

// The launch samples `base` (table record convention) corrected by s, δ, ε and k (see above); friction is
// not used. `rotation_sense` of the machine (δ > 0 is later release in the sense of rotation).
std::vector<tables::LaunchSample> corrected_launch_samples(std::vector<tables::LaunchSample> base,
                                                           const PatternParameters& parameters, int rotation_sense);

// The parameters a stored material stands for: μ = friction_wall, k = 1, δ = 0.
PatternParameters parameters_of(const tables::Material& material);

// The aerodynamic-equivalent material of `base` with `parameters` (see above), renamed.
tables::Material calibrated_material(const tables::Material& base, const PatternParameters& parameters,
                                     const std::string& name);

// Launch samples of the calibrated material at `rpm`: the analytic model's (or, with table_samples, those
// thinned by a whole stride to at most `sample_count`), corrected by corrected_launch_samples(). Table
// record convention (normalised by ωR, ω).
// Throws std::invalid_argument when the parameters are outside their ranges or the launch model cannot
// run them.
std::vector<tables::LaunchSample> calibrated_launch_samples(const PatternSetup& setup,
                                                            const PatternParameters& parameters, double rpm,
                                                            int sample_count);

// Fixed-step RK4 at 2 ms with the exact ground crossing (predict::fixed_step_rk4_settings): smooth in the
// launch state (see above), and within a few mm of the adaptive reference over a 1 s flight.
flight::Settings pattern_flight_settings(double dt_s = 2e-3);

struct PatternModelOptions {
  int sample_count = 1024;      // launch samples (trajectories) per evaluation
  double kernel_sigma_m = 0.0;  // landing kernel sd; 0 = half the tray width
  flight::Settings flight = pattern_flight_settings();
  int threads = 1;              // flight threads (results identical for any count)
};

class PatternModel {
 public:
  // `trays`: the layout to predict on (the tray test's symmetric layout). Machine frame: disc_count and
  // disc_spacing_m of the scene's machine.
  PatternModel(PatternSetup setup, metrics::TrayLayout trays, PatternModelOptions options = {});

  // Fraction of the machine's discharged mass in each tray (both discs; mass landing outside the layout
  // or not landing is not in any tray). Throws std::invalid_argument for parameters outside their ranges.
  std::vector<double> tray_fractions(const PatternParameters& parameters) const;

  const PatternSetup& setup() const { return setup_; }
  const metrics::TrayLayout& trays() const { return trays_; }
  const PatternModelOptions& options() const { return options_; }

 private:
  PatternSetup setup_;
  metrics::TrayLayout trays_;
  PatternModelOptions options_;
};

// Ranges of the parameters (std::invalid_argument naming the parameter when outside).
void check_parameters(const PatternParameters& parameters);

}  // namespace spread::calibration
