#include "libspread/analysis/calibration/pattern_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include "libspread/analysis/calibration/scene_of_run.hpp"
#include "libspread/physics/launch/analytic_launch.hpp"
#include "libspread/analysis/predict/flight_defaults.hpp"
#include "libspread/analysis/predict/run_flight_effects.hpp"

namespace spread::calibration {
namespace {

double standard_normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

// Rotation about +z by `angle_rad` of a float triple (x, y) in place.
void turn(float& x, float& y, double cos_a, double sin_a) {
  const double x0 = x, y0 = y;
  x = static_cast<float>(x0 * cos_a - y0 * sin_a);
  y = static_cast<float>(x0 * sin_a + y0 * cos_a);
}

}  // namespace

flight::Settings pattern_flight_settings(double dt_s) { return predict::fixed_step_rk4_settings(dt_s); }

std::array<double, kPatternParameterCount> as_array(const PatternParameters& p) {
  return {p.friction_wall, p.drag_diameter_factor, p.launch_angle_offset_rad, p.launch_speed_factor,
          p.launch_elevation_offset_rad};
}

PatternParameters from_array(const std::array<double, kPatternParameterCount>& a) {
  return {a[kFriction], a[kDragDiameter], a[kAngleOffset], a[kLaunchSpeed], a[kElevationOffset]};
}

void check_parameters(const PatternParameters& p) {
  if (!std::isfinite(p.friction_wall) || p.friction_wall < 0.0 || p.friction_wall > 2.0) {
    throw std::invalid_argument("friction_wall must be in [0, 2], got " + std::to_string(p.friction_wall));
  }
  if (!std::isfinite(p.drag_diameter_factor) || p.drag_diameter_factor < 0.2 || p.drag_diameter_factor > 5.0) {
    throw std::invalid_argument("drag_diameter_factor must be in [0.2, 5], got " +
                                std::to_string(p.drag_diameter_factor));
  }
  if (!std::isfinite(p.launch_angle_offset_rad) || std::abs(p.launch_angle_offset_rad) > 0.5 * kPi) {
    throw std::invalid_argument("launch_angle_offset must be within ±90°, got " +
                                std::to_string(p.launch_angle_offset_rad * 180.0 / kPi) + "°");
  }
  if (!std::isfinite(p.launch_speed_factor) || p.launch_speed_factor < 0.5 || p.launch_speed_factor > 2.0) {
    throw std::invalid_argument("launch_speed_factor must be in [0.5, 2], got " + std::to_string(p.launch_speed_factor));
  }
  if (!std::isfinite(p.launch_elevation_offset_rad) || std::abs(p.launch_elevation_offset_rad) > kPi / 6.0) {
    throw std::invalid_argument("launch_elevation_offset must be within ±30°, got " +
                                std::to_string(p.launch_elevation_offset_rad * 180.0 / kPi) + "°");
  }
}

PatternSetup pattern_setup_from_table(const tables::TableContents& contents, const std::string& material,
                                      double rpm, bool analytic_model) {
  if (!std::isfinite(rpm) || !(rpm > 0.0)) throw std::invalid_argument("rpm must be > 0");
  const tables::Material* row = nullptr;
  std::string known;
  for (const tables::Material& m : contents.materials) {
    if (m.name == material) row = &m;
    known += (known.empty() ? "" : ", ") + ("'" + m.name + "'");
  }
  if (row == nullptr) throw std::invalid_argument("material '" + material + "' is not in the table; materials: " + known);
  const tables::Run* nearest = nullptr;
  for (const tables::Run& run : contents.runs) {
    if (run.material != material) continue;
    if (nearest == nullptr || std::abs(run.rpm - rpm) < std::abs(nearest->rpm - rpm)) nearest = &run;
  }
  if (nearest == nullptr) throw std::invalid_argument("material '" + material + "' has no runs in the table");
  // The fitted material is written as one row per rpm of the table: a tray test at a disc speed the
  // table does not cover would calibrate rows it says nothing about (and a mistyped --rpm fits a wrong
  // friction "converged").
  double low_rpm = nearest->rpm, high_rpm = nearest->rpm;
  for (const tables::Run& run : contents.runs) {
    if (run.material != material) continue;
    low_rpm = std::min(low_rpm, run.rpm);
    high_rpm = std::max(high_rpm, run.rpm);
  }
  constexpr double kRpmTolerance = 1e-6;  // relative: rows are stored as the scene's rpm list
  if (rpm < low_rpm * (1.0 - kRpmTolerance) || rpm > high_rpm * (1.0 + kRpmTolerance)) {
    char text[256];
    std::snprintf(text, sizeof text, "rpm %g is outside the table's range for '%s' (%g to %g rpm)", rpm,
                  material.c_str(), low_rpm, high_rpm);
    throw std::invalid_argument(text);
  }

  const scene::Scene scene = scene_of_run(*nearest);
  PatternSetup setup;
  setup.machine = scene.machine;
  // The table's machine row is what predictions use: keep the two consistent where they overlap.
  setup.machine.disc_count = contents.machine.disc_count;
  setup.machine.disc_spacing_m = contents.machine.disc_spacing_m;
  setup.machine.disc_radius_m = contents.machine.disc_radius_m;
  setup.machine.rotation_sense = contents.machine.rotation_sense;
  setup.machine.cone_angle_rad = contents.machine.cone_angle_rad;
  setup.inlet = scene.inlet;
  setup.spin_model = scene.sweep.spin_model;
  setup.seed = scene.numerics.seed;
  setup.material = *row;
  setup.rpm = rpm;
  setup.disc_height_m = contents.machine.disc_height_m;
  setup.air.density_kg_m3 = scene.air.density_kg_m3;
  setup.air.viscosity_pa_s = scene.air.viscosity_pa_s;
  // The effects the run's launches are flown with by predict (predict::run_flight_effects: the recorded
  // ones, or all of them for a run that records none).
  setup.effects = predict::run_flight_effects(*nearest) & ~static_cast<flight::EffectSet>(flight::kWind);  // still air
  if (!analytic_model && nearest->source != "analytic") {
    setup.table_samples = nearest->samples;
    setup.table_row_rpm = nearest->rpm;
  }
  return setup;
}

PatternParameters parameters_of(const tables::Material& material) {
  return {material.friction_wall, 1.0, 0.0};
}

tables::Material calibrated_material(const tables::Material& base, const PatternParameters& p,
                                     const std::string& name) {
  check_parameters(p);
  tables::Material m = base;
  m.name = name;
  m.friction_wall = p.friction_wall;
  const double k = p.drag_diameter_factor;
  m.diameter_mean_m = base.diameter_mean_m * k;
  m.diameter_sd_m = base.diameter_sd_m * k;
  m.density_kg_m3 = base.density_kg_m3 / (k * k * k);  // same granule mass at k times the diameter
  return m;
}

std::vector<tables::LaunchSample> corrected_launch_samples(std::vector<tables::LaunchSample> samples,
                                                           const PatternParameters& p, int rotation_sense) {
  check_parameters(p);
  // Later release = further round in the disc's sense of rotation; positions, velocities and spins are
  // all turned, so the launch state is the same one seen from a turned frame.
  const double angle = (rotation_sense >= 0 ? 1.0 : -1.0) * p.launch_angle_offset_rad;
  const double c = std::cos(angle), s = std::sin(angle);
  const double cos_e = std::cos(p.launch_elevation_offset_rad), sin_e = std::sin(p.launch_elevation_offset_rad);
  for (tables::LaunchSample& sample : samples) {
    if (angle != 0.0) {
      turn(sample.x_m, sample.y_m, c, s);
      turn(sample.vx_norm, sample.vy_norm, c, s);
      turn(sample.wx_norm, sample.wy_norm, c, s);
    }
    if (p.launch_elevation_offset_rad != 0.0) {
      // Turn (v_h, v_z) by ε in the velocity's own vertical plane: v_h' = v_h cos ε − v_z sin ε,
      // v_z' = v_h sin ε + v_z cos ε, the horizontal direction unchanged.
      const double vx = sample.vx_norm, vy = sample.vy_norm, vz = sample.vz_norm;
      const double vh = std::sqrt(vx * vx + vy * vy);
      if (vh > 0.0) {
        const double vh_new = vh * cos_e - vz * sin_e;
        sample.vx_norm = static_cast<float>(vx * vh_new / vh);
        sample.vy_norm = static_cast<float>(vy * vh_new / vh);
        sample.vz_norm = static_cast<float>(vh * sin_e + vz * cos_e);
      }
    }
    if (p.launch_speed_factor != 1.0) {
      sample.vx_norm = static_cast<float>(sample.vx_norm * p.launch_speed_factor);
      sample.vy_norm = static_cast<float>(sample.vy_norm * p.launch_speed_factor);
      sample.vz_norm = static_cast<float>(sample.vz_norm * p.launch_speed_factor);
    }
    sample.diameter_m = static_cast<float>(sample.diameter_m * p.drag_diameter_factor);
  }
  return samples;
}

std::vector<tables::LaunchSample> calibrated_launch_samples(const PatternSetup& setup, const PatternParameters& p,
                                                            double rpm, int sample_count) {
  if (!setup.table_samples.empty()) {
    // A whole stride keeps an even share of the row's granules (they are in the DEM's release order,
    // not sorted by any launch quantity).
    const std::size_t n = setup.table_samples.size();
    const std::size_t stride = sample_count > 0 ? (n + static_cast<std::size_t>(sample_count) - 1) /
                                                      static_cast<std::size_t>(sample_count)
                                                : 1;
    std::vector<tables::LaunchSample> thinned;
    thinned.reserve(n / stride + 1);
    for (std::size_t i = 0; i < n; i += stride) thinned.push_back(setup.table_samples[i]);
    return corrected_launch_samples(std::move(thinned), p, setup.machine.rotation_sense);
  }
  // The analytic model takes k through the material's diameters; the correction applies the rest.
  const tables::Material material = calibrated_material(setup.material, p, setup.material.name);
  launch::AnalyticLaunchOptions options;
  options.spin = setup.spin_model;
  PatternParameters rest = p;
  rest.drag_diameter_factor = 1.0;
  return corrected_launch_samples(
      launch::analytic_launch_samples(setup.machine, material, rpm, setup.inlet, sample_count, setup.seed, options), rest,
      setup.machine.rotation_sense);
}

PatternModel::PatternModel(PatternSetup setup, metrics::TrayLayout trays, PatternModelOptions options)
    : setup_(std::move(setup)), trays_(trays), options_(options) {
  if (trays_.tray_count < 1 || !(trays_.tray_width_m > 0.0)) throw std::invalid_argument("pattern model: empty tray layout");
  if (options_.sample_count < 1) throw std::invalid_argument("pattern model: sample_count must be >= 1");
  if (!(options_.kernel_sigma_m >= 0.0)) throw std::invalid_argument("pattern model: kernel_sigma_m must be >= 0");
  if (options_.kernel_sigma_m == 0.0) options_.kernel_sigma_m = 0.5 * trays_.tray_width_m;
  if (setup_.machine.disc_count != 1 && setup_.machine.disc_count != 2) {
    throw std::invalid_argument("pattern model: disc_count must be 1 or 2");
  }
}

std::vector<double> PatternModel::tray_fractions(const PatternParameters& parameters) const {
  check_parameters(parameters);
  const std::vector<tables::LaunchSample> samples =
      calibrated_launch_samples(setup_, parameters, setup_.rpm, options_.sample_count);
  const double omega_rad_s = setup_.rpm * 2.0 * kPi / 60.0;
  const double rim_speed_m_s = omega_rad_s * setup_.machine.disc_radius_m;
  const double density_kg_m3 = setup_.material.density_kg_m3 / std::pow(parameters.drag_diameter_factor, 3);

  const std::size_t n = samples.size();
  std::vector<flight::Granule> granules(n);
  std::vector<flight::State> launches(n);
  double total_mass_kg = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const tables::LaunchSample& s = samples[i];
    granules[i] = {s.diameter_m, density_kg_m3};
    launches[i].position_m = Vec3(s.x_m, s.y_m, s.z_m + setup_.disc_height_m);
    launches[i].velocity_m_s = rim_speed_m_s * Vec3(s.vx_norm, s.vy_norm, s.vz_norm);
    launches[i].spin_rad_s = omega_rad_s * Vec3(s.wx_norm, s.wy_norm, s.wz_norm);
    total_mass_kg += s.mass_kg;
  }
  std::vector<flight::Landing> landings(n);
  flight::fly_batch(granules, launches, 0.0, setup_.air, setup_.effects, options_.flight, landings, options_.threads);

