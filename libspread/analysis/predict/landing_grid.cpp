#include "libspread/analysis/predict/landing_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "libspread/core/cpu_features.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <emmintrin.h>
#endif

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

// The stencil's 16 lines (diameter × vertical speed), each four heights of four speeds, R and T
// interleaved per speed (R0 T0 R1 T1 R2 T2 R3 T3: 8 floats, one 32-byte read), summed with their weights:
// sums = Σ_h wh[h] Σ_line w[line] · values(line, h), in that order, lane by lane. For one or two landings
// of the same diameter, vertical speed and height (a sample's two discs in a wind), which share the
// weights and differ only in the speeds read (first[l]).
struct StencilLines {
  const float* first[2];      // line 0 at height 0 of each landing
  std::size_t diameter_step;  // floats between diameter nodes, vertical-speed nodes and height nodes
  std::size_t vertical_step;
  std::size_t height_step;
  // w_d · w_v of line 4a + b at weight[(4a + b) · weight_stride], the heights' at height_weight[c ·
  // weight_stride] (a block's weights are stored lane by lane: LandingGrid::StencilBlock).
  const float* weight;
  const float* height_weight;
  std::size_t weight_stride;
  float line_weight(std::size_t line) const { return weight[line * weight_stride]; }
  float height(std::size_t c) const { return height_weight[c * weight_stride]; }
};

// In SSE registers, two per height (R0 T0 R1 T1 | R2 T2 R3 T3); still air (no T) takes the four R out of
// the two halves (one shuffle) and sums those alone. One accumulator per height, named so that they stay
// in registers: the sums of different heights do not wait for each other (an addition's latency, not the
// loads, bounds a single chain).
template <bool kWithTime>
void sum_stencil_lines(const StencilLines& in, std::size_t landing, float (&sums)[8]) {
  Float4 a0 = {}, a1 = {}, a2 = {}, a3 = {}, b0 = {}, b1 = {}, b2 = {}, b3 = {};
  for (std::size_t a = 0; a < kDiameterPoints; ++a) {
    for (std::size_t b = 0; b < kVerticalPoints; ++b) {
      const float* line = in.first[landing] + a * in.diameter_step + b * in.vertical_step;
      const float w = in.line_weight(4 * a + b);
      const auto add = [w](Float4& low, Float4& high, const float* values) {
        Float4 v0, v1;
        std::memcpy(&v0, values, sizeof v0);
        std::memcpy(&v1, values + 4, sizeof v1);
        if constexpr (kWithTime) {
          low += w * v0;
          high += w * v1;
        } else {
          low += w * __builtin_shufflevector(v0, v1, 0, 2, 4, 6);
        }
      };
      add(a0, b0, line);
      add(a1, b1, line + in.height_step);
      add(a2, b2, line + 2 * in.height_step);
      add(a3, b3, line + 3 * in.height_step);
    }
  }
  const float wh[4] = {in.height(0), in.height(1), in.height(2), in.height(3)};
  const Float4 low = wh[0] * a0 + wh[1] * a1 + wh[2] * a2 + wh[3] * a3;
  if constexpr (kWithTime) {
    const Float4 high = wh[0] * b0 + wh[1] * b1 + wh[2] * b2 + wh[3] * b3;
    std::memcpy(sums, &low, sizeof low);
    std::memcpy(sums + 4, &high, sizeof high);
  } else {
    for (int k = 0; k < 4; ++k) sums[2 * k] = low[k];  // the R lanes
  }
}

