#pragma once
// Launch samples from the analytic vane model (patterson_reece.hpp), for tables without DEM.
//
// Sample k (k = 0 … n−1) is built from a 4-D low-discrepancy point (Roberts' R4 sequence, shifted by
// four offsets drawn from std::mt19937_64(seed) — a Cranley–Patterson rotation): u0, u1 place the feed
// point uniformly in the inlet circle (radius √u0 · r_in, angle 2π u1); u2 gives the diameter from the
// lognormal with the material's mean and sd (inverse normal CDF); u3 the pick-up phase, the wait for the
// next of the vane_count vanes, uniform in [0, 2π/(ω n_vanes)). None of u depends on rpm, so sample k of
// two rows of one material has the same feed point and diameter: rows interpolate pairwise in rpm.
//
// Assumptions (docs/building-tables.md): the granule falls from drop_height_m (t = sqrt(2h/g)), rests at
// its feed point until a vane reaches it, then slides along the vane from r0 = max(feed radius,
// vane_start_radius_m) with ṙ(0) = 0 and leaves at vane_end_radius_m. Launch angle = feed angle +
// rotation_sense · (angle the vane turned during the transit). Radial vanes only (vane_pitch_rad = 0).
// Spin: "sliding" — the granule keeps its orientation relative to the vane, so in the inertial frame it
// turns with the disc (ω_spin = rotation_sense · ω ẑ); "rolling" — in addition it rolls on the disc
// surface without slip, ω_roll = n̂ × v_rel/(d/2) = (ṡ/(d/2)) e_θ, horizontal (on a cone, in the
// surface) and ⟂ to the motion relative to the disc.
// Output frame as tables::LaunchSample: disc centre at the origin, z up, z = d/2 (the granule centre
// above the disc surface at the rim), velocities / (ω R), spins / ω, R = disc_radius_m.
#include <cstdint>
#include <vector>

#include "libspread/core/vec3.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::launch {

struct AnalyticLaunchOptions {
  scene::SpinModel spin = scene::SpinModel::kRolling;
  double gravity_m_s2 = kStandardGravity_m_s2;
};

// Throws std::invalid_argument naming the problem (no vanes, pitched vanes, rpm too low for the feed
// radius, sample_count < 1, ...).
std::vector<tables::LaunchSample> analytic_launch_samples(const scene::Machine& machine,
                                                          const tables::Material& material, double rpm,
                                                          const scene::Inlet& inlet, int sample_count,
                                                          std::uint64_t seed,
                                                          const AnalyticLaunchOptions& options = {});

// Inverse of the standard normal CDF, |error| < 1.2e-9 (Acklam's rational approximation refined by one
// Halley step). p in (0, 1).
double inverse_normal_cdf(double p);

}  // namespace spread::launch
