#include "libspread/analysis/predict/landing_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace spread::predict {

namespace {

constexpr std::size_t kGridBuildChunk = 1024;  // flights per fly_many call while building
constexpr std::size_t kGridStencil = 4;        // cubic Lagrange: four nodes per axis
constexpr std::size_t kDiameterPoints = kGridStencil, kVerticalPoints = kGridStencil;
// Four floats in one SSE register (GCC/Clang vector extension; any x86-64 or AArch64 has it).
typedef float Float4 __attribute__((vector_size(16)));

// Cubic Lagrange weights of the nodes −1, 0, 1, 2 at fraction f of the interval [0, 1] (f outside it
// extrapolates the same cubic).
inline void grid_cubic_weights(double f, double (&w)[kGridStencil]) {
  const double fm1 = f - 1.0, fm2 = f - 2.0, fp1 = f + 1.0;
  w[0] = -f * fm1 * fm2 * (1.0 / 6.0);
  w[1] = fp1 * fm1 * fm2 * 0.5;
  w[2] = -fp1 * f * fm2 * 0.5;
  w[3] = fp1 * f * fm1 * (1.0 / 6.0);
}

// The stencil's first node index and weights of x on an axis, with `points` nodes: 4 (cubic Lagrange
// through nodes first .. first + 3, x between the middle two) or 2 (linear). `lowest` is the smallest first
// index allowed (−1 on the speed axis, continued through 0 by symmetry).
template <std::size_t points>
inline std::ptrdiff_t grid_stencil(double x, const GridAxis& axis, double inverse_step, std::ptrdiff_t lowest,
                                   double (&w)[points]) {
  // Truncation is the floor for positions >= −1, and any position below that takes the lowest stencil;
  // bounded first so that the conversion is defined (std::floor is a libm call on baseline x86-64).
  const double position = std::clamp((x - axis.first) * inverse_step, -2.0, static_cast<double>(axis.count) + 1.0);
  const auto highest = static_cast<std::ptrdiff_t>(axis.count - points);
  if constexpr (points == 2) {
    auto first = std::clamp(static_cast<std::ptrdiff_t>(position), lowest, highest);
    const double f = position - static_cast<double>(first);
    w[0] = 1.0 - f;
    w[1] = f;
    return first;
  } else {
    auto first = std::clamp(static_cast<std::ptrdiff_t>(position) - 1, lowest, highest);
    grid_cubic_weights(position - static_cast<double>(first + 1), w);
    return first;
  }
}

}  // namespace

LandingGrid::LandingGrid(std::pmr::memory_resource* memory) : values_(memory) {}

std::size_t LandingGrid::value_count(const Axes& axes) {
  std::size_t count = 2;
  for (const GridAxis& axis : axes) count *= axis.count;
  return count;
}

namespace {
void check_axes(const LandingGrid::Axes& axes) {
  for (std::size_t a = 0; a < LandingGrid::kAxisCount; ++a) {
    if (axes[a].count < kGridStencil || !(axes[a].step > 0.0) || !std::isfinite(axes[a].first) ||
        !std::isfinite(axes[a].last())) {
      throw std::invalid_argument("LandingGrid: axis " + std::to_string(a) +
                                  " needs at least 4 nodes, a positive step and finite ends");
    }
  }
  if (axes[LandingGrid::kSpeed].first != 0.0) throw std::invalid_argument("LandingGrid: the speed axis starts at 0");
  if (axes[LandingGrid::kDiameter].first <= 0.0) throw std::invalid_argument("LandingGrid: diameters must be > 0");
  if (axes[LandingGrid::kHeight].first < 0.0) throw std::invalid_argument("LandingGrid: heights must be >= 0");
}
}  // namespace