#if defined(__x86_64__) || defined(__i386__)
#define SPREAD_GRID_AVX 1
// The same sums with one AVX register per height (all eight lanes at once; still air sums T too and
// leaves it), both landings in one loop. Each lane takes the same multiplications and additions in the
// same order as in SSE, and no fused multiply-add (the target is "avx", not "fma"), so the two give the
// same bits.
typedef float Float8 __attribute__((vector_size(32)));
__attribute__((target("avx"), always_inline)) inline void add_line_avx(Float8& sum, float w, const float* values) {
  Float8 v;
  std::memcpy(&v, values, sizeof v);
  sum += w * v;
}
__attribute__((target("avx"), always_inline)) inline void store_heights_avx(const StencilLines& in, Float8 s0,
                                                                            Float8 s1, Float8 s2, Float8 s3,
                                                                            float* sums) {
  const Float8 sum = in.height(0) * s0 + in.height(1) * s1 + in.height(2) * s2 + in.height(3) * s3;
  std::memcpy(sums, &sum, sizeof sum);
}
// The accumulators are named (not an array), so that they stay in registers.
__attribute__((target("avx"))) void sum_stencil_lines_avx(const StencilLines& in, float (&sums)[2][8]) {
  Float8 s0 = {}, s1 = {}, s2 = {}, s3 = {};
  const std::size_t step = in.height_step;
  for (std::size_t a = 0; a < kDiameterPoints; ++a) {
    for (std::size_t b = 0; b < kVerticalPoints; ++b) {
      const float* line = in.first[0] + a * in.diameter_step + b * in.vertical_step;
      const float w = in.line_weight(4 * a + b);
      add_line_avx(s0, w, line);
      add_line_avx(s1, w, line + step);
      add_line_avx(s2, w, line + 2 * step);
      add_line_avx(s3, w, line + 3 * step);
    }
  }
  store_heights_avx(in, s0, s1, s2, s3, sums[0]);
}
__attribute__((target("avx"))) void sum_stencil_line_pairs_avx(const StencilLines& in, float (&sums)[2][8]) {
  Float8 s0 = {}, s1 = {}, s2 = {}, s3 = {}, t0 = {}, t1 = {}, t2 = {}, t3 = {};
  const std::size_t step = in.height_step;
  for (std::size_t a = 0; a < kDiameterPoints; ++a) {
    for (std::size_t b = 0; b < kVerticalPoints; ++b) {
      const std::size_t offset = a * in.diameter_step + b * in.vertical_step;
      const float* line = in.first[0] + offset;
      const float* other = in.first[1] + offset;
      const float w = in.line_weight(4 * a + b);
      add_line_avx(s0, w, line);
      add_line_avx(s1, w, line + step);
      add_line_avx(s2, w, line + 2 * step);
      add_line_avx(s3, w, line + 3 * step);
      add_line_avx(t0, w, other);
      add_line_avx(t1, w, other + step);
      add_line_avx(t2, w, other + 2 * step);
      add_line_avx(t3, w, other + 3 * step);
    }
  }
  store_heights_avx(in, s0, s1, s2, s3, sums[0]);
  store_heights_avx(in, t0, t1, t2, t3, sums[1]);
}
#endif

// The stencil's sums of `landings` (1 or 2) landings of one diameter, vertical speed and height, in AVX
// registers (avx) or SSE ones.
template <bool kWithTime>
void sum_stencil(const StencilLines& lines, std::size_t landings, bool avx, float (&sums)[2][8]) {
#ifdef SPREAD_GRID_AVX
  if (avx) {
    if (landings == 2) {
      sum_stencil_line_pairs_avx(lines, sums);
    } else {
      sum_stencil_lines_avx(lines, sums);
    }
    return;
  }
#endif
  for (std::size_t l = 0; l < landings; ++l) sum_stencil_lines<kWithTime>(lines, l, sums[l]);
}

// The stencil's four speeds (lane 2k: R, 2k + 1: T) summed with their weights. From speed node −1 (node 1
// mirrored: R(−u) = −R(u), T(−u) = T(u)) the lines were read from node 0, so they shift one node up.
inline double speed_sum(const float* sum, int lane, bool from_below_zero, double w0, double w1, double w2, double w3) {
  double f[kGridStencil] = {sum[lane], sum[lane + 2], sum[lane + 4], sum[lane + 6]};
  if (from_below_zero) {
    f[3] = f[2];
    f[2] = f[1];
    f[1] = f[0];
    f[0] = (lane == 0 ? -1.0 : 1.0) * f[2];
  }
  return w0 * f[0] + w1 * f[1] + w2 * f[2] + w3 * f[3];
}

}  // namespace

