#pragma once
// Measurements of a drum bed from the particle data alone (no engine internals), on one snapshot, and
// the flow-regime label from their averages over a rotation window (thresholds in docs/drum.md).
#include <string>
#include <vector>

#include "libspread/physics/dem/particles.hpp"

namespace spread::drum {

struct DrumGeometry {
  double radius_m = 0.05;
  double length_m = 0.01;
  double angular_velocity_rad_s = 0.0;  // about +z, counter-clockwise
};

struct Snapshot {
  double time_s = 0.0;
  double angle_of_repose_deg = 0.0;   // atan of the line fitted to the free-surface particles (Sect. 4)
  double surface_sagitta = 0.0;       // max |surface − line| / chord: 0 flat (rolling), larger for an S/kidney shape
  int surface_points = 0;
  double airborne_fraction = 0.0;     // in free flight: no particle or mantle within d/4, no in-plane contact force
  double co_rotating_fraction = 0.0;  // particles moving with the wall: |v − ω×r| < 0.2 ω |r|
  double wall_coverage = 0.0;         // share of 10° sectors of the wall with a particle within 1.5 d of it
  double wall_speed_ratio = 0.0;      // tangential speed of the layer touching the wall under the bed (±45°) / ωR (~1: no slip)
  double centroid_angle_deg = 0.0;    // bed centroid angle from straight down, + towards +x (lift of the bed)
  double lacey_index = 0.0;           // two species only (else 0)
};

Snapshot measure(const dem::ParticleArrays& p, const DrumGeometry& g, double time_s);

// Lacey (1954) mixing index M = (σ0² − σ²)/(σ0² − σ_R²) of the species-1 fraction over square cells of
// `cell_m` in the cross-section: σ0² = p(1−p) fully segregated, σ_R² = p(1−p)/n̄ random, σ² the
// particle-weighted variance over cells holding at least 3 particles. 0 segregated, 1 random.
double lacey_index(const dem::ParticleArrays& p, double cell_m);

enum class Regime { kSlipping, kSlumping, kRolling, kCascading, kCataracting, kCentrifuging };
std::string regime_name(Regime r);

struct RegimeEvidence {
  Regime regime = Regime::kRolling;
  int samples = 0;
  double froude = 0.0;
  double angle_of_repose_deg = 0.0;      // mean over samples
  double angle_of_repose_sd_deg = 0.0;   // spread over samples (slumping: avalanches)
  double surface_sagitta = 0.0;
  double airborne_fraction = 0.0;
  double co_rotating_fraction = 0.0;
  double wall_coverage = 0.0;
  double wall_speed_ratio = 0.0;
  double centroid_angle_deg = 0.0;
  double lacey_index = 0.0;
  std::string reason;                    // the rule that fired, with its numbers
};

RegimeEvidence classify(const std::vector<Snapshot>& window, double froude);

}  // namespace spread::drum