bool LandingGrid::build(const Axes& axes, double density_kg_m3, flight::EffectSet effects,
                        const flight::Settings& settings, const flight::Air& air) {
  check_axes(axes);
  if (!holds(effects)) throw std::invalid_argument("LandingGrid::build: effects other than drag");
  effects_ = effects;
  axes_ = axes;
  for (std::size_t a = 0; a < kAxisCount; ++a) inverse_step_[a] = 1.0 / axes[a].step;
  const std::size_t nodes = value_count(axes) / 2;
  values_.assign(2 * nodes, 0.0f);
  std::vector<flight::Granule> granules(kGridBuildChunk);
  std::vector<flight::State> launches(kGridBuildChunk);
  std::vector<flight::Landing> landings(kGridBuildChunk);
  const flight::Air still_air{air.density_kg_m3, air.viscosity_pa_s, Vec3::Zero()};
  const auto node = [&](Axis a, std::size_t k) { return axes[a].first + axes[a].step * static_cast<double>(k); };
  for (std::size_t first = 0; first < nodes; first += kGridBuildChunk) {
    const std::size_t count = std::min(kGridBuildChunk, nodes - first);
    for (std::size_t c = 0; c < count; ++c) {
      std::size_t index = first + c;
      const std::size_t u = index % axes[kSpeed].count;
      index /= axes[kSpeed].count;
      const std::size_t h = index % axes[kHeight].count;
      index /= axes[kHeight].count;
      const std::size_t v = index % axes[kVerticalSpeed].count;
      const std::size_t d = index / axes[kVerticalSpeed].count;
      granules[c] = flight::Granule{node(kDiameter, d), density_kg_m3};
      const double root_height = node(kHeight, h);
      launches[c].position_m = Vec3(0.0, 0.0, root_height * root_height);
      launches[c].velocity_m_s = Vec3(node(kSpeed, u), 0.0, node(kVerticalSpeed, v));
      launches[c].spin_rad_s = Vec3::Zero();
    }
    flight::fly_many(std::span(granules).first(count), std::span(launches).first(count), 0.0, still_air, effects,
                     settings, std::span(landings).first(count));
    for (std::size_t c = 0; c < count; ++c) {
      if (!landings[c].landed) {
        values_.clear();
        return false;
      }
      values_[first + c] = static_cast<float>(landings[c].state.position_m.x());
      values_[nodes + first + c] = static_cast<float>(landings[c].flight_time_s);
    }
  }
  return true;
}

namespace {
constexpr std::uint32_t kMaxRestoredNodes = 4096;  // per axis, far above kGridNodes
}  // namespace

bool LandingGrid::restore(const Axes& axes, flight::EffectSet effects, std::span<const float> values) {
  values_.clear();
  try {
    check_axes(axes);
  } catch (const std::invalid_argument&) {
    return false;
  }
  for (const GridAxis& axis : axes) {
    if (axis.count > kMaxRestoredNodes) return false;  // value_count must not overflow
  }
  if (!holds(effects) || values.size() != value_count(axes)) return false;
  for (float value : values) {
    if (!std::isfinite(value)) return false;
  }
  effects_ = effects;
  axes_ = axes;
  for (std::size_t a = 0; a < kAxisCount; ++a) inverse_step_[a] = 1.0 / axes[a].step;
  values_.assign(values.begin(), values.end());
  return true;
}

