// Particle–wall contacts: each particle's walls within its radius, the law per contact, and the
// particle's wall-history slots (kWallSlots, particles.hpp) carried from step to step. This pass also
// starts the force and torque sums of the step (the particle–particle pass adds to them).
#include <cstdint>
#include <utility>

#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"

namespace spread::dem {

using detail::kMinParallelItems;
using detail::thread_index;

template <class Law, bool kRotation>
void DemEngine::wall_forces() {
  const typename Law::Coeffs* const wall_coeffs = coeffs_table<Law>(wall_coeffs_);
  const std::size_t material_count = materials_.size();
  const std::size_t n = p_.size();
  const double dt = dt_s_;
  const long long nn = static_cast<long long>(n);
  std::uint64_t dropped = 0;
  const bool parallel_particles = params_.threads > 1 && nn >= kMinParallelItems;
  WallContact* const scratch = wall_scratch_.data();
  const std::uint8_t* const far_from_walls = far_from_walls_.size() == n ? far_from_walls_.data() : nullptr;
  // Walls, per particle (each particle owns its wall-history slots: no races).
#pragma omp parallel for schedule(static) num_threads(params_.threads) reduction(+ : dropped) if (parallel_particles)
  for (long long ii = 0; ii < nn; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    p_.fx[i] = p_.fy[i] = p_.fz[i] = 0.0;
    if constexpr (kRotation) p_.tx[i] = p_.ty[i] = p_.tz[i] = 0.0;
    if (!p_.active[i] || (far_from_walls != nullptr && far_from_walls[i])) continue;
    const Vec3 x = p_.position(i);
    const double r = p_.radius_m[i];
    WallContact* const wc = scratch + static_cast<std::size_t>(thread_index()) * (kWallSlots + 2);
    int nc = walls_.collect(x, r, wc, kWallSlots + 2);
    if (nc > kWallSlots) { dropped += static_cast<std::uint64_t>(nc - kWallSlots); nc = kWallSlots; }
    const std::size_t base = i * kWallSlots;
    // Slots are filled from the front, so an empty first slot means no wall history to carry: most
    // particles of a bed touch no wall, and they skip the slot bookkeeping below.
    if (nc == 0 && p_.wall_key[base] == 0) continue;
    // Old slots (copy), then matched by key; an unmatched contact inherits the history of an unclaimed
    // old slot with a nearly equal normal (a particle sliding from one triangle to its coplanar
    // neighbour keeps its tangential spring).
    std::uint32_t okey[kWallSlots];
    double ohist[kWallSlots * kHistoryDoubles];
    double onorm[kWallSlots * 3];
    bool claimed[kWallSlots] = {};
    for (int s = 0; s < kWallSlots; ++s) {
      okey[s] = p_.wall_key[base + s];
      for (int k = 0; k < kHistoryDoubles; ++k) ohist[s * kHistoryDoubles + k] = p_.wall_history[(base + s) * kHistoryDoubles + k];
      for (int k = 0; k < 3; ++k) onorm[s * 3 + k] = p_.wall_normal[(base + s) * 3 + k];
    }
    Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
    const Vec3 v = p_.velocity(i);
    Vec3 w = Vec3::Zero();
    if constexpr (kRotation) w = Vec3(p_.wx[i], p_.wy[i], p_.wz[i]);
    const double m = p_.mass_kg[i];
    for (int c = 0; c < nc; ++c) {
      int match = -1;
      for (int s = 0; s < kWallSlots && match < 0; ++s)
        if (!claimed[s] && okey[s] == wc[c].key) match = s;
      if (match < 0) {
        double best = 0.95;
        for (int s = 0; s < kWallSlots; ++s) {
          if (claimed[s] || okey[s] == 0) continue;
          const double d = wc[c].normal.dot(Vec3(onorm[s * 3], onorm[s * 3 + 1], onorm[s * 3 + 2]));
          if (d > best) { best = d; match = s; }
        }
      }
      double hist[kHistoryDoubles] = {0.0, 0.0, 0.0, 0.0};
      if (match >= 0) {
        claimed[match] = true;
        for (int k = 0; k < kHistoryDoubles; ++k) hist[k] = ohist[match * kHistoryDoubles + k];
      }
      const PairParams& pp = pair_table_(p_.material[i], wc[c].material);
      ContactInput in;
      in.normal = wc[c].normal;
      in.overlap_m = r - wc[c].distance_m;
      const double lever = Law::lever(r, pp.share_a, in.overlap_m);
      const Vec3 arm = -lever * in.normal;  // centre → contact point
      Vec3 v_contact = v;
      if constexpr (kRotation) v_contact += w.cross(arm);
      in.slip_m_s = v_contact - wc[c].wall_velocity_m_s;
      in.dt_s = dt;
      const typename Law::Coeffs& tab = wall_coeffs[static_cast<std::size_t>(p_.material[i]) * material_count +
                                          static_cast<std::size_t>(wc[c].material)];
      const ContactForce cf = Law::eval(pp, tab.uniform ? tab : Law::coeffs(pp, r, m), in, hist);
      force += cf.force_n;
      if constexpr (kRotation) torque += arm.cross(cf.tangential_force_n);  // Eq. 15
      if constexpr (Law::kRolling) {
        const Vec3 wall_spin(0.0, 0.0, walls_.groups[static_cast<std::size_t>(wc[c].group)].angular_velocity_rad_s);
        torque += Law::RollingModel::torque(pp.rolling_friction, cf.normal_force_n, r, w - wall_spin, p_.inertia_kg_m2[i], dt);
      }
      p_.wall_key[base + c] = wc[c].key;
      for (int k = 0; k < kHistoryDoubles; ++k) p_.wall_history[(base + c) * kHistoryDoubles + k] = hist[k];
      for (int k = 0; k < 3; ++k) p_.wall_normal[(base + c) * 3 + k] = wc[c].normal[k];
    }
    for (int s = nc; s < kWallSlots; ++s) p_.wall_key[base + s] = 0;
    p_.fx[i] = force.x(); p_.fy[i] = force.y(); p_.fz[i] = force.z();
    if constexpr (kRotation) { p_.tx[i] = torque.x(); p_.ty[i] = torque.y(); p_.tz[i] = torque.z(); }
  }
  stats_.wall_contacts_dropped += dropped;
}

const ForcePassTable kWallPasses = ForcePassTables::wall(std::make_index_sequence<kForceVariantCount>{});

}  // namespace spread::dem
