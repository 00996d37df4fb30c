#include "libspread/analysis/predict/landing_cache.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spread::predict {

namespace {

constexpr std::size_t kBuildChunk = 1024;  // flights per fly_many call while building
constexpr std::size_t kSpeeds = LandingCache::kSpeedNodes;
static_assert(kSpeeds == 4 && LandingCache::kPairNodes == 4, "the cubic fits below assume four nodes");
constexpr std::size_t kStride = LandingCache::kFloatsPerNode;

// Speed node k at s_k = −1, −⅓, ⅓, 1 of the scaled offset s = (u′ − u)/Δ.
double speed_node(std::size_t k) { return -1.0 + 2.0 * static_cast<double>(k) / 3.0; }

// Monomial coefficients c of the cubic through (s_k, f_k), s_k = −1, −⅓, ⅓, 1: f(s) = c0 + c1 s + c2 s² + c3 s³
// (the Vandermonde system of these nodes solved once by hand).
void cubic_coefficients(const double (&f)[4], float* c) {
  const double even_outer = f[0] + f[3], even_inner = f[1] + f[2];
  const double odd_outer = f[3] - f[0], odd_inner = f[2] - f[1];
  c[0] = static_cast<float>((9.0 * even_inner - even_outer) / 16.0);
  c[2] = static_cast<float>(9.0 * (even_outer - even_inner) / 16.0);
  c[1] = static_cast<float>((27.0 * odd_inner - odd_outer) / 16.0);
  c[3] = static_cast<float>(9.0 * (odd_outer - 3.0 * odd_inner) / 16.0);
}

double horner(const float* c, double s) {
  return static_cast<double>(c[0]) +
         s * (static_cast<double>(c[1]) + s * (static_cast<double>(c[2]) + s * static_cast<double>(c[3])));
}

}  // namespace

LandingCache::LandingCache(std::pmr::memory_resource* memory) : data_(memory) {}

void LandingCache::node_weights(double t, double (&weight)[kPairNodes]) const {
  if (node_count_ == 1) {
    weight[0] = 1.0;
    weight[1] = weight[2] = weight[3] = 0.0;
    return;
  }
  // Cubic Lagrange basis of the nodes t = 0, ⅓, ⅔, 1 (σ = 3t at 0, 1, 2, 3).
  const double sigma = 3.0 * t;
  weight[0] = -(sigma - 1.0) * (sigma - 2.0) * (sigma - 3.0) / 6.0;
  weight[1] = sigma * (sigma - 2.0) * (sigma - 3.0) / 2.0;
  weight[2] = -sigma * (sigma - 1.0) * (sigma - 3.0) / 2.0;
  weight[3] = sigma * (sigma - 1.0) * (sigma - 2.0) / 6.0;
}