template <bool kWithTime>
void LandingGrid::interpolate(double diameter_m, double vertical_speed_m_s, double height_m, double speed_m_s,
                              double& range_m, double& time_s) const {
  double wd[kDiameterPoints], wv[kVerticalPoints], wh[kGridStencil], wu[kGridStencil];
  const std::ptrdiff_t d0 = grid_stencil(diameter_m, axes_[kDiameter], inverse_step_[kDiameter], 0, wd);
  const std::ptrdiff_t v0 = grid_stencil(vertical_speed_m_s, axes_[kVerticalSpeed], inverse_step_[kVerticalSpeed], 0, wv);
  const std::ptrdiff_t h0 = grid_stencil(std::sqrt(std::max(height_m, 0.0)), axes_[kHeight], inverse_step_[kHeight], 0, wh);
  const std::ptrdiff_t u0 = grid_stencil(speed_m_s, axes_[kSpeed], inverse_step_[kSpeed], -1, wu);
  const std::size_t nu = axes_[kSpeed].count, nh = axes_[kHeight].count, nv = axes_[kVerticalSpeed].count;
  const std::size_t time_offset = values_.size() / 2;  // the T values follow the R values
  // Σ_dvh w_d w_v w_h Σ_u w_u f = Σ_u w_u (Σ_dvh w_d w_v w_h f): the 64 lines of the stencil (four speeds,
  // one SSE register each) are summed first with their weights, then the speeds. One accumulator per
  // height node, named so that they stay in registers: the sums of different heights do not wait for each
  // other (an addition's latency, not the loads, bounds a single chain).
  const std::size_t line_u = u0 < 0 ? 0 : static_cast<std::size_t>(u0);
  Float4 r0 = {}, r1 = {}, r2 = {}, r3 = {}, t0 = {}, t1 = {}, t2 = {}, t3 = {};
  for (std::size_t a = 0; a < kDiameterPoints; ++a) {
    for (std::size_t b = 0; b < kVerticalPoints; ++b) {
      const float* line = &values_[nu * nh * ((static_cast<std::size_t>(d0) + a) * nv + static_cast<std::size_t>(v0) + b) +
                                   nu * static_cast<std::size_t>(h0) + line_u];
      const float w = static_cast<float>(wd[a] * wv[b]);
      const auto add = [w](Float4& sum, const float* values) {
        Float4 v;
        std::memcpy(&v, values, sizeof v);
        sum += w * v;
      };
      add(r0, line);
      add(r1, line + nu);
      add(r2, line + 2 * nu);
      add(r3, line + 3 * nu);
      if constexpr (kWithTime) {
        add(t0, line + time_offset);
        add(t1, line + time_offset + nu);
        add(t2, line + time_offset + 2 * nu);
        add(t3, line + time_offset + 3 * nu);
      }
    }
  }
  const auto weight = [&](std::size_t c) { return static_cast<float>(wh[c]); };
  // The stencil's four speeds; from speed node −1 (node 1 mirrored: R(−u) = −R(u), T(−u) = T(u)) the
  // lines were read from node 0, so they shift one node up.
  const auto speeds = [&](const Float4& sum, double mirror_sign, double& out) {
    double f[kGridStencil] = {sum[0], sum[1], sum[2], sum[3]};
    if (u0 < 0) {
      f[3] = f[2];
      f[2] = f[1];
      f[1] = f[0];
      f[0] = mirror_sign * f[2];
    }
    out = wu[0] * f[0] + wu[1] * f[1] + wu[2] * f[2] + wu[3] * f[3];
  };
  speeds(weight(0) * r0 + weight(1) * r1 + weight(2) * r2 + weight(3) * r3, -1.0, range_m);
  if constexpr (kWithTime) speeds(weight(0) * t0 + weight(1) * t1 + weight(2) * t2 + weight(3) * t3, 1.0, time_s);
}

void LandingGrid::range_and_time(double diameter_m, double vertical_speed_m_s, double height_m, double speed_m_s,
                                 double& range_m, double& time_s) const {
  interpolate<true>(diameter_m, vertical_speed_m_s, height_m, speed_m_s, range_m, time_s);
}