LandingGrid::LandingGrid(std::pmr::memory_resource* memory) : values_(memory) { set_avx(true); }

bool LandingGrid::set_avx(bool enabled) {
  avx_ = enabled && cpu_has_avx();
  avx512_ = avx_ && cpu_has_avx512f();
  return avx_;
}

bool LandingGrid::set_avx512(bool enabled) {
  avx512_ = enabled && avx_ && cpu_has_avx512f();
  return avx512_;
}

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
      values_[2 * (first + c)] = static_cast<float>(landings[c].state.position_m.x());
      values_[2 * (first + c) + 1] = static_cast<float>(landings[c].flight_time_s);
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
  // Stored as all R then all T (values()); held interleaved per node.
  const std::size_t nodes = values.size() / 2;
  values_.resize(values.size());
  for (std::size_t i = 0; i < nodes; ++i) {
    values_[2 * i] = values[i];
    values_[2 * i + 1] = values[nodes + i];
  }
  return true;
}

std::vector<float> LandingGrid::values() const {
  const std::size_t nodes = values_.size() / 2;
  std::vector<float> out(values_.size());
  for (std::size_t i = 0; i < nodes; ++i) {
    out[i] = values_[2 * i];
    out[nodes + i] = values_[2 * i + 1];
  }
  return out;
}

template <bool kWithTime>
void LandingGrid::interpolate(double diameter_m, double vertical_speed_m_s, double height_m,
                              std::span<const double> speeds_m_s, double* range_m, double* time_s) const {
  double wd[kDiameterPoints], wv[kVerticalPoints], wh[kGridStencil];
  const std::ptrdiff_t d0 = grid_stencil(diameter_m, axes_[kDiameter], inverse_step_[kDiameter], 0, wd);
  const std::ptrdiff_t v0 = grid_stencil(vertical_speed_m_s, axes_[kVerticalSpeed], inverse_step_[kVerticalSpeed], 0, wv);
  const std::ptrdiff_t h0 = grid_stencil(std::sqrt(std::max(height_m, 0.0)), axes_[kHeight], inverse_step_[kHeight], 0, wh);
  const std::size_t nu = axes_[kSpeed].count, nh = axes_[kHeight].count, nv = axes_[kVerticalSpeed].count;
  // Σ_dvh w_d w_v w_h Σ_u w_u f = Σ_u w_u (Σ_dvh w_d w_v w_h f): the 64 lines of the stencil (four speeds
  // of R and T each) are summed first with their weights, then the speeds.
  const std::size_t count = speeds_m_s.size();
  StencilLines lines;
  double wu[2][kGridStencil];
  std::ptrdiff_t u0[2];
  const std::size_t base = nu * nh * (static_cast<std::size_t>(d0) * nv + static_cast<std::size_t>(v0)) +
                           nu * static_cast<std::size_t>(h0);
  for (std::size_t l = 0; l < count; ++l) {
    u0[l] = grid_stencil(speeds_m_s[l], axes_[kSpeed], inverse_step_[kSpeed], -1, wu[l]);
    const std::size_t line_u = u0[l] < 0 ? 0 : static_cast<std::size_t>(u0[l]);
    lines.first[l] = &values_[2 * (base + line_u)];
  }
  lines.diameter_step = 2 * nu * nh * nv;
  lines.vertical_step = 2 * nu * nh;
  lines.height_step = 2 * nu;
  float line_weight[16], height_weight[kGridStencil];
  for (std::size_t a = 0; a < kDiameterPoints; ++a) {
    for (std::size_t b = 0; b < kVerticalPoints; ++b) line_weight[4 * a + b] = static_cast<float>(wd[a] * wv[b]);
  }
  for (std::size_t c = 0; c < kGridStencil; ++c) height_weight[c] = static_cast<float>(wh[c]);
  lines.weight = line_weight;
  lines.height_weight = height_weight;
  lines.weight_stride = 1;
  float sums[2][8];
  sum_stencil<kWithTime>(lines, count, avx_, sums);
  for (std::size_t l = 0; l < count; ++l) {
    range_m[l] = speed_sum(sums[l], 0, u0[l] < 0, wu[l][0], wu[l][1], wu[l][2], wu[l][3]);
    if constexpr (kWithTime) time_s[l] = speed_sum(sums[l], 1, u0[l] < 0, wu[l][0], wu[l][1], wu[l][2], wu[l][3]);
  }
}