  // In still air the right disc throws the mirror image of the left one (docs/design.md §3): fly once, land twice.
  const bool two_discs = setup_.machine.disc_count == 2;
  const double half_spacing_m = two_discs ? 0.5 * setup_.machine.disc_spacing_m : 0.0;
  const double discs = two_discs ? 2.0 : 1.0;
  const double sigma_m = options_.kernel_sigma_m;
  const double w = trays_.tray_width_m;
  const double left_edge_m = trays_.left_edge_m();
  const int count = trays_.tray_count;
  std::vector<double> fraction(static_cast<std::size_t>(count), 0.0);
  auto deposit = [&](double x_m, double weight) {
    // Trays within 6 σ hold all but 1e-9 of the kernel.
    const int first = std::max(0, static_cast<int>(std::floor((x_m - 6.0 * sigma_m - left_edge_m) / w)));
    const int last = std::min(count - 1, static_cast<int>(std::floor((x_m + 6.0 * sigma_m - left_edge_m) / w)));
    double below = standard_normal_cdf((left_edge_m + first * w - x_m) / sigma_m);
    for (int k = first; k <= last; ++k) {
      const double above = standard_normal_cdf((left_edge_m + (k + 1) * w - x_m) / sigma_m);
      fraction[static_cast<std::size_t>(k)] += weight * (above - below);
      below = above;
    }
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!landings[i].landed) continue;
    const double weight = samples[i].mass_kg / (discs * total_mass_kg);
    const double left_x_m = landings[i].state.position_m.x() - half_spacing_m;
    deposit(left_x_m, weight);
    if (two_discs) deposit(-left_x_m, weight);
  }
  return fraction;
}

}  // namespace spread::calibration
