#include "libspread/io/tables/table_format.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "libspread/io/tables/material_schema.hpp"

namespace spread::tables {
namespace {

std::string show(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

// "" when `value` is finite and within [low, high] (an open end when the flag says so).
std::string range_problem(const std::string& field, double value, double low, bool low_open, double high,
                          bool high_open) {
  const bool ok = std::isfinite(value) && (low_open ? value > low : value >= low) &&
                  (high_open ? value < high : value <= high);
  if (ok) return {};
  std::string need = "must be finite";
  if (std::isfinite(low)) need += std::string(low_open ? " and > " : " and >= ") + show(low);
  if (std::isfinite(high)) need += std::string(high_open ? " and < " : " and <= ") + show(high);
  return field + " = " + show(value) + ": " + need;
}

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string non_negative(const std::string& field, double value) {
  return range_problem(field, value, 0.0, false, kInf, true);
}

}  // namespace

std::string machine_problem(const Machine& m) {
  using L = PlausibleLimits;
  for (const std::string& p : {range_problem("machine.disc_radius_m", m.disc_radius_m, 0.0, true, L::kMaxDiscRadius_m, false),
                        range_problem("machine.disc_height_m", m.disc_height_m, 0.0, false, L::kMaxDiscHeight_m, false),
                        range_problem("machine.disc_spacing_m", m.disc_spacing_m, 0.0, false, L::kMaxDiscSpacing_m, false),
                        range_problem("machine.cone_angle_rad", m.cone_angle_rad, -std::numbers::pi / 2, true,
                                      std::numbers::pi / 2, true)}) {
    if (!p.empty()) return p;
  }
  if (m.disc_count != 1 && m.disc_count != 2) return "machine.disc_count = " + std::to_string(m.disc_count) + ": must be 1 or 2";
  if (m.vane_count < 0 || m.vane_count > L::kMaxVaneCount) {
    return "machine.vane_count = " + std::to_string(m.vane_count) + ": must be >= 0 and <= " + std::to_string(L::kMaxVaneCount);
  }
  if (m.rotation_sense != 1 && m.rotation_sense != -1) {
    return "machine.rotation_sense = " + std::to_string(m.rotation_sense) + ": must be +1 or -1";
  }
  return {};
}

std::string material_problem(const Material& m) {
  const std::string at = "materials." + m.name + ".";
  for (const MaterialQuantity& q : kMaterialQuantities) {
    const Bounds& b = q.table_bounds;
    std::string p = range_problem(at + std::string(q.name), m.*q.member, b.low, b.low_open, b.high, b.high_open);
    if (!p.empty()) return p;
  }
  return {};
}

std::string run_values_problem(const Run& run) {
  std::string problem = run_record_problem(run);
  return problem.empty() ? samples_problem(run.samples) : problem;
}

std::string run_record_problem(const Run& run) {
  using L = PlausibleLimits;
  for (const std::string& p : {range_problem("rpm", run.rpm, 0.0, true, L::kMaxRpm, false),
                        non_negative("dt_contact_s", run.dt_contact_s),
                        non_negative("dt_flight_s", run.dt_flight_s)}) {
    if (!p.empty()) return p;
  }
  return {};
}

std::string samples_problem(std::span<const LaunchSample> samples) {
  using L = PlausibleLimits;
  static constexpr const char* kNames[kSampleFloats] = {"x_m", "y_m", "z_m", "t_s", "vx_norm", "vy_norm",
                                                        "vz_norm", "wx_norm", "wy_norm", "wz_norm",
                                                        "diameter_m", "mass_kg"};
  // Bound of |value| per field; diameter and mass are checked below.
  static constexpr double kBound[kSampleFloats] = {
      L::kMaxSamplePosition_m, L::kMaxSamplePosition_m, L::kMaxSamplePosition_m, L::kMaxSampleTime_s,
      L::kMaxVelocityPerRimSpeed, L::kMaxVelocityPerRimSpeed, L::kMaxVelocityPerRimSpeed,
      L::kMaxSpinPerDiscSpeed, L::kMaxSpinPerDiscSpeed, L::kMaxSpinPerDiscSpeed, kInf, kInf};
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const LaunchSample& s = samples[i];
    const float values[kSampleFloats] = {s.x_m, s.y_m, s.z_m, s.t_s, s.vx_norm, s.vy_norm, s.vz_norm,
                                         s.wx_norm, s.wy_norm, s.wz_norm, s.diameter_m, s.mass_kg};
    for (int f = 0; f < 10; ++f) {
      // Checked without building a string: tables hold millions of these.
      const double value = static_cast<double>(values[f]);
      if (std::abs(value) <= kBound[f]) continue;  // false for NaN
      return range_problem("sample " + std::to_string(i) + " " + kNames[f], value, -kBound[f], false, kBound[f], false);
    }
    const double d = static_cast<double>(s.diameter_m);
    if (!(d > 0.0 && d <= L::kMaxDiameter_m)) {
      return range_problem("sample " + std::to_string(i) + " diameter_m", d, 0.0, true, L::kMaxDiameter_m, false);
    }
    const double mass = static_cast<double>(s.mass_kg);
    if (!(mass > 0.0)) return range_problem("sample " + std::to_string(i) + " mass_kg", mass, 0.0, true, kInf, true);
    const double volume_m3 = std::numbers::pi / 6.0 * d * d * d;
    const double density = mass / volume_m3;
    if (!(density >= L::kMinSampleDensity_kg_m3 && density <= L::kMaxDensity_kg_m3)) {
      return "sample " + std::to_string(i) + " mass_kg = " + show(mass) + ": must be finite and give a density in [" +
             show(L::kMinSampleDensity_kg_m3) + ", " + show(L::kMaxDensity_kg_m3) + "] kg/m^3 for diameter_m " +
             show(d) + " (got " + show(density) + ")";
    }
  }
  return {};
}

}  // namespace spread::tables

namespace spread::tables {

std::optional<std::string> recorded_flight_effects(const Run& run) {
  static constexpr std::string_view kKey = "\"flight_effects\":\"";
  const std::size_t at = run.stats_json.find(kKey);
  if (at == std::string::npos) return std::nullopt;
  const std::size_t begin = at + kKey.size();
  const std::size_t end = run.stats_json.find('"', begin);
  if (end == std::string::npos) return std::nullopt;
  return run.stats_json.substr(begin, end - begin);
}

}  // namespace spread::tables