void LandingGrid::range_and_time(double diameter_m, double vertical_speed_m_s, double height_m, double speed_m_s,
                                 double& range_m, double& time_s) const {
  interpolate<true>(diameter_m, vertical_speed_m_s, height_m, std::span(&speed_m_s, 1), &range_m, &time_s);
}

void LandingGrid::landing(double diameter_m, double x_m, double y_m, double height_m, double vx_m_s, double vy_m_s,
                          double vz_m_s, double wind_x_m_s, double wind_y_m_s, double& landing_x_m,
                          double& landing_y_m) const {
  const double rx = vx_m_s - wind_x_m_s, ry = vy_m_s - wind_y_m_s;
  const double u = std::sqrt(rx * rx + ry * ry);
  double range_m = 0.0, time_s = 0.0;
  // In still air the flight time is not needed: half the values read.
  if (wind_x_m_s == 0.0 && wind_y_m_s == 0.0) {
    interpolate<false>(diameter_m, vz_m_s, height_m, std::span(&u, 1), &range_m, &time_s);
  } else {
    interpolate<true>(diameter_m, vz_m_s, height_m, std::span(&u, 1), &range_m, &time_s);
  }
  const double along = u > 0.0 ? range_m / u : 0.0;  // the range along the unit vector (rx, ry)/u
  landing_x_m = x_m + along * rx + wind_x_m_s * time_s;
  landing_y_m = y_m + along * ry + wind_y_m_s * time_s;
}

void LandingGrid::mirrored_landings(double diameter_m, double x_m, double y_m, double height_m, double vx_m_s,
                                    double vy_m_s, double vz_m_s, double wind_x_m_s, double wind_y_m_s,
                                    double (&landing_x_m)[2], double (&landing_y_m)[2]) const {
  // The launch as given (mirror +1) and mirrored x → −x (−1), relative to the air.
  const double rx[2] = {vx_m_s - wind_x_m_s, -1.0 * vx_m_s - wind_x_m_s};
  const double ry = vy_m_s - wind_y_m_s;
  const double u[2] = {std::sqrt(rx[0] * rx[0] + ry * ry), std::sqrt(rx[1] * rx[1] + ry * ry)};
  double range_m[2] = {0.0, 0.0}, time_s[2] = {0.0, 0.0};
  interpolate<true>(diameter_m, vz_m_s, height_m, std::span(u), range_m, time_s);
  const double sx[2] = {x_m, -1.0 * x_m};
  for (int l = 0; l < 2; ++l) {
    const double along = u[l] > 0.0 ? range_m[l] / u[l] : 0.0;
    landing_x_m[l] = sx[l] + along * rx[l] + wind_x_m_s * time_s[l];
    landing_y_m[l] = y_m + along * ry + wind_y_m_s * time_s[l];
  }
}