bool LandingCache::build(std::span<const std::span<const tables::LaunchSample>> node_samples,
                         std::span<const Flying> node_flying) {
  if (node_samples.size() != node_flying.size() ||
      (node_samples.size() != 1 && node_samples.size() != kPairNodes)) {
    throw std::invalid_argument("LandingCache::build: 1 or kPairNodes nodes, each with its flying conditions");
  }
  const std::size_t n = node_samples[0].size();
  for (const auto& samples : node_samples) {
    if (samples.size() != n) throw std::invalid_argument("LandingCache::build: nodes of different sample counts");
  }
  for (const auto& flying : node_flying) {
    if (!covers(flying.effects)) throw std::invalid_argument("LandingCache::build: effects whose flights are not planar");
  }
  const std::size_t nodes = node_samples.size();
  data_.assign(n * nodes * kStride, 0.0f);
  node_count_ = nodes;
  sample_count_ = n;

  std::vector<flight::Granule> granules(kBuildChunk);
  std::vector<flight::State> launches(kBuildChunk);
  std::vector<flight::Landing> landings(kBuildChunk);
  std::vector<double> range_m(kSpeeds * n), time_s(kSpeeds * n);
  const flight::Air still_air;
  // Horizontal launch speed (m/s) and direction of a sample at a node; any direction for a granule thrown
  // straight up.
  struct Horizontal {
    double speed_m_s, ux, uy;
  };
  const auto horizontal = [](const tables::LaunchSample& s, const Flying& fl) {
    const double vx = fl.rim_speed_m_s * s.vx_norm, vy = fl.rim_speed_m_s * s.vy_norm;
    const double u = std::hypot(vx, vy);
    return u > 0.0 ? Horizontal{u, vx / u, vy / u} : Horizontal{0.0, 1.0, 0.0};
  };
  // Flight f of a node: sample f / kSpeeds at speed node f % kSpeeds.
  for (std::size_t node = 0; node < nodes; ++node) {
    const Flying& fl = node_flying[node];
    const auto samples = node_samples[node];
    const std::size_t flights = kSpeeds * n;
    for (std::size_t first = 0; first < flights; first += kBuildChunk) {
      const std::size_t count = std::min(kBuildChunk, flights - first);
      for (std::size_t c = 0; c < count; ++c) {
        const std::size_t f = first + c, i = f / kSpeeds;
        const tables::LaunchSample& s = samples[i];
        const Horizontal h = horizontal(s, fl);
        const double speed = std::abs(h.speed_m_s + kWindRadius_m_s * speed_node(f % kSpeeds));
        granules[c] = flight::Granule{s.diameter_m, fl.density_kg_m3};
        launches[c].position_m = Vec3(s.x_m, s.y_m, s.z_m + fl.disc_height_m);
        launches[c].velocity_m_s = Vec3(speed * h.ux, speed * h.uy, fl.rim_speed_m_s * s.vz_norm);
        launches[c].spin_rad_s = Vec3::Zero();  // no effect here acts on spin or through it
      }
      flight::fly_many(std::span(granules).first(count), std::span(launches).first(count), 0.0, still_air,
                       fl.effects, fl.settings, std::span(landings).first(count));
      for (std::size_t c = 0; c < count; ++c) {
        const std::size_t f = first + c, i = f / kSpeeds;
        const flight::Landing& landing = landings[c];
        if (!landing.landed) {
          data_.clear();
          node_count_ = sample_count_ = 0;
          return false;
        }
        const tables::LaunchSample& s = samples[i];
        const Horizontal h = horizontal(s, fl);
        const double signed_speed = h.speed_m_s + kWindRadius_m_s * speed_node(f % kSpeeds);
        // Range along the flown direction, negative for a signed speed below zero (R is odd in u).
        const double range =
            h.ux * (landing.state.position_m.x() - s.x_m) + h.uy * (landing.state.position_m.y() - s.y_m);
        range_m[f] = signed_speed < 0.0 ? -range : range;
        time_s[f] = landing.flight_time_s;
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      float* entry = &data_[(i * nodes + node) * kStride];
      entry[0] = static_cast<float>(horizontal(samples[i], fl).speed_m_s);
      double r[4], t[4];
      for (std::size_t k = 0; k < kSpeeds; ++k) {
        r[k] = range_m[kSpeeds * i + k];
        t[k] = time_s[kSpeeds * i + k];
      }
      cubic_coefficients(r, entry + 1);
      cubic_coefficients(t, entry + 5);
    }
  }
  return true;
}

void LandingCache::landing(std::size_t index, const double (&node_weight)[kPairNodes], const Launch& launch,
                           double wind_x_m_s, double wind_y_m_s, double& x_m, double& y_m) const {
  const double vx = launch.vx_m_s - wind_x_m_s, vy = launch.vy_m_s - wind_y_m_s;
  const double u = std::sqrt(vx * vx + vy * vy);
  constexpr double kInverseRadius = 1.0 / kWindRadius_m_s;
  const float* entry = &data_[index * node_count_ * kStride];
  double range_m = 0.0, time_s = 0.0;
  for (std::size_t node = 0; node < node_count_; ++node, entry += kStride) {
    const double s = (u - static_cast<double>(entry[0])) * kInverseRadius;
    range_m += node_weight[node] * horner(entry + 1, s);
    time_s += node_weight[node] * horner(entry + 5, s);
  }
  const double along = u > 0.0 ? range_m / u : 0.0;  // the range along the unit vector (vx, vy)/u
  x_m = launch.x_m + along * vx + wind_x_m_s * time_s;
  y_m = launch.y_m + along * vy + wind_y_m_s * time_s;
}

}  // namespace spread::predict
