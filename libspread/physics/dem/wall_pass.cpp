// Particle–wall contacts: each particle's walls within its radius, the law per contact, and the
// particle's wall-history slots (kWallSlots, particles.hpp) carried from step to step. This pass also
// starts the force and torque sums of the step (the particle–particle pass adds to them); where the opening
// kick has zeroed them already, it sets those of the particles on the wall list only.
#include <algorithm>
#include <cstdint>
#include <utility>

#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"

namespace spread::dem {

using detail::kMinParallelItems;
using detail::thread_index;

namespace {

// A particle's wall slots of the step before, copied (this step's contacts overwrite the slots in place).
struct OldWallSlots {
  std::uint32_t key[kWallSlots];
  double history[kWallSlots * kHistoryDoubles];
  double normal[kWallSlots * 3];
  bool claimed[kWallSlots] = {};

  OldWallSlots(const ParticleArrays& p, std::size_t base) {
    for (int s = 0; s < kWallSlots; ++s) {
      key[s] = p.wall_key[base + s];
      for (int k = 0; k < kHistoryDoubles; ++k) history[s * kHistoryDoubles + k] = p.wall_history[(base + s) * kHistoryDoubles + k];
      for (int k = 0; k < 3; ++k) normal[s * 3 + k] = p.wall_normal[(base + s) * 3 + k];
    }
  }
  // The slot whose history contact c carries on, claimed, or −1: the slot with c's key, else an unclaimed
  // old slot with a nearly equal normal (a particle sliding from one triangle to its coplanar neighbour
  // keeps its tangential spring).
  int claim(const WallContact& c) {
    int match = -1;
    for (int s = 0; s < kWallSlots && match < 0; ++s)
      if (!claimed[s] && key[s] == c.key) match = s;
    if (match < 0) {
      double best = 0.95;
      for (int s = 0; s < kWallSlots; ++s) {
        if (claimed[s] || key[s] == 0) continue;
        const double d = c.normal.dot(Vec3(normal[s * 3], normal[s * 3 + 1], normal[s * 3 + 2]));
        if (d > best) { best = d; match = s; }
      }
    }
    if (match >= 0) claimed[match] = true;
    return match;
  }
};

// What one particle's wall contacts read of it.
struct WallBody {
  Vec3 v, w;         // velocity (m/s), spin (rad/s)
  double r, m;       // radius (m), mass (kg)
  double inertia;    // moment of inertia (kg m²)
  int material;
};

// One wall contact: the law with the particle's lever (Eq. 10), the contact point's slip against the wall's
// surface velocity (Eq. 8), the moment (Eq. 15) and the law's rolling resistance against the wall's spin.
template <class V>
SPREAD_CONTACT_INLINE void wall_contact(const PairTable& pair_table, const typename V::Law::Coeffs* wall_coeffs, std::size_t material_count,
                  const WallSet& walls, const WallBody& b, const WallContact& c, double dt, double* history, Vec3& force,
                  Vec3& torque) {
  using Law = typename V::Law;
  const PairParams& pp = pair_table(b.material, c.material);
  ContactInput in;
  in.normal = c.normal;
  in.overlap_m = b.r - c.distance_m;
  const double lever = Law::lever(b.r, pp.share_a, in.overlap_m);
  const Vec3 arm = -lever * in.normal;  // centre → contact point
  Vec3 v_contact = b.v;
  if constexpr (V::kRotation) v_contact += b.w.cross(arm);
  in.slip_m_s = v_contact - c.wall_velocity_m_s;
  in.dt_s = dt;
  const typename Law::Coeffs& tab = wall_coeffs[static_cast<std::size_t>(b.material) * material_count + static_cast<std::size_t>(c.material)];
  const ContactForce cf = Law::eval(pp, tab.uniform ? tab : Law::coeffs(pp, b.r, b.m), in, history);
  force += cf.force_n;
  if constexpr (V::kRotation) torque += arm.cross(cf.tangential_force_n);  // Eq. 15
  if constexpr (Law::kRolling) {
    const Vec3 relative_spin = b.w - Vec3(0.0, 0.0, walls.groups[static_cast<std::size_t>(c.group)].angular_velocity_rad_s);
    const lanes::V3<double> t = Law::rolling_torque(pp, cf.normal_force_n, b.r, {relative_spin.x(), relative_spin.y(), relative_spin.z()},
                                                    b.inertia, dt);
    torque += Vec3(t.x, t.y, t.z);
  }
}

}  // namespace

template <class V>
void DemEngine::wall_particle(std::size_t i, std::uint64_t groups, const typename V::Law::Coeffs* wall_coeffs, WallContact* wc,
                              std::uint64_t& dropped) {
  const std::size_t material_count = materials_.size();
  const double r = p_.radius_m[i];
  int nc = walls_.collect(p_.position(i), r, wc, kWallSlots + 2, groups, mesh_near_.of(i, p_.id[i]));
  if (nc > kWallSlots) { dropped += static_cast<std::uint64_t>(nc - kWallSlots); nc = kWallSlots; }
  const std::size_t base = i * kWallSlots;
  // Slots are filled from the front, so an empty first slot means no wall history to carry: most
  // particles of a bed touch no wall, and they skip the slot bookkeeping below.
  if (nc == 0 && p_.wall_key[base] == 0) return;
  WallBody b{.v = p_.velocity(i), .w = Vec3::Zero(), .r = r, .m = p_.mass_kg[i], .inertia = p_.inertia_kg_m2[i],
             .material = p_.material[i]};
  if constexpr (V::kRotation) b.w = Vec3(p_.wx[i], p_.wy[i], p_.wz[i]);
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
  // The usual case, a particle resting on the same walls as a step ago: each contact finds its own key
  // in its own slot (keys are unique within a particle's slots, so that is the slot claim() would
  // give), and its history is carried on in place, without the copy of every slot below.
  bool in_place = true;
  for (int c = 0; c < nc; ++c) in_place &= p_.wall_key[base + c] == wc[c].key;
  if (in_place) {
    for (int c = 0; c < nc; ++c) {
      wall_contact<V>(pair_table_, wall_coeffs, material_count, walls_, b, wc[c], dt_s_,
                      &p_.wall_history[(base + c) * kHistoryDoubles], force, torque);
      for (int k = 0; k < 3; ++k) p_.wall_normal[(base + c) * 3 + k] = wc[c].normal[k];
    }
  } else {
    OldWallSlots old(p_, base);
    for (int c = 0; c < nc; ++c) {
      const int match = old.claim(wc[c]);
      double hist[kHistoryDoubles] = {0.0, 0.0, 0.0, 0.0};
      if (match >= 0) std::copy_n(old.history + match * kHistoryDoubles, kHistoryDoubles, hist);
      wall_contact<V>(pair_table_, wall_coeffs, material_count, walls_, b, wc[c], dt_s_, hist, force, torque);
      p_.wall_key[base + c] = wc[c].key;
      std::copy_n(hist, kHistoryDoubles, &p_.wall_history[(base + c) * kHistoryDoubles]);
      for (int k = 0; k < 3; ++k) p_.wall_normal[(base + c) * 3 + k] = wc[c].normal[k];
    }
  }
  for (int s = nc; s < kWallSlots; ++s) p_.wall_key[base + s] = 0;
  p_.fx[i] = force.x(); p_.fy[i] = force.y(); p_.fz[i] = force.z();
  if constexpr (V::kRotation) { p_.tx[i] = torque.x(); p_.ty[i] = torque.y(); p_.tz[i] = torque.z(); }
}

template <class V>
void DemEngine::wall_forces() {
  const std::size_t n = p_.size();
  const typename V::Law::Coeffs* const wall_coeffs = coeffs_table<typename V::Law>(wall_coeffs_);
  WallContact* const scratch = wall_scratch_.data();  // kWallSlots + 2 per thread
  std::uint64_t dropped = 0;
  mesh_near_.resize(n);  // particles added since the last pass: no mesh list yet
  const bool listed = walls_near_.size() == n;
  const std::uint64_t* const walls_near = listed ? walls_near_.data() : nullptr;
  if (listed && sums_cleared_) {
    // The sums are zero already: only the particles that may touch a wall before the next build.
    const std::uint32_t* const on_list = wall_listed_.data();
    const long long count = static_cast<long long>(wall_listed_.size());
#pragma omp parallel for schedule(static) num_threads(params_.threads) reduction(+ : dropped) if (params_.threads > 1 && count >= kMinParallelItems)
    for (long long q = 0; q < count; ++q) {
      const std::size_t i = on_list[q];
      if (p_.active[i])
        wall_particle<V>(i, walls_near[i], wall_coeffs, scratch + static_cast<std::size_t>(thread_index()) * (kWallSlots + 2), dropped);
    }
  } else {
    const long long nn = static_cast<long long>(n);
#pragma omp parallel for schedule(static) num_threads(params_.threads) reduction(+ : dropped) if (params_.threads > 1 && nn >= kMinParallelItems)
    for (long long ii = 0; ii < nn; ++ii) {
      const std::size_t i = static_cast<std::size_t>(ii);
      p_.fx[i] = p_.fy[i] = p_.fz[i] = 0.0;
      if constexpr (V::kRotation) p_.tx[i] = p_.ty[i] = p_.tz[i] = 0.0;
      const std::uint64_t groups = walls_near != nullptr ? walls_near[i] : ~0ull;
      if (p_.active[i] && groups != 0)
        wall_particle<V>(i, groups, wall_coeffs, scratch + static_cast<std::size_t>(thread_index()) * (kWallSlots + 2), dropped);
    }
  }
  stats_.wall_contacts_dropped += dropped;
}

const ForcePassTable kWallPasses = ForcePassTables::wall(std::make_index_sequence<kForceVariantCount>{});

}  // namespace spread::dem