namespace {

// kLanes doubles (and as many 32-bit integers and floats) side by side, GCC/Clang vector extension: four
// are one AVX register (or two SSE ones), eight one AVX-512 register.
template <std::size_t kLanes>
struct Lanes {
  typedef double Double __attribute__((vector_size(8 * kLanes)));
  typedef float Float __attribute__((vector_size(4 * kLanes)));
  typedef std::int32_t Int __attribute__((vector_size(4 * kLanes)));
};

// An axis as the lanes read it (grid_stencil's constants, computed once per call).
struct AxisLanes {
  double first, inverse_step, top;  // top: count + 1, the highest position
  std::int32_t lowest, highest;     // the stencil's first node: lowest .. count − 4
};
AxisLanes axis_lanes(const GridAxis& axis, double inverse_step, std::int32_t lowest) {
  return {axis.first, inverse_step, static_cast<double>(axis.count) + 1.0, lowest,
          static_cast<std::int32_t>(axis.count - kGridStencil)};
}

// grid_stencil<4> of kLanes values, lane by lane the same operations: std::clamp(v, lo, hi) is v < lo ? lo :
// hi < v ? hi : v, and the conversion to an integer truncates in both.
template <typename Double, typename Int>
__attribute__((always_inline)) inline void stencil_lanes(const Double& x, const AxisLanes& axis, Int& first,
                                                         Double (&w)[4]) {
  Double position = (x - axis.first) * axis.inverse_step;
  const Double lo = Double{} - 2.0, hi = Double{} + axis.top;
  position = position < lo ? lo : (hi < position ? hi : position);
  const Int lowest_lanes = Int{} + axis.lowest, highest_lanes = Int{} + axis.highest;
  Int k = __builtin_convertvector(position, Int) - 1;
  k = k < lowest_lanes ? lowest_lanes : (highest_lanes < k ? highest_lanes : k);
  first = k;
  const Double f = position - __builtin_convertvector(k + 1, Double);
  const Double fm1 = f - 1.0, fm2 = f - 2.0, fp1 = f + 1.0;
  w[0] = -f * fm1 * fm2 * (1.0 / 6.0);
  w[1] = fp1 * fm1 * fm2 * 0.5;
  w[2] = -fp1 * f * fm2 * 0.5;
  w[3] = fp1 * f * fm1 * (1.0 / 6.0);
}

// Correctly rounded square roots, the same bits as std::sqrt one at a time, without its check for a
// negative argument (libm's errno; the arguments are >= 0): SSE2's, two lanes at a time (AVX's encoding
// of the same instruction where the caller is compiled for AVX).
template <typename Double>
__attribute__((always_inline)) inline void sqrt_lanes(Double& x) {
  constexpr std::size_t kLanes = sizeof(Double) / sizeof(double);
#if defined(__x86_64__) || defined(__i386__)
  for (std::size_t k = 0; k < kLanes; k += 2) {
    const __m128d root = _mm_sqrt_pd(_mm_set_pd(x[k + 1], x[k]));
    x[k] = root[0];
    x[k + 1] = root[1];
  }
#else
  for (std::size_t k = 0; k < kLanes; ++k) x[k] = std::sqrt(x[k]);
#endif
}

// What sample_landings' set-up of a block needs of the request.
struct BlockRequest {
  const tables::LaunchSample* samples;
  std::size_t count;  // <= LandingGrid::kBlock
  double rim_speed_m_s, disc_height_m, wind_x_m_s, wind_y_m_s;
  bool sides[2];  // as stored, mirrored
  AxisLanes axes[LandingGrid::kAxisCount];
};

// The set-up of a block, kLanes samples at a time: what interpolate() and landing() compute per landing
// before reading the grid (a lane past the block's end repeats its last sample).
template <std::size_t kLanes>
__attribute__((always_inline)) inline void set_up_block(const BlockRequest& r, LandingGrid::StencilBlock& b) {
  using Grid = LandingGrid;
  using Double = typename Lanes<kLanes>::Double;
  using Float = typename Lanes<kLanes>::Float;
  using Int = typename Lanes<kLanes>::Int;
  static_assert(LandingGrid::kBlock % kLanes == 0);
  for (std::size_t i = 0; i < r.count; i += kLanes) {
    Double vx, vy, vz, z, diameter;
    for (std::size_t k = 0; k < kLanes; ++k) {
      const tables::LaunchSample& s = r.samples[std::min(i + k, r.count - 1)];
      vx[k] = s.vx_norm;
      vy[k] = s.vy_norm;
      vz[k] = s.vz_norm;
      z[k] = s.z_m;
      diameter[k] = s.diameter_m;
    }
    vx = r.rim_speed_m_s * vx;
    vy = r.rim_speed_m_s * vy;
    vz = r.rim_speed_m_s * vz;
    z = z + r.disc_height_m;
    const Double ry = vy - r.wind_y_m_s;
    std::memcpy(&b.relative_y[i], &ry, sizeof ry);
    for (int side = 0; side < 2; ++side) {
      if (!r.sides[side]) continue;
      const Double rx = (side == 0 ? vx : -1.0 * vx) - r.wind_x_m_s;
      Double u = rx * rx + ry * ry;
      sqrt_lanes(u);
      Int first;
      Double wu[4];
      stencil_lanes(u, r.axes[Grid::kSpeed], first, wu);
      std::memcpy(&b.relative_x[side][i], &rx, sizeof rx);
      std::memcpy(&b.speed[side][i], &u, sizeof u);
      std::memcpy(&b.speed_first[side][i], &first, sizeof first);
      for (int c = 0; c < 4; ++c) std::memcpy(&b.speed_weight[side][c][i], &wu[c], sizeof wu[c]);
    }
    Int d0, v0, h0;
    Double wd[4], wv[4], wh[4];
    stencil_lanes(diameter, r.axes[Grid::kDiameter], d0, wd);
    stencil_lanes(vz, r.axes[Grid::kVerticalSpeed], v0, wv);
    const Double zero{};
    Double root_height = z < zero ? zero : z;
    sqrt_lanes(root_height);
    stencil_lanes(root_height, r.axes[Grid::kHeight], h0, wh);
    std::memcpy(&b.diameter_first[i], &d0, sizeof d0);
    std::memcpy(&b.vertical_first[i], &v0, sizeof v0);
    std::memcpy(&b.height_first[i], &h0, sizeof h0);
    for (int a = 0; a < 4; ++a) {
      for (int c = 0; c < 4; ++c) {
        const Float w = __builtin_convertvector(wd[a] * wv[c], Float);
        std::memcpy(&b.line_weight[4 * a + c][i], &w, sizeof w);
      }
      const Float w = __builtin_convertvector(wh[a], Float);
      std::memcpy(&b.height_weight[a][i], &w, sizeof w);
    }
  }
}

void set_up_block_portable(const BlockRequest& r, LandingGrid::StencilBlock& b) { set_up_block<4>(r, b); }
#ifdef SPREAD_GRID_AVX
__attribute__((target("avx"))) void set_up_block_avx(const BlockRequest& r, LandingGrid::StencilBlock& b) {
  set_up_block<4>(r, b);
}
__attribute__((target("avx512f"))) void set_up_block_avx512(const BlockRequest& r, LandingGrid::StencilBlock& b) {
  set_up_block<8>(r, b);
}
#endif

}  // namespace

