#include "libspread/physics/launch/analytic_launch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

#include "libspread/core/sieve_analysis.hpp"
#include "libspread/core/unit_uniform.hpp"
#include "libspread/physics/launch/patterson_reece.hpp"

namespace spread::launch {
namespace {

// Roberts' R_d sequence: α_i = φ_d^{−i}, φ_d the real root > 1 of x^{d+1} = x + 1.
std::array<double, 4> r4_steps() {
  double phi = 1.2;
  for (int i = 0; i < 60; ++i) phi -= (std::pow(phi, 5) - phi - 1.0) / (5.0 * std::pow(phi, 4) - 1.0);
  return {1.0 / phi, 1.0 / (phi * phi), 1.0 / (phi * phi * phi), 1.0 / (phi * phi * phi * phi)};
}

double fraction(double x) { return x - std::floor(x); }

}  // namespace

double inverse_normal_cdf(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("inverse_normal_cdf: p must be in (0, 1)");
  // Acklam (2003) coefficients.
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01,  -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  constexpr double p_low = 0.02425;
  double x = 0.0;
  if (p < p_low) {
    const double q = std::sqrt(-2.0 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  } else if (p <= 1.0 - p_low) {
    const double q = p - 0.5;
    const double r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  } else {
    const double q = std::sqrt(-2.0 * std::log(1.0 - p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  // One Halley step on Φ(x) − p, Φ via erfc.
  const double e = 0.5 * std::erfc(-x / std::sqrt(2.0)) - p;
  const double u = e * std::sqrt(2.0 * kPi) * std::exp(0.5 * x * x);
  return x - u / (1.0 + 0.5 * x * u);
}

std::vector<tables::LaunchSample> analytic_launch_samples(const scene::Machine& machine,
                                                          const tables::Material& material, double rpm,
                                                          const scene::Inlet& inlet, int sample_count,
                                                          std::uint64_t seed, const AnalyticLaunchOptions& options) {
  auto fail = [](const std::string& problem) { throw std::invalid_argument("analytic launch model: " + problem); };
  if (sample_count < 1) fail("sample_count must be >= 1");
  if (!(rpm > 0.0) || !std::isfinite(rpm)) fail("rpm must be > 0, got " + std::to_string(rpm));
  if (machine.vane_count < 1) fail("needs vanes (machine.vane_count >= 1)");
  if (machine.vane_pitch_rad != 0.0) fail("radial vanes only (machine.vane_pitch_rad must be 0)");
  if (!(material.diameter_mean_m > 0.0) || !(material.diameter_sd_m >= 0.0) || !(material.density_kg_m3 > 0.0)) {
    fail("material " + material.name + ": needs diameter_mean_m > 0, diameter_sd_m >= 0, density_kg_m3 > 0");
  }
  const double radius_m = machine.disc_radius_m;
  const double exit_radius_m = machine.vane_end_radius_m > 0.0 ? machine.vane_end_radius_m : radius_m;
  const double omega = rpm * 2.0 * kPi / 60.0;
  const double rim_speed = omega * radius_m;
  const double sense = machine.rotation_sense >= 0 ? 1.0 : -1.0;
  const double g = options.gravity_m_s2;
  const VaneMotion motion{omega, material.friction_wall, machine.cone_angle_rad, g};
  const double vane_period_s = 2.0 * kPi / (omega * machine.vane_count);
  const double fall_time_s = std::sqrt(2.0 * inlet.drop_height_m / g);

  // Lognormal with mean m and sd s: σ² = ln(1 + s²/m²), μ = ln m − σ²/2.
  const double ratio = material.diameter_sd_m / material.diameter_mean_m;
  const double sigma_ln = std::sqrt(std::log1p(ratio * ratio));
  const double mu_ln = std::log(material.diameter_mean_m) - 0.5 * sigma_ln * sigma_ln;
  // A sieve material: its number distribution's inverse at the same quasi-random coordinate.
  std::optional<SieveNumberDistribution> sieve;
  if (!material.sieve.empty()) {
    const std::string problem = sieve_problem(material.sieve);
    if (!problem.empty()) fail("material " + material.name + ": " + problem);
    sieve.emplace(material.sieve);
  }

  std::mt19937_64 rng(seed);
  std::array<double, 4> shift{};
  for (double& s : shift) s = unit_uniform(rng());
  const std::array<double, 4> step = r4_steps();

  std::vector<tables::LaunchSample> samples;
  samples.reserve(static_cast<std::size_t>(sample_count));
  for (int k = 0; k < sample_count; ++k) {
    std::array<double, 4> u{};
    for (std::size_t i = 0; i < 4; ++i) u[i] = fraction(shift[i] + static_cast<double>(k + 1) * step[i]);

    const double feed_rho = inlet.radius_m * std::sqrt(u[0]);
    const double feed_phi = 2.0 * kPi * u[1];
    const double feed_x = inlet.offset_m * std::cos(inlet.angle_rad) + feed_rho * std::cos(feed_phi);
    const double feed_y = inlet.offset_m * std::sin(inlet.angle_rad) + feed_rho * std::sin(feed_phi);
    const double feed_radius = std::hypot(feed_x, feed_y);
    const double feed_angle = std::atan2(feed_y, feed_x);

    const double diameter = sieve ? sieve->diameter_m(u[2])
                                  : std::exp(mu_ln + sigma_ln * inverse_normal_cdf(std::clamp(u[2], 1e-12, 1.0 - 1e-12)));
    const double mass = material.density_kg_m3 * kPi * diameter * diameter * diameter / 6.0;

    const double r0 = std::max(feed_radius, machine.vane_start_radius_m);
    VaneExit exit{};
    try {
      exit = vane_exit(motion, r0, exit_radius_m);
    } catch (const std::invalid_argument& e) {
      fail(std::string(e.what()) + " (material " + material.name + ", " + std::to_string(rpm) + " rpm)");
    }
    const double launch_angle = feed_angle + sense * exit.turned_angle_rad;
    const double cos_t = std::cos(launch_angle);
    const double sin_t = std::sin(launch_angle);
    // e_r = (cos, sin, 0), e_θ = (−sin, cos, 0); the rim moves along sense · e_θ.
    const double v_r = exit.radial_speed_m_s;
    const double v_t = sense * exit.tangential_speed_m_s;
    const double vx = v_r * cos_t - v_t * sin_t;
    const double vy = v_r * sin_t + v_t * cos_t;
    const double vz = exit.vertical_speed_m_s;

    double wx = 0.0, wy = 0.0, wz = sense * omega;  // turning with the vane
    if (options.spin == scene::SpinModel::kRolling) {
      // Rolling along the vane face: ω_rel = (n × v_rel)/a with the face normal n = sense·e_θ and
      // v_rel = ṡ (cos α e_r + sin α e_z) along the generatrix; e_θ × e_r = −e_z, e_θ × e_z = e_r.
      const double roll = sense * exit.speed_along_vane_m_s / (0.5 * diameter);
      const double cos_a = std::cos(machine.cone_angle_rad), sin_a = std::sin(machine.cone_angle_rad);
      wx += roll * sin_a * cos_t;
      wy += roll * sin_a * sin_t;
      wz -= roll * cos_a;
    }

    tables::LaunchSample s{};
    s.x_m = static_cast<float>(exit_radius_m * cos_t);
    s.y_m = static_cast<float>(exit_radius_m * sin_t);
    s.z_m = static_cast<float>(0.5 * diameter);
    s.t_s = static_cast<float>(fall_time_s + u[3] * vane_period_s + exit.time_s);
    s.vx_norm = static_cast<float>(vx / rim_speed);
    s.vy_norm = static_cast<float>(vy / rim_speed);
    s.vz_norm = static_cast<float>(vz / rim_speed);
    s.wx_norm = static_cast<float>(wx / omega);
    s.wy_norm = static_cast<float>(wy / omega);
    s.wz_norm = static_cast<float>(wz / omega);
    s.diameter_m = static_cast<float>(diameter);
    s.mass_kg = static_cast<float>(mass);
    samples.push_back(s);
  }
  return samples;
}

}  // namespace spread::launch
