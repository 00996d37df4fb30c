#pragma once
// Landings of a table's launch samples flown once when the table is opened, so that a prediction under the
// machine's own conditions evaluates a polynomial per granule instead of integrating its flight.
//
// Valid for flights whose forces keep them in one vertical plane: gravity and drag only (a table built with
// "flight_effects":"drag", or none), still air or a horizontal wind. Then, for a granule launched from p
// with horizontal velocity V_h and vertical velocity v_z:
//   - in still air the flight stays in the vertical plane through V_h, so the landing is
//       p_h + R(|V_h|) · V_h/|V_h|,  with the range R and flight time T functions of |V_h| (v_z, the launch
//     height and the granule fixed);
//   - in a uniform horizontal wind W drag depends only on the velocity relative to the air, and gravity and
//     the ground plane are the same in the frame that moves with the air (a Galilean change of frame), so
//     the flight is the still-air flight of the relative launch velocity V_h − W, carried along by W for
//     its flight time:  landing = p_h + R(u′) · (V_h − W)/u′ + W · T(u′),  u′ = |V_h − W|.
// R is odd and T even in a signed horizontal speed (a granule thrown backwards lands at −R), so speeds
// below zero are flown as |u| and the sign is put back: the functions stay smooth through u = 0.
//
// A segment caches one row (one node, t = 0) or a pair of neighbouring rows (nodes t = 0, ⅓, ⅔, 1 of the
// interpolation weight t, with the launch samples the interpolation gives at each node). Every launch
// sample the interpolation yields is linear in t (launch_interpolation.hpp) and the disc speed ω is linear
// in t, so R and T are smooth in t. At each node j each granule is flown at four horizontal speeds
// u_j + Δ·(−1, −⅓, ⅓, 1) (its own speed u_j; Δ = kWindRadius_m_s), the rest of its launch state unchanged,
// and R and T are kept as the cubics through these four points. A landing is then these cubics at the
// speed offset u′ − u_j of each node, combined by the cubic Lagrange weights of t across the nodes
// t = 0, ⅓, ⅔, 1. Its error against flying the granule is measured in
// bench_predict (counter max_landing_error_m) and tested (tests/predict/test_landing_cache.cpp).
//
// The cache holds 9 floats per granule and node (float: 1e-6 m on a 20 m range) and costs 4 flights per
// granule and node when the table is opened. Evaluation does not allocate.
#include <cstddef>
#include <memory_resource>
#include <span>
#include <vector>

#include "libspread/physics/flight/flight.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::predict {

class LandingCache {
 public:
  // Wind speeds (each landing's horizontal speed offset) the cache covers: fertiliser is spread in winds
  // below about 5 m/s (Beaufort 3); a stronger wind is flown.
  static constexpr double kWindRadius_m_s = 5.0;
  // Horizontal speeds flown per granule and node, equally spaced over u ± Δ (a cubic in the speed).
  static constexpr std::size_t kSpeedNodes = 4;
  // Nodes of the interpolation weight t for a pair of rows, equally spaced over [0, 1] (a cubic in t).
  static constexpr std::size_t kPairNodes = 4;
  // Flight effects under which flights are planar (see above): the cache is made only for these.
  static bool covers(flight::EffectSet still_air_effects) { return (still_air_effects & ~flight::kDrag) == 0; }

  // What the granules of one node are flown with.
  struct Flying {
    double rim_speed_m_s = 0.0;    // ω R at this node
    double disc_height_m = 0.0;    // the machine's stored height (launch z = sample z + this)
    double density_kg_m3 = 0.0;    // the material's
    flight::EffectSet effects = 0;  // still-air effects (covers() holds)
    flight::Settings settings;
  };

  explicit LandingCache(std::pmr::memory_resource* memory = std::pmr::get_default_resource());

  // Nodes of the weight t: {0} for a row, {0, ⅓, ⅔, 1} for a pair of rows. Every node has the same number of
  // samples (the interpolation's output count). Flies kSpeedNodes flights per sample (fly_many, in chunks; allocates
  // only its own arrays). Returns false, leaving the cache empty, when a flight did not land (then the
  // caller flies instead).
  bool build(std::span<const std::span<const tables::LaunchSample>> node_samples, std::span<const Flying> node_flying);

  bool empty() const { return node_count_ == 0; }
  std::size_t node_count() const { return node_count_; }
  std::size_t sample_count() const { return sample_count_; }
  std::size_t bytes() const { return sizeof(float) * data_.size(); }

  // Weights of the nodes at interpolation weight t in [0, 1] (a row: t = 0), once per prediction.
  void node_weights(double t, double (&weight)[kPairNodes]) const;
  // Landing (x, y) of sample `index` launched from (launch_x, launch_y) with horizontal velocity
  // (launch_vx, launch_vy) (its actual launch at t: mirrored for the right disc, scaled by ω) in the
  // horizontal wind (wind_x, wind_y), |wind| <= kWindRadius_m_s; node_weight from node_weights(t).
  struct Launch {
    double x_m, y_m, vx_m_s, vy_m_s;
  };
  void landing(std::size_t index, const double (&node_weight)[kPairNodes], const Launch& launch, double wind_x_m_s,
               double wind_y_m_s, double& x_m, double& y_m) const;

  // Floats per granule and node: its horizontal launch speed u at the node (m/s), then the cubics of the
  // range R (m) and the flight time T (s) in s = (u′ − u)/Δ, four monomial coefficients each.
  static constexpr std::size_t kFloatsPerNode = 9;

 private:
  std::size_t node_count_ = 0;
  std::size_t sample_count_ = 0;
  // [(index · node_count + node) · kFloatsPerNode + k]: a granule's nodes side by side, read in one pass.
  std::pmr::vector<float> data_;
};

}  // namespace spread::predict
