#pragma once
// The landings of one material's granules tabulated over everything a drag-only flight depends on, so
// that a prediction anywhere in its domain evaluates an interpolant per granule instead of integrating
// its flight, from every launch sample (no thinning), at any disc height and wind in the domain.
//
// Under gravity and drag alone, or gravity alone (no lift, no spin: a table built with
// "flight_effects":"drag", or with none) a granule of
// the material's density is fully described by its diameter d, and its flight from a launch at height h
// with horizontal speed u and vertical speed v_z stays in the vertical plane through the horizontal
// velocity (the forces all lie in it). So its horizontal range R and flight time T are functions of four
// numbers, R(d, v_z, u, h) and T(d, v_z, u, h), whatever the disc, row, drop point or disc speed:
//   - still air: landing = p_h + R(u) · V_h/|V_h|;
//   - a uniform horizontal wind W: drag depends only on the velocity relative to the air, and gravity and
//     the ground are the same in the frame moving with the air (a Galilean change of frame), so the flight
//     is the still-air flight of the relative launch velocity V_h − W, carried along by W for its flight
//     time: landing = p_h + R(u′) · (V_h − W)/u′ + W · T(u′), u′ = |V_h − W|.
// R is odd and T even in a signed horizontal speed (a granule thrown backwards lands at −R), so the speed
// axis is continued through u = 0 by these symmetries and the interpolant stays smooth there.
//
// The grid's nodes are equally spaced on each axis; the interpolant is the tensor product of cubic
// Lagrange polynomials through the four nodes around the point on each axis (continuous everywhere:
// two neighbouring stencils agree at their shared nodes). Its error against flying each granule is
// measured (tests/predict/test_landing_grid.cpp, bench_predict counter max_landing_error_m).
//
// The values are floats (1e-6 relative: 0.04 mm on a 40 m range), R and T side by side per node, the
// speed axis innermost so that a stencil line's four speeds of both are one 32-byte read (one AVX
// register, or two SSE ones). Evaluation does not allocate.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory_resource>
#include <span>
#include <vector>

#include "libspread/io/tables/table_format.hpp"
#include "libspread/physics/flight/flight.hpp"

namespace spread::predict {

// One equally spaced axis: nodes first + k · step for k = 0 .. count − 1 (units of the quantity).
struct GridAxis {
  double first = 0.0;
  double step = 1.0;
  std::uint32_t count = 0;
  double last() const { return first + step * static_cast<double>(count - 1); }
  bool operator==(const GridAxis&) const = default;
};

class LandingGrid {
 public:
  // Axes, in the order of the values' layout (outermost first).
  enum Axis : std::size_t { kDiameter, kVerticalSpeed, kHeight, kSpeed, kAxisCount };
  // m, m/s, √m, m/s; kSpeed.first must be 0. The height axis is in √h: from a low launch R and T grow like
  // √h (the fall time), so they are nearly linear in √h and a few nodes hold them.
  using Axes = std::array<GridAxis, kAxisCount>;

  explicit LandingGrid(std::pmr::memory_resource* memory = std::pmr::get_default_resource());

  // Still-air effects whose flights the grid can hold: drag or nothing.
  static bool holds(flight::EffectSet still_air_effects) { return (still_air_effects & ~flight::kDrag) == 0; }

  // Flies every node: a granule of `density_kg_m3` and the node's diameter, launched from height h with
  // velocity (u, 0, v_z) in still air under gravity and `effects` (holds() must be true; fly_many, SIMD
  // lanes), and records R and T. Returns false, leaving the grid empty, when a flight did not land within
  // the settings' limits.
  bool build(const Axes& axes, double density_kg_m3, flight::EffectSet effects, const flight::Settings& settings,
             const flight::Air& air);

  // Takes values flown earlier by build() with these axes and effects (a table's stored landing data).
  // False, leaving the grid empty, when the count is not value_count(axes), a value is not finite, or the
  // axes or effects are ones build() refuses.
  bool restore(const Axes& axes, flight::EffectSet effects, std::span<const float> values);

  bool empty() const { return values_.empty(); }
  const Axes& axes() const { return axes_; }
  flight::EffectSet effects() const { return effects_; }  // the still-air effects it was flown with
  // The values as build() flew them and restore() takes them: all R, then all T.
  std::vector<float> values() const;
  std::size_t bytes() const { return sizeof(float) * values_.size(); }
  static std::size_t value_count(const Axes& axes);
  // Sums the stencil in AVX registers (on x86 processors that have AVX, chosen at construction) or in SSE
  // ones, and sets up a block's stencils eight samples at a time in AVX-512 registers where the processor
  // has them too (else four at a time): the same bits every way. set_avx(true) takes the widest the
  // processor has; set_avx512(false) then keeps to AVX. Each returns whether its registers are now used.
  bool set_avx(bool enabled);
  bool set_avx512(bool enabled);

  // R (m) and T (s) of a launch with horizontal speed speed_m_s >= 0. Arguments slightly outside the axes
  // extrapolate the edge stencil.
  void range_and_time(double diameter_m, double vertical_speed_m_s, double height_m, double speed_m_s,
                      double& range_m, double& time_s) const;

