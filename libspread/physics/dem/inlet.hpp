#pragma once
// Inlet (seed Sect. 3.2): lognormal diameters with a given arithmetic mean and standard deviation, or
// those of a sieve analysis (libspread/core/sieve_analysis.hpp), a particle rate set from the mass feed
// rate through the distribution's E[d³], and release at random points of the inlet circle without
// overlapping particles already there.
#include <cstdint>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "libspread/core/sieve_analysis.hpp"

#include "libspread/physics/dem/engine.hpp"

namespace spread::dem {

// One component of a blend fed through the inlet: its material, its share of the feed's mass and its own
// size distribution (lognormal or sieve analysis, as InletParams's own fields for a single material).
struct InletComponent {
  int material = 0;                 // index into the run's materials
  double density_kg_m3 = 0.0;       // that material's density (for the component's granule rate)
  double mass_fraction = 0.0;       // > 0; the components' fractions sum to 1
  double diameter_mean_m = 3e-3;
  double diameter_sd_m = 0.0;
  SieveAnalysis sieve;
};

struct InletParams {
  Vec3 centre_m = Vec3::Zero();     // centre of the release circle (inertial); particles appear in a
                                    // slab from here up to 4 largest diameters higher
  double radius_m = 0.0145;
  double mass_rate_kg_s = 0.11;
  double diameter_mean_m = 3e-3;    // arithmetic mean of the lognormal
  double diameter_sd_m = 0.0;       // arithmetic sd; 0 = one size
  SieveAnalysis sieve;              // non-empty: diameters from this analysis instead of the lognormal
  double release_speed_m_s = 0.5;   // downwards, as the granules leave the metering opening
  int material = 0;
  // Non-empty: a blend. Each granule draws its component (by the components' granule shares, so the
  // released mass splits by mass_fraction), then its diameter from that component's distribution; the
  // single-material fields above (sizes, material) are then unused.
  std::vector<InletComponent> components;
  std::uint64_t seed = 1;
  double batch_interval_s = 1e-3;   // particles are released in batches (each batch rebuilds the pair list)
};

// Lognormal in terms of the arithmetic mean μ and sd σ: s² = ln(1 + σ²/μ²), m = ln μ − s²/2.
// Samples are truncated to exp(m ± 3s) so one outlier cannot set the time step or cell size.
struct LognormalDiameter {
  double m = 0.0, s = 0.0;
  LognormalDiameter(double mean_m, double sd_m);
  double min_m() const;
  double max_m() const;
  double mean_cube_m3() const;  // E[d³] = exp(3m + 9s²/2) (untruncated moment)
};

// The smallest and largest diameter (m) the inlet releases: the lognormal's truncation, or the bottom and
// top of the sieve analysis's intervals with mass; of a blend, over its components.
std::pair<double, double> inlet_diameter_range_m(const InletParams& params);

class Inlet {
 public:
  // density_kg_m3: the single material's (a blend's components carry their own).
  Inlet(const InletParams& params, double density_kg_m3);
  // Particles per second so that the mean mass rate is the feed rate: Q / (ρ π/6 E[d³]); of a blend,
  // Σ_c w_c Q / (ρ_c π/6 E_c[d³]).
  double particle_rate_per_s() const { return rate_per_s_; }
  const LognormalDiameter& diameters() const { return feeds_.front().dist; }
  // Releases the particles due by time t (whole batches). Returns how many were added.
  std::size_t release_due(DemEngine& engine, double t_s);
  std::uint64_t released() const { return released_; }
  std::uint64_t deferred() const { return deferred_; }  // placements retried in a later batch

 private:
  // One size distribution the inlet draws from: the single material's, or one blend component's.
  struct Feed {
    int material = 0;
    LognormalDiameter dist;
    std::optional<SieveNumberDistribution> sieve;
    double rate_per_s = 0.0;          // granules per second of this feed
    double cumulative_share = 1.0;    // of the granules, this feed's and the ones before it
    double max_m() const { return sieve ? sieve->max_m() : dist.max_m(); }
  };
  Feed feed_of(double mean_m, double sd_m, const SieveAnalysis& sieve, int material, double mass_rate_kg_s,
               double density_kg_m3) const;
  double uniform();
  double normal();
  const Feed& next_feed();
  double next_diameter_m(const Feed& feed);
  InletParams params_;
  std::vector<Feed> feeds_;
  double max_diameter_m_ = 0.0;
  double rate_per_s_ = 0.0;
  std::mt19937_64 rng_;
  double next_batch_s_ = 0.0;
  std::uint64_t released_ = 0;
  std::uint64_t deferred_ = 0;
};

}  // namespace spread::dem