void LandingGrid::sample_landings(std::span<const tables::LaunchSample> samples, double rim_speed_m_s,
                                  double disc_height_m, double wind_x_m_s, double wind_y_m_s, Sides sides,
                                  StencilBlock& scratch, std::span<double> landing_x_m,
                                  std::span<double> landing_y_m) const {
  const std::size_t count = samples.size();
  const std::size_t outputs = sides == Sides::kBoth ? 2 * count : count;
  if (landing_x_m.size() < outputs || landing_y_m.size() < outputs) {
    throw std::length_error("LandingGrid::sample_landings: the landing buffers hold fewer than the landings");
  }
  const bool still = wind_x_m_s == 0.0 && wind_y_m_s == 0.0;
  // As landing() and mirrored_landings(): the flight time only in a wind, or for both sides at once.
  const bool with_time = !still || sides == Sides::kBoth;
  BlockRequest request{nullptr, 0, rim_speed_m_s, disc_height_m, wind_x_m_s, wind_y_m_s,
                       {sides != Sides::kMirrored, sides != Sides::kAsStored}, {}};
  for (std::size_t a = 0; a < kAxisCount; ++a) {
    request.axes[a] = axis_lanes(axes_[a], inverse_step_[a], a == kSpeed ? -1 : 0);  // through u = 0 by symmetry
  }
  const std::size_t nu = axes_[kSpeed].count, nh = axes_[kHeight].count, nv = axes_[kVerticalSpeed].count;
  StencilLines lines;
  lines.diameter_step = 2 * nu * nh * nv;
  lines.vertical_step = 2 * nu * nh;
  lines.height_step = 2 * nu;
  lines.weight_stride = kBlock;
  StencilBlock& b = scratch;
  for (std::size_t first = 0; first < count; first += kBlock) {
    request.samples = samples.data() + first;
    request.count = std::min(kBlock, count - first);
#ifdef SPREAD_GRID_AVX
    if (avx512_) {
      set_up_block_avx512(request, b);
    } else if (avx_) {
      set_up_block_avx(request, b);
    } else {
      set_up_block_portable(request, b);
    }
#else
    set_up_block_portable(request, b);
#endif
    for (std::size_t i = 0; i < request.count; ++i) {
      const std::size_t base = nu * nh * (static_cast<std::size_t>(b.diameter_first[i]) * nv +
                                          static_cast<std::size_t>(b.vertical_first[i])) +
                               nu * static_cast<std::size_t>(b.height_first[i]);
      int side_of[2];
      std::size_t landings = 0;
      for (int side = 0; side < 2; ++side) {
        if (!request.sides[side]) continue;
        const std::int32_t u0 = b.speed_first[side][i];
        lines.first[landings] = &values_[2 * (base + static_cast<std::size_t>(u0 < 0 ? 0 : u0))];
        side_of[landings++] = side;
      }
      lines.weight = &b.line_weight[0][i];
      lines.height_weight = &b.height_weight[0][i];
      float sums[2][8];
      if (with_time) {
        sum_stencil<true>(lines, landings, avx_, sums);
      } else {
        sum_stencil<false>(lines, landings, avx_, sums);
      }
      const tables::LaunchSample& sample = samples[first + i];
      for (std::size_t l = 0; l < landings; ++l) {
        const int side = side_of[l];
        const bool below_zero = b.speed_first[side][i] < 0;
        const double w0 = b.speed_weight[side][0][i], w1 = b.speed_weight[side][1][i];
        const double w2 = b.speed_weight[side][2][i], w3 = b.speed_weight[side][3][i];
        const double range_m = speed_sum(sums[l], 0, below_zero, w0, w1, w2, w3);
        const double time_s = with_time ? speed_sum(sums[l], 1, below_zero, w0, w1, w2, w3) : 0.0;
        // landing(): the range along the unit vector (rx, ry)/u, carried by the wind for the flight time.
        const double u = b.speed[side][i], rx = b.relative_x[side][i], ry = b.relative_y[i];
        const double along = u > 0.0 ? range_m / u : 0.0;
        const double x_m = side == 0 ? double{sample.x_m} : -1.0 * sample.x_m;
        const std::size_t out = side == 1 && sides == Sides::kBoth ? count + first + i : first + i;
        landing_x_m[out] = x_m + along * rx + wind_x_m_s * time_s;
        landing_y_m[out] = sample.y_m + along * ry + wind_y_m_s * time_s;
      }
    }
  }
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