  // Landing (x, y) of a granule launched from (x_m, y_m) at height_m with horizontal velocity
  // (vx_m_s, vy_m_s) and vertical speed vz_m_s, in the horizontal wind (wind_x_m_s, wind_y_m_s).
  void landing(double diameter_m, double x_m, double y_m, double height_m, double vx_m_s, double vy_m_s,
               double vz_m_s, double wind_x_m_s, double wind_y_m_s, double& landing_x_m, double& landing_y_m) const;
  // landing() of the launch as given ([0]) and of its mirror image x → −x ([1]: position x_m and velocity
  // vx_m_s negated; a sample's right disc), both in the wind, bit for bit as two calls of landing() in a
  // wind would give them: the two share the stencil's diameter, vertical speed and height.
  void mirrored_landings(double diameter_m, double x_m, double y_m, double height_m, double vx_m_s, double vy_m_s,
                         double vz_m_s, double wind_x_m_s, double wind_y_m_s, double (&landing_x_m)[2],
                         double (&landing_y_m)[2]) const;

  // Which landings of a launch sample sample_landings() gives: the launch as stored (the left disc), its
  // mirror image x → −x (the right disc), or both.
  enum class Sides { kAsStored, kMirrored, kBoth };
  // The stencils of a block of samples, set up side by side (sample_landings' scratch; a prediction's
  // workspace holds one, so that none is on the caller's stack).
  static constexpr std::size_t kBlock = 32;
  struct StencilBlock {
    double relative_x[2][kBlock];  // launch velocity relative to the air, m/s, per side
    double relative_y[kBlock];
    double speed[2][kBlock];  // its magnitude u′
    double speed_weight[2][4][kBlock];
    float line_weight[16][kBlock];  // w_d · w_v, line 4a + b
    float height_weight[4][kBlock];
    std::int32_t diameter_first[kBlock], vertical_first[kBlock], height_first[kBlock];
    std::int32_t speed_first[2][kBlock];
  };
  // The landings of launch samples (normalised, as a table's rows store them) launched at rim speed ω R
  // from `disc_height_m` in the horizontal wind: for sample i, position (x, y, z + disc_height_m) and
  // velocity rim_speed_m_s · (vx, vy, vz)_norm, landing() of it (kAsStored: into [i]), of its mirror image
  // (kMirrored: into [i]), or mirrored_landings() of it (kBoth: as stored into [i], mirrored into
  // [count + i]) — bit for bit. The stencils' indices and weights of a block of samples are computed side
  // by side in SIMD lanes (AVX where the processor has it: the same operations lane by lane), which one
  // landing at a time computes one lane at a time (measured there: more time than the grid's sums).
  void sample_landings(std::span<const tables::LaunchSample> samples, double rim_speed_m_s, double disc_height_m,
                       double wind_x_m_s, double wind_y_m_s, Sides sides, StencilBlock& scratch,
                       std::span<double> landing_x_m, std::span<double> landing_y_m) const;

 private:
  // R (and T) of one or two horizontal speeds (speeds_m_s.size() <= 2) at the same diameter, vertical
  // speed and height.
  template <bool kWithTime>
  void interpolate(double diameter_m, double vertical_speed_m_s, double height_m, std::span<const double> speeds_m_s,
                   double* range_m, double* time_s) const;

  Axes axes_{};
  flight::EffectSet effects_ = 0;
  std::array<double, kAxisCount> inverse_step_{};
  // R at 2 · [((d · N_vz + v) · N_h + h) · N_u + u], T right after it: a stencil line's four speeds of
  // both are one 32-byte read.
  std::pmr::vector<float> values_;
  bool avx_ = false;
  bool avx512_ = false;
};

// The conditions a table's landing grids cover: what a controller meets in the field. Requests inside it
// are answered from the grid, from every launch sample.
//   - Disc heights above the surface the granules land on, 0.2–2.0 m: mounted and trailed twin-disc
//     spreaders are set from a few decimetres (border spreading, a low linkage) to well over a metre
//     (late top-dressing over a standing crop); with a machine's stored height h0 outside that range,
//     from h0/2 or up to 2 h0.
//   - Horizontal winds up to 10 m/s (Beaufort 5: spreading granular fertiliser stops well before it).
struct LandingDomain {
  double min_disc_height_m = 0.2;
  double max_disc_height_m = 2.0;
  double max_wind_m_s = 10.0;
  bool covers(double disc_height_m, double wind_x_m_s, double wind_y_m_s) const {
    return disc_height_m >= min_disc_height_m && disc_height_m <= max_disc_height_m &&
           wind_x_m_s * wind_x_m_s + wind_y_m_s * wind_y_m_s <= max_wind_m_s * max_wind_m_s;
  }
};
LandingDomain landing_domain_for(double stored_disc_height_m);

// Nodes per axis of a material's grid (LandingGrid::Axis order): 320 KB per material. Measured on the
// product's default table, every 5th launch sample at random disc heights and winds across the domain
// against the sample flown at the tight reference tolerance (bench_predict BM_LandingGridError): 1.1–2.8
// mm root mean square, 1.1–1.4 cm at worst by material — about the accuracy of a default flight (1 cm).
inline constexpr std::array<std::uint32_t, LandingGrid::kAxisCount> kGridNodes = {10, 20, 10, 20};

// Axes that cover every launch of a material's samples (normalised, as stored in its rows) at disc speeds
// up to max_rim_speed_m_s (ω R of its fastest row), launched from any disc height of the domain into any of
// its winds: the samples' diameters and vertical speeds, their heights above the disc plus the domain's
// disc heights, horizontal speeds relative to the air from 0 to the fastest plus the strongest wind —
// each with a margin of one node, as interpolated samples between rows can reach a little beyond.
LandingGrid::Axes landing_grid_axes(std::span<const tables::LaunchSample> samples, double max_rim_speed_m_s,
                                    const LandingDomain& domain);

}  // namespace spread::predict
