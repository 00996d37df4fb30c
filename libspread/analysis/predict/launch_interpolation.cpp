#include "libspread/analysis/predict/launch_interpolation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

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
  const std::size_t count = lower.size();
  if (upper_weight != 0.0 && upper.size() != count) {
    throw std::invalid_argument("interpolate_launch_samples: pairwise interpolation needs rows of equal size");
  }
  if (out_samples.size() < count || out_weight_kg.size() < count) {
    throw std::length_error("interpolate_launch_samples: output spans smaller than the sample count");
  }
  for (std::size_t k = 0; k < count; ++k) {
    out_samples[k] = upper_weight == 0.0 ? lower[k] : lerp(lower[k], upper[k], upper_weight);
    out_weight_kg[k] = static_cast<double>(out_samples[k].mass_kg);
  }
  return count;
}

namespace {

void check_celled(const CelledRow& row, std::size_t cells, const char* which) {
  if (row.samples.empty() || row.cell_of_sample.size() != row.samples.size() || row.cell_mean.size() != cells) {
    throw std::invalid_argument(std::string("interpolate_by_quantile_cells: ") + which +
                                " row is empty or its cells do not match it or the other row's");
  }
  for (CellIndex c : row.cell_of_sample) {
    if (c >= cells) {
      throw std::invalid_argument(std::string("interpolate_by_quantile_cells: ") + which +
                                  " row has a cell index out of range");
    }
  }
}

// s − own + target on the kinematic fields (position, velocity, spin); the granule keeps its launch
// time, diameter and mass.
tables::LaunchSample moved(const tables::LaunchSample& s, const tables::LaunchSample& own,
                           const tables::LaunchSample& target) {
  auto shift = [](float value, float from, float to) {
    return static_cast<float>(static_cast<double>(value) - static_cast<double>(from) + static_cast<double>(to));
  };
  tables::LaunchSample out = s;
  out.x_m = shift(s.x_m, own.x_m, target.x_m);
  out.y_m = shift(s.y_m, own.y_m, target.y_m);
  out.z_m = shift(s.z_m, own.z_m, target.z_m);
  out.vx_norm = shift(s.vx_norm, own.vx_norm, target.vx_norm);
  out.vy_norm = shift(s.vy_norm, own.vy_norm, target.vy_norm);
  out.vz_norm = shift(s.vz_norm, own.vz_norm, target.vz_norm);
  out.wx_norm = shift(s.wx_norm, own.wx_norm, target.wx_norm);
  out.wy_norm = shift(s.wy_norm, own.wy_norm, target.wy_norm);
  out.wz_norm = shift(s.wz_norm, own.wz_norm, target.wz_norm);
  return out;
}

}  // namespace

void check_celled_rows(const CelledRow& lower, const CelledRow& upper) {
  const std::size_t cells = lower.cell_mean.size();
  check_celled(lower, cells, "lower");
  check_celled(upper, cells, "upper");
}

void quantile_cell_targets(const CelledRow& lower, const CelledRow& upper, double upper_weight,
                           std::span<tables::LaunchSample> cell_target) {
  for (std::size_t c = 0; c < cell_target.size(); ++c) {
    const tables::LaunchSample& a = lower.cell_mean[c];
    const tables::LaunchSample& b = upper.cell_mean[c];
    const bool moves = a.mass_kg > 0.0f && b.mass_kg > 0.0f;
    cell_target[c] = moves ? lerp(a, b, upper_weight) : tables::LaunchSample{};
    cell_target[c].mass_kg = moves ? 1.0f : 0.0f;
  }
}

void interpolate_by_quantile_cells(const CelledRow& lower, const CelledRow& upper, double upper_weight,
                                   std::size_t first, std::span<tables::LaunchSample> out_samples,
                                   std::span<double> out_weight_kg,
                                   std::span<const tables::LaunchSample> cell_target) {
  const std::size_t na = lower.samples.size();
  const double t = upper_weight;
  // Each granule of the lower row, then of the upper row, moved from its cell's mean in its row to the
  // interpolated cell mean.
  for (std::size_t o = 0; o < out_samples.size(); ++o) {
    const std::size_t index = first + o;
    const bool from_lower = index < na;
    const CelledRow& row = from_lower ? lower : upper;
    const std::size_t k = from_lower ? index : index - na;
    const CellIndex c = row.cell_of_sample[k];
    const tables::LaunchSample& s = row.samples[k];
    if (!cell_target.empty()) {
      out_samples[o] = cell_target[c].mass_kg > 0.0f ? moved(s, row.cell_mean[c], cell_target[c]) : s;
    } else {
      const tables::LaunchSample& a = lower.cell_mean[c];
      const tables::LaunchSample& b = upper.cell_mean[c];
      out_samples[o] = a.mass_kg > 0.0f && b.mass_kg > 0.0f ? moved(s, row.cell_mean[c], lerp(a, b, t)) : s;
    }
    out_weight_kg[o] = (from_lower ? 1.0 - t : t) * static_cast<double>(s.mass_kg);
  }
}

std::size_t interpolate_by_quantile_cells(const CelledRow& lower, const CelledRow& upper, double upper_weight,
                                          std::span<tables::LaunchSample> out_samples,
                                          std::span<double> out_weight_kg) {
  check_celled_rows(lower, upper);
  const std::size_t count = lower.samples.size() + upper.samples.size();
  if (out_samples.size() < count || out_weight_kg.size() < count) {
    throw std::length_error("interpolate_by_quantile_cells: output spans smaller than n_lower + n_upper");
  }
  interpolate_by_quantile_cells(lower, upper, upper_weight, 0, out_samples.first(count), out_weight_kg.first(count));
  return count;
}

}  // namespace spread::predict
