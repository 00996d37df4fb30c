#include "libspread/physics/dem/inlet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "libspread/core/unit_uniform.hpp"

namespace spread::dem {

LognormalDiameter::LognormalDiameter(double mean_m, double sd_m) {
  if (!(mean_m > 0.0) || !(sd_m >= 0.0)) throw std::invalid_argument("inlet: diameter mean must be > 0 and sd >= 0");
  s = std::sqrt(std::log(1.0 + (sd_m * sd_m) / (mean_m * mean_m)));
  m = std::log(mean_m) - 0.5 * s * s;
}
double LognormalDiameter::min_m() const { return std::exp(m - 3.0 * s); }
double LognormalDiameter::max_m() const { return std::exp(m + 3.0 * s); }
double LognormalDiameter::mean_cube_m3() const { return std::exp(3.0 * m + 4.5 * s * s); }

namespace {
std::pair<double, double> diameter_range_m(double mean_m, double sd_m, const SieveAnalysis& sieve) {
  if (!sieve.empty()) {
    const SieveNumberDistribution number(sieve);
    return {number.min_m(), number.max_m()};
  }
  const LognormalDiameter dist(mean_m, sd_m);
  return {dist.min_m(), dist.max_m()};
}
}  // namespace

std::pair<double, double> inlet_diameter_range_m(const InletParams& params) {
  if (params.components.empty()) return diameter_range_m(params.diameter_mean_m, params.diameter_sd_m, params.sieve);
  std::pair<double, double> range{std::numeric_limits<double>::infinity(), 0.0};
  for (const InletComponent& c : params.components) {
    const auto [low, high] = diameter_range_m(c.diameter_mean_m, c.diameter_sd_m, c.sieve);
    range = {std::min(range.first, low), std::max(range.second, high)};
  }
  return range;
}

Inlet::Feed Inlet::feed_of(double mean_m, double sd_m, const SieveAnalysis& sieve, int material, double mass_rate_kg_s,
                           double density_kg_m3) const {
  Feed feed{material, LognormalDiameter(mean_m, sd_m), std::nullopt};
  if (!sieve.empty()) {
    const std::string problem = sieve_problem(sieve);
    if (!problem.empty()) throw std::invalid_argument("inlet: " + problem);
    feed.sieve.emplace(sieve);
  }
  if (!(density_kg_m3 > 0.0)) throw std::invalid_argument("inlet: the fed material's density must be > 0");
  const double mean_cube_m3 = feed.sieve ? feed.sieve->mean_cube_m3() : feed.dist.mean_cube_m3();
  feed.rate_per_s = mass_rate_kg_s / (density_kg_m3 * kPi / 6.0 * mean_cube_m3);
  return feed;
}

Inlet::Inlet(const InletParams& params, double density_kg_m3) : params_(params), rng_(params.seed) {
  if (!(params.radius_m > 0.0)) throw std::invalid_argument("inlet: radius_m must be > 0");
  if (!(params.mass_rate_kg_s > 0.0)) throw std::invalid_argument("inlet: mass flow must be > 0");
  if (!(params.batch_interval_s > 0.0)) throw std::invalid_argument("inlet: batch_interval_s must be > 0");
  if (params.components.empty()) {
    feeds_.push_back(feed_of(params.diameter_mean_m, params.diameter_sd_m, params.sieve, params.material,
                             params.mass_rate_kg_s, density_kg_m3));
  }
  for (const InletComponent& c : params.components) {
    if (!(c.mass_fraction > 0.0)) throw std::invalid_argument("inlet: a blend component's mass fraction must be > 0");
    feeds_.push_back(feed_of(c.diameter_mean_m, c.diameter_sd_m, c.sieve, c.material, c.mass_fraction * params.mass_rate_kg_s,
                             c.density_kg_m3));
  }
  for (const Feed& feed : feeds_) {
    rate_per_s_ += feed.rate_per_s;
    max_diameter_m_ = std::max(max_diameter_m_, feed.max_m());
  }
  double cumulative = 0.0;
  for (Feed& feed : feeds_) {
    cumulative += feed.rate_per_s;
    feed.cumulative_share = cumulative / rate_per_s_;
  }
  feeds_.back().cumulative_share = 1.0;
}

// Own distributions (std:: ones differ between standard libraries): 53-bit uniform, Box–Muller.
double Inlet::uniform() { return unit_uniform(rng_()); }
double Inlet::normal() {
  const double u1 = 1.0 - uniform(), u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

// A blend's component by its share of the granules (one uniform); a single material draws nothing, so
// its stream of draws is the same as before blends existed.
const Inlet::Feed& Inlet::next_feed() {
  if (feeds_.size() == 1) return feeds_.front();
  const double u = uniform();
  for (const Feed& feed : feeds_) {
    if (u < feed.cumulative_share) return feed;
  }
  return feeds_.back();
}

// A sieve analysis: one uniform through its inverse number distribution. The lognormal: Box–Muller,
// redrawn outside its truncation.
double Inlet::next_diameter_m(const Feed& feed) {
  if (feed.sieve) return feed.sieve->diameter_m(uniform());
  double d;
  do {
    d = std::exp(feed.dist.m + feed.dist.s * normal());
  } while (d < feed.dist.min_m() * (1 - 1e-12) || d > feed.dist.max_m() * (1 + 1e-12));
  return d;
}

std::size_t Inlet::release_due(DemEngine& engine, double t_s) {
  if (t_s + 1e-15 < next_batch_s_) return 0;
  next_batch_s_ += params_.batch_interval_s;
  // Count due so far at the average rate (the rate is imposed exactly in the mean, Sect. 3.2).
  const double due = rate_per_s_ * t_s;
  std::size_t added = 0;
  while (static_cast<double>(released_) + 1.0 <= due + 1e-9) {
    const Feed& feed = next_feed();
    const double d = next_diameter_m(feed);
    const double r = 0.5 * d;
    const double reach = std::max(0.0, params_.radius_m - r);
    bool placed = false;
    for (int attempt = 0; attempt < 40 && !placed; ++attempt) {
      // Uniform over the disc of radius `reach`.
      const double rr = reach * std::sqrt(uniform()), a = 2.0 * kPi * uniform();
      // Release volume: the inlet circle times a slab of 4 largest diameters above it, so a batch of
      // several particles finds room without overlaps (the seed's inlet mesh spaces them the same way).
      const double dz = 4.0 * max_diameter_m_ * uniform();
      const Vec3 pos = params_.centre_m + Vec3(rr * std::cos(a), rr * std::sin(a), dz);
      if (engine.overlaps_particle(pos, r)) continue;
      engine.add_particle(pos, Vec3(0.0, 0.0, -params_.release_speed_m_s), r, feed.material);
      placed = true;
    }
    if (!placed) {
      ++deferred_;
      break;  // the circle is crowded: try again next batch
    }
    ++released_;
    ++added;
  }
  return added;
}

}  // namespace spread::dem