void LandingGrid::landing(double diameter_m, double x_m, double y_m, double height_m, double vx_m_s, double vy_m_s,
                          double vz_m_s, double wind_x_m_s, double wind_y_m_s, double& landing_x_m,
                          double& landing_y_m) const {
  const double rx = vx_m_s - wind_x_m_s, ry = vy_m_s - wind_y_m_s;
  const double u = std::sqrt(rx * rx + ry * ry);
  double range_m = 0.0, time_s = 0.0;
  // In still air the flight time is not needed: half the values read.
  if (wind_x_m_s == 0.0 && wind_y_m_s == 0.0) {
    interpolate<false>(diameter_m, vz_m_s, height_m, u, range_m, time_s);
  } else {
    interpolate<true>(diameter_m, vz_m_s, height_m, u, range_m, time_s);
  }
  const double along = u > 0.0 ? range_m / u : 0.0;  // the range along the unit vector (rx, ry)/u
  landing_x_m = x_m + along * rx + wind_x_m_s * time_s;
  landing_y_m = y_m + along * ry + wind_y_m_s * time_s;
}

LandingDomain landing_domain_for(double stored_disc_height_m) {
  LandingDomain domain;
  if (stored_disc_height_m < domain.min_disc_height_m) domain.min_disc_height_m = 0.5 * stored_disc_height_m;
  if (stored_disc_height_m > domain.max_disc_height_m) domain.max_disc_height_m = 2.0 * stored_disc_height_m;
  return domain;
}

LandingGrid::Axes landing_grid_axes(std::span<const tables::LaunchSample> samples, double max_rim_speed_m_s,
                                    const LandingDomain& domain) {
  double lo[LandingGrid::kAxisCount], hi[LandingGrid::kAxisCount];
  for (std::size_t a = 0; a < LandingGrid::kAxisCount; ++a) {
    lo[a] = std::numeric_limits<double>::infinity();
    hi[a] = -std::numeric_limits<double>::infinity();
  }
  const auto widen = [&](std::size_t axis, double value) {
    lo[axis] = std::min(lo[axis], value);
    hi[axis] = std::max(hi[axis], value);
  };
  for (const tables::LaunchSample& s : samples) {
    widen(LandingGrid::kDiameter, s.diameter_m);
    // vz = ω R · vz_norm for any ω up to the fastest row's: between 0 and the fastest row's value.
    widen(LandingGrid::kVerticalSpeed, 0.0);
    widen(LandingGrid::kVerticalSpeed, max_rim_speed_m_s * s.vz_norm);
    widen(LandingGrid::kHeight, std::sqrt(std::max(s.z_m + domain.min_disc_height_m, 0.0)));
    widen(LandingGrid::kHeight, std::sqrt(std::max(s.z_m + domain.max_disc_height_m, 0.0)));
    widen(LandingGrid::kSpeed, max_rim_speed_m_s * std::hypot(double{s.vx_norm}, double{s.vy_norm}) + domain.max_wind_m_s);
  }
  if (samples.empty()) throw std::invalid_argument("landing_grid_axes: no samples");
  LandingGrid::Axes axes;
  for (std::size_t a = 0; a < LandingGrid::kAxisCount; ++a) {
    const std::uint32_t count = kGridNodes[a];
    // A range of one value (one diameter) still gets a span: 1 % of its size, or 1 of its unit.
    double span = hi[a] - lo[a];
    if (!(span > 0.0)) span = std::max(0.01 * std::abs(hi[a]), a == LandingGrid::kDiameter ? 1e-4 : 1e-2);
    // count − 3 intervals inside, one node of margin each side (the speed axis starts at 0: its margin is
    // all above).
    const double step = span / static_cast<double>(count - 3);
    double first = lo[a] - step;
    if (a == LandingGrid::kSpeed) first = 0.0;
    // Diameters and heights stay positive: no granule is launched from the ground (a launch there going
    // up a fraction of a millimetre is no flight a grid should hold).
    if (a == LandingGrid::kDiameter || a == LandingGrid::kHeight) first = std::max(first, 0.5 * lo[a]);
    axes[a] = GridAxis{first, step, count};
  }
  // The speed axis: from 0, its last node a margin above the fastest.
  axes[LandingGrid::kSpeed].step = hi[LandingGrid::kSpeed] / static_cast<double>(kGridNodes[LandingGrid::kSpeed] - 2);
  return axes;
}

}  // namespace spread::predict
