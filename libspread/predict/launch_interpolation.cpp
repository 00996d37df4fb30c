#include "libspread/predict/launch_interpolation.hpp"

#include <cmath>
#include <stdexcept>

namespace spread::predict {

std::optional<RowBracket> bracket_rpm(std::span<const double> row_rpm, double rpm) {
  if (row_rpm.empty() || !std::isfinite(rpm) || rpm < row_rpm.front() || rpm > row_rpm.back()) {
    return std::nullopt;
  }
  // Rows are few (tens): a linear scan is as fast as a binary search and obviously right.
  for (std::size_t i = 0; i < row_rpm.size(); ++i) {
    if (rpm == row_rpm[i]) return RowBracket{i, i, 0.0};
    if (i + 1 < row_rpm.size() && rpm < row_rpm[i + 1]) {
      const double t = (rpm - row_rpm[i]) / (row_rpm[i + 1] - row_rpm[i]);
      return RowBracket{i, i + 1, t};
    }
  }
  return std::nullopt;  // unreachable for ascending rows
}

std::size_t interpolated_sample_count(std::size_t lower_count, std::size_t upper_count, double upper_weight) {
  if (upper_weight == 0.0) return lower_count;
  return lower_count == upper_count ? lower_count : lower_count + upper_count;
}

namespace {

float lerp(float a, float b, double t) {
  return static_cast<float>((1.0 - t) * static_cast<double>(a) + t * static_cast<double>(b));
}

tables::LaunchSample lerp(const tables::LaunchSample& a, const tables::LaunchSample& b, double t) {
  tables::LaunchSample s{};
  s.x_m = lerp(a.x_m, b.x_m, t);
  s.y_m = lerp(a.y_m, b.y_m, t);
  s.z_m = lerp(a.z_m, b.z_m, t);
  s.t_s = lerp(a.t_s, b.t_s, t);
  s.vx_norm = lerp(a.vx_norm, b.vx_norm, t);
  s.vy_norm = lerp(a.vy_norm, b.vy_norm, t);
  s.vz_norm = lerp(a.vz_norm, b.vz_norm, t);
  s.wx_norm = lerp(a.wx_norm, b.wx_norm, t);
  s.wy_norm = lerp(a.wy_norm, b.wy_norm, t);
  s.wz_norm = lerp(a.wz_norm, b.wz_norm, t);
  s.diameter_m = lerp(a.diameter_m, b.diameter_m, t);
  s.mass_kg = lerp(a.mass_kg, b.mass_kg, t);
  return s;
}

}  // namespace

std::size_t interpolate_launch_samples(std::span<const tables::LaunchSample> lower,
                                       std::span<const tables::LaunchSample> upper, double upper_weight,
                                       std::span<tables::LaunchSample> out_samples,
                                       std::span<double> out_weight_kg) {
  const std::size_t count = interpolated_sample_count(lower.size(), upper.size(), upper_weight);
  if (out_samples.size() < count || out_weight_kg.size() < count) {
    throw std::length_error("interpolate_launch_samples: output spans smaller than the sample count");
  }
  if (upper_weight == 0.0) {
    for (std::size_t k = 0; k < lower.size(); ++k) {
      out_samples[k] = lower[k];
      out_weight_kg[k] = static_cast<double>(lower[k].mass_kg);
    }
  } else if (lower.size() == upper.size()) {
    for (std::size_t k = 0; k < lower.size(); ++k) {
      out_samples[k] = lerp(lower[k], upper[k], upper_weight);
      out_weight_kg[k] = static_cast<double>(out_samples[k].mass_kg);
    }
  } else {
    const double lower_weight = 1.0 - upper_weight;
    for (std::size_t k = 0; k < lower.size(); ++k) {
      out_samples[k] = lower[k];
      out_weight_kg[k] = lower_weight * static_cast<double>(lower[k].mass_kg);
    }
    for (std::size_t k = 0; k < upper.size(); ++k) {
      out_samples[lower.size() + k] = upper[k];
      out_weight_kg[lower.size() + k] = upper_weight * static_cast<double>(upper[k].mass_kg);
    }
  }
  return count;
}

}  // namespace spread::predict
