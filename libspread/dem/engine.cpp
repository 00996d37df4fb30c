#include "libspread/dem/engine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "libspread/dem/contact_laws.hpp"
#include "libspread/dem/energy_monitor.hpp"
#include "libspread/dem/time_step.hpp"
#include "libspread/flight/flight.hpp"

namespace spread::dem {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
constexpr long long kMinParallelItems = 4096;
double sphere_mass(double density, double r) { return density * 4.0 / 3.0 * kPi * r * r * r; }
int thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

using lanes::Lanes2;
using lanes::pack;
using lanes::V3;

// One touching pair's contact (T = double), or two pairs' side by side (T = Lanes2) with the same
// material pair: normal and overlap from the pair vector d (from j to i), the levers (Eq. 10), the
// contact points' relative velocity (Eq. 8), the law, and the moments on both (Eq. 15).
template <class T>
struct PairOut {
  V3<T> f, t_i, t_j;  // force on i (j gets −f); torques on i and j
  T normal_force_n;
};
template <class Law, bool kRotation, class T>
SPREAD_CONTACT_INLINE PairOut<T> pair_contact(const V3<T>& d, T dist2, T ri, T rj, const V3<T>& v_rel, const V3<T>& wi,
                                              const V3<T>& wj, const PairParams& pp, const PairCoeffs& pc, double dt,
                                              LawHistory<T>& h) {
  // 1/|d|² does not wait for the sqrt (the two overlap); the normal is d |d| / |d|².
  const T inv_dist2 = lanes::splat<T>(1.0) / dist2;
  const T dist = lanes::sqrt(dist2);
  const V3<T> n = d * (dist * inv_dist2);
  const T overlap = (ri + rj) - dist;
  const T li = Law::lever(ri, pp.share_a, overlap), lj = Law::lever(rj, pp.share_b, overlap);
  // Arms −l_i n and +l_j n both lie along n, so the relative velocity of the contact points,
  // v_i + ω_i × (−l_i n) − v_j − ω_j × (l_j n), takes one cross product, and both torques share n × F_t.
  V3<T> slip = v_rel;
  if constexpr (kRotation) slip = slip - cross(li * wi + lj * wj, n);
  const LawForce<T> law = Law::kernel(pc, pp.friction, ContactNormal<T>{n, d, inv_dist2}, overlap, slip, dt, h);
  PairOut<T> out{law.force_n, lanes::zero3<T>(), lanes::zero3<T>(), law.normal_force_n};
  if constexpr (kRotation) {
    const V3<T> n_cross_ft = cross(n, law.tangential_n);
    out.t_i = (-li) * n_cross_ft;  // (−l_i n) × F_t
    out.t_j = (-lj) * n_cross_ft;  // (l_j n) × (−F_t)
  }
  return out;
}
}  // namespace

DemEngine::DemEngine(std::vector<Material> materials, std::vector<PairOverride> overrides, WallSet walls,
                     EngineParams params)
    : materials_(std::move(materials)),
      pair_table_(materials_, overrides, params.model, params.linear),
      walls_(std::move(walls)),
      params_(params) {
  if (materials_.empty()) throw std::invalid_argument("dem: at least one material is needed");
  if (materials_.size() > 65535) throw std::invalid_argument("dem: too many materials");
  if (!(params_.min_particle_radius_m > 0.0))
    throw std::invalid_argument("dem: min_particle_radius_m must be > 0 (it sets the contact time step)");
  if (params_.max_particle_radius_m <= 0.0) params_.max_particle_radius_m = params_.min_particle_radius_m;
  if (params_.max_particle_radius_m < params_.min_particle_radius_m)
    throw std::invalid_argument("dem: max_particle_radius_m must be >= min_particle_radius_m");
  if (!(params_.contact_steps >= 1.0)) throw std::invalid_argument("dem: contact_steps (N_c) must be >= 1");
  if (params_.rolling && !params_.rotation)
    throw std::invalid_argument("dem: the rolling effect needs the rotation effect");
  if (params_.threads < 1) params_.threads = 1;
  for (const auto& g : walls_.groups)
    if (g.material < 0 || static_cast<std::size_t>(g.material) >= materials_.size())
      throw std::invalid_argument("dem: wall group '" + g.name + "' refers to an unknown material");
  p_.with_spin = params_.rotation;
  if (params_.integrator == Integrator::kGear4 || params_.integrator == Integrator::kGear5 ||
      params_.integrator == Integrator::kGear6)
    gear_ = GearPredictorCorrector(4 + static_cast<int>(params_.integrator) - static_cast<int>(Integrator::kGear4));
  skin_m_ = params_.skin_m > 0.0 ? params_.skin_m : params_.max_particle_radius_m;
  if (params_.periodic_z.enabled) {
    const PeriodicZ& pz = params_.periodic_z;
    const double cutoff = 2.0 * params_.max_particle_radius_m + skin_m_;
    if (!std::isfinite(pz.min_m) || !std::isfinite(pz.max_m) || !(pz.length_m() >= 2.0 * cutoff)) {
      std::ostringstream os;
      os << "dem: periodic_z: period max_m - min_m = " << pz.length_m() << " m must be finite and at least twice the "
         << "pair-search cut-off 2 r_max + skin = " << cutoff << " m";
      throw std::invalid_argument(os.str());
    }
  }
  wall_scratch_.resize(static_cast<std::size_t>(params_.threads) * (kWallSlots + 2));
  // A group's surface stays where it is when it does not turn, or when it turns about its own z axis and
  // consists only of surfaces of revolution about that axis and planes normal to it. Analytic pieces only:
  // mesh and bead queries are built for contact radii, not for radius + skin.
  walls_fixed_in_space_ = true;
  for (const auto& g : walls_.groups) {
    if (!g.meshes.empty() || !g.bead_walls.empty()) { walls_fixed_in_space_ = false; continue; }
    if (g.angular_velocity_rad_s == 0.0) continue;
    bool symmetric = true;
    for (const auto& piece : g.pieces)
      symmetric = symmetric && (piece.kind == PieceKind::kRevolution ||
                                (piece.kind == PieceKind::kPlane && piece.normal.x() == 0.0 && piece.normal.y() == 0.0));
    walls_fixed_in_space_ = walls_fixed_in_space_ && symmetric;
  }

  // Contact time and stability over every material pair at the smallest radius (t_c ∝ R): as particle
  // against a wall (R* = r, M* = m) and against an equal particle (R* = r/2, M* = m/2).
  const double v = params_.impact_speed_m_s > 0.0 ? params_.impact_speed_m_s
                                                  : std::max(1.0, walls_.max_surface_speed_m_s() + 5.0);
  const double r = params_.min_particle_radius_m;
  double tc = std::numeric_limits<double>::infinity();
  double bound = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < materials_.size(); ++a) {
    if (materials_[a].rigid) continue;
    const double m = sphere_mass(materials_[a].density_kg_m3, r);
    for (std::size_t b = 0; b < materials_.size(); ++b) {
      const PairParams& pp = pair_table_(static_cast<int>(a), static_cast<int>(b));
      for (int partner = 0; partner < 2; ++partner) {
        const double r_eff = partner == 0 ? r : 0.5 * r;
        const double m_eff = partner == 0 ? m : 0.5 * m;
        const double t = params_.model == ContactModel::kHertzThornton
                             ? hertz_contact_time_s(m_eff, r_eff, pp.e_star_pa, v)
                             : linear_contact_time_s(m_eff, pp.kn_linear_n_m);
        tc = std::min(tc, t);
        bound = std::min(bound, dem::stable_step_bound_s(params_.model, pp, m_eff, r_eff, v, params_.rotation));
      }
    }
  }
  contact_time_s_ = tc;
  stable_bound_s_ = bound;
  // 0 means "automatic"; a NaN (or a negative step) must not quietly become that.
  if (!(params_.dt_s >= 0.0)) {
    std::ostringstream os;
    os << "dt_s (scene: numerics.dt_contact_s) = " << params_.dt_s
       << " s: must be 0 (automatic, t_c/N_c) or a finite step > 0";
    throw std::invalid_argument(os.str());
  }
  if (params_.dt_s > 0.0) {
    if (params_.dt_s > bound) {
      std::ostringstream os;
      os << "dt_s (scene: numerics.dt_contact_s) = " << params_.dt_s << " s exceeds the stable bound " << bound
         << " s of the stiffest contact (impact speed " << v << " m/s); use at most that, or leave it 0 for t_c/N_c = "
         << tc / params_.contact_steps << " s";
      throw std::invalid_argument(os.str());
    }
    dt_s_ = params_.dt_s;
  } else {
    dt_s_ = std::min(tc / params_.contact_steps, bound);
  }
}

std::uint32_t DemEngine::add_particle(const Vec3& pos, const Vec3& vel, double radius, int material, const Vec3& spin) {
  if (material < 0 || static_cast<std::size_t>(material) >= materials_.size())
    throw std::invalid_argument("dem: add_particle with an unknown material index");
  if (!(radius >= params_.min_particle_radius_m * (1.0 - 1e-12)) || !(radius <= params_.max_particle_radius_m * (1.0 + 1e-12)))
    throw std::invalid_argument("dem: particle radius outside [min_particle_radius_m, max_particle_radius_m]");
  if (!pos.allFinite() || !vel.allFinite() || !spin.allFinite()) throw std::invalid_argument("dem: non-finite particle state");
  const double m = sphere_mass(materials_[static_cast<std::size_t>(material)].density_kg_m3, radius);
  const std::uint32_t pid = next_id_++;
  Vec3 at = pos;
  if (params_.periodic_z.enabled) at.z() = wrap_into_period(at.z(), params_.periodic_z);
  p_.push_back(at, vel, spin, radius, m, 0.4 * m * radius * radius, static_cast<std::uint16_t>(material), pid, time_s_);
  lists_dirty_ = true;
  coeffs_dirty_ = true;
  return pid;
}

bool DemEngine::overlaps_particle(const Vec3& pos, double radius) const {
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!p_.active[i]) continue;
    const double cut = radius + p_.radius_m[i];
    Vec3 d = p_.position(i) - pos;
    if (params_.periodic_z.enabled) d.z() = minimum_image_z(d.z(), params_.periodic_z.length_m());
    if (d.squaredNorm() < cut * cut) return true;
  }
  return false;
}

std::size_t DemEngine::active_count() const { return p_.size() - inactive_; }

double DemEngine::kinetic_energy_j() const {
  double e = 0.0;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!p_.active[i]) continue;
    e += 0.5 * p_.mass_kg[i] * p_.velocity(i).squaredNorm();
    if (p_.with_spin) e += 0.5 * p_.inertia_kg_m2[i] * p_.spin(i).squaredNorm();
  }
  return e;
}

void DemEngine::maintain_lists() {
  const auto t0 = Clock::now();
  if (!params_.particle_contact) {
    if (inactive_ > 0) { p_.compact(); inactive_ = 0; }
    lists_dirty_ = false;
    return;
  }
  if (!lists_dirty_) {
    const double half = 0.5 * skin_m_;
    if (max_displacement2(p_, params_.periodic_z) > half * half) lists_dirty_ = true;
  }
  if (lists_dirty_) {
    if (inactive_ > 0) {
      // Compaction renumbers the slots; the pair history follows the particle ids.
      p_.compact();
      inactive_ = 0;
    }
    build_pair_list(p_, skin_m_, pairs_, params_.periodic_z);
    ++stats_.pair_list_builds;
    if (walls_fixed_in_space_) {
      // Until the next build no particle moves more than skin/2, so one with no wall within its radius
      // plus the skin (and no wall history) cannot touch a wall before then. (A centre behind a one-sided
      // wall is not reported either; it is looked at again at the next build.)
      walls_.set_time(time_s_);
      far_from_walls_.assign(p_.size(), 0);
      WallContact* const wc = wall_scratch_.data();
      for (std::size_t i = 0; i < p_.size(); ++i)
        far_from_walls_[i] = p_.active[i] && p_.wall_key[i * kWallSlots] == 0 &&
                             walls_.collect(p_.position(i), p_.radius_m[i] + skin_m_, wc, 1) == 0;
    }
    lists_dirty_ = false;
  }
  stats_.pair_search_s += seconds_since(t0);
}

template <class Law>
void DemEngine::update_pair_coeffs() {
  const std::size_t mc = materials_.size();
  // One radius and mass per material? (Removing particles cannot break it, so only additions refresh.)
  std::vector<double> r(mc, 0.0), m(mc, 0.0);
  std::vector<std::uint8_t> seen(mc, 0), uniform(mc, 1);
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!p_.active[i]) continue;
    const std::size_t a = p_.material[i];
    if (!seen[a]) { seen[a] = 1; r[a] = p_.radius_m[i]; m[a] = p_.mass_kg[i]; }
    else if (p_.radius_m[i] != r[a] || p_.mass_kg[i] != m[a]) uniform[a] = 0;
  }
  pair_coeffs_.assign(mc * mc, PairCoeffs{});
  wall_coeffs_.assign(mc * mc, PairCoeffs{});
  for (std::size_t a = 0; a < mc; ++a) {
    if (!seen[a] || !uniform[a]) continue;
    for (std::size_t b = 0; b < mc; ++b) {
      const PairParams& pp = pair_table_(static_cast<int>(a), static_cast<int>(b));
      // The same expressions as the per-contact fallback in the pass, so the results are bit-identical.
      wall_coeffs_[a * mc + b] = Law::coeffs(pp, r[a], m[a]);
      wall_coeffs_[a * mc + b].uniform = true;
      if (!seen[b] || !uniform[b]) continue;
      pair_coeffs_[a * mc + b] = Law::coeffs(pp, r[a] * r[b] / (r[a] + r[b]), m[a] * m[b] / (m[a] + m[b]));
      pair_coeffs_[a * mc + b].uniform = true;
    }
  }
  coeffs_dirty_ = false;
}

template <class Law, bool kRotation, bool kRolling>
void DemEngine::compute_forces_impl() {
  if (coeffs_dirty_) update_pair_coeffs<Law>();
  const PairCoeffs* const wall_coeffs = wall_coeffs_.data();
  const std::size_t material_count = materials_.size();
  const std::size_t n = p_.size();
  const double dt = dt_s_;
  const long long nn = static_cast<long long>(n);
  std::uint64_t dropped = 0;
  // A parallel region per pass costs a few microseconds of fork/join; below a few thousand items (and
  // on a loaded machine) it costs more than it saves.
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
      const PairCoeffs& tab = wall_coeffs[static_cast<std::size_t>(p_.material[i]) * material_count +
                                          static_cast<std::size_t>(wc[c].material)];
      const ContactForce cf = Law::eval(pp, tab.uniform ? tab : Law::coeffs(pp, r, m), in, hist);
      force += cf.force_n;
      if constexpr (kRotation) torque += arm.cross(cf.tangential_force_n);  // Eq. 15
      if constexpr (kRolling) {
        const Vec3 wall_spin(0.0, 0.0, walls_.groups[static_cast<std::size_t>(wc[c].group)].angular_velocity_rad_s);
        torque += rolling_torque(pp.rolling_friction, cf.normal_force_n, r, w - wall_spin, p_.inertia_kg_m2[i], dt);
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

  if (!params_.particle_contact) return;
  if (pair_sum_.size() != n) pair_sum_.assign(n, PairSum{});
  // Per-pair results are stored (and gathered in a second pass) when threads share the pairs or an
  // energy monitor reads them; one thread adds them straight into the sums. Same sums, same order.
  const bool threaded = params_.threads > 1 && static_cast<long long>(pairs_.size()) >= kMinParallelItems;
  const bool periodic = params_.periodic_z.enabled;
  if (threaded || monitor_ != nullptr) {
    if (periodic) pair_forces<Law, kRotation, kRolling, true, true>();
    else pair_forces<Law, kRotation, kRolling, true, false>();
    gather_stored_pair_forces<kRotation>();
  } else {
    if (periodic) pair_forces<Law, kRotation, kRolling, false, true>();
    else pair_forces<Law, kRotation, kRolling, false, false>();
  }
}

// flatten: the whole pair kernel (geometry, law, lane operations) inlined into the loop; at -O2 GCC
// otherwise keeps the law as a call per touching pair, which costs about a third of the pass.
template <class Law, bool kRotation, bool kRolling, bool kStorePairs, bool kPeriodic>
SPREAD_CONTACT_FLATTEN void DemEngine::pair_forces() {
  // Flat arrays once, outside the loop (the vectors' bounds and sizes do not change within the pass).
  const double* const px = p_.x.data();
  const double* const py = p_.y.data();
  const double* const pz = p_.z.data();
  const double* const pvx = p_.vx.data();
  const double* const pvy = p_.vy.data();
  const double* const pvz = p_.vz.data();
  const double* const pwx = kRotation ? p_.wx.data() : nullptr;
  const double* const pwy = kRotation ? p_.wy.data() : nullptr;
  const double* const pwz = kRotation ? p_.wz.data() : nullptr;
  const double* const radius = p_.radius_m.data();
  const double* const mass = p_.mass_kg.data();
  const double* const inertia = p_.inertia_kg_m2.data();
  const std::uint16_t* const material = p_.material.data();
  const std::uint8_t* const active = p_.active.data();
  const std::uint32_t* const pair_start = pairs_.first_start.data();
  const std::uint32_t* const partner = pairs_.second.data();
  double* const history = pairs_.history.data();
  std::uint8_t* const held = pairs_.held.data();
  double* const out_force = pairs_.force.data();
  double* const out_torque_i = pairs_.torque_first.data();
  double* const out_torque_j = pairs_.torque_second.data();
  PairSum* const sums = pair_sum_.data();
  const PairParams* const params_row0 = &pair_table_(0, 0);
  const std::size_t material_count = pair_table_.material_count();
  const PairCoeffs* const coeffs_row0 = pair_coeffs_.data();
  const double period = params_.periodic_z.length_m();
  const double dt = dt_s_;
  const long long nn = static_cast<long long>(p_.size());
  const bool parallel = kStorePairs && params_.threads > 1 && nn >= kMinParallelItems;

  // firstprivate: each thread (also the only one) gets the pointers as locals. Shared, they are read
  // through the outlined region's argument block, and since a byte store (held) may alias anything,
  // GCC reloaded every array's pointer for every listed pair.
#pragma omp parallel for schedule(static) num_threads(params_.threads) if (parallel)                                  \
    firstprivate(px, py, pz, pvx, pvy, pvz, pwx, pwy, pwz, radius, mass, inertia, material, active, pair_start, partner, \
                     history, held, out_force, out_torque_i, out_torque_j, sums, params_row0, material_count,         \
                     coeffs_row0, period, dt)
  for (long long ii = 0; ii < nn; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    const std::uint32_t k_begin = pair_start[i], k_end = pair_start[i + 1];
    const bool i_active = active[i] != 0;
    const double xi = px[i], yi = py[i], zi = pz[i];
    const V3<double> vi{pvx[i], pvy[i], pvz[i]};
    V3<double> wi{0.0, 0.0, 0.0};
    if constexpr (kRotation) wi = V3<double>{pwx[i], pwy[i], pwz[i]};
    const double ri = radius[i], mi = mass[i];
    const PairParams* const params_row = params_row0 + static_cast<std::size_t>(material[i]) * material_count;
    const PairCoeffs* const coeffs_row = coeffs_row0 + static_cast<std::size_t>(material[i]) * material_count;
    // This particle's share of its own pairs (it is `first` in all of them), summed from zero in pair order.
    double sum_f[3] = {0.0, 0.0, 0.0}, sum_t[3] = {0.0, 0.0, 0.0};
    // Pair vector from j to i (minimum image along a periodic axis).
    auto separation = [&](std::size_t j) {
      double dz = zi - pz[j];
      if constexpr (kPeriodic) dz = minimum_image_z(dz, period);
      return V3<double>{xi - px[j], yi - py[j], dz};
    };
    // A finished pair: i's share into the running sums, j's share (Newton's third law, Eq. 1) into j's
    // sums — finished when the loop reaches j > i — or, when stored, into the pair's output slots.
    auto add = [&](std::uint32_t k, std::size_t j, const V3<double>& f, const V3<double>& t_i, const V3<double>& t_j) {
      held[k] = 1;
      sum_f[0] += f.x; sum_f[1] += f.y; sum_f[2] += f.z;
      if constexpr (kRotation) { sum_t[0] += t_i.x; sum_t[1] += t_i.y; sum_t[2] += t_i.z; }
      if constexpr (kStorePairs) {
        out_force[k * 3] = f.x; out_force[k * 3 + 1] = f.y; out_force[k * 3 + 2] = f.z;
        if constexpr (kRotation) {
          out_torque_i[k * 3] = t_i.x; out_torque_i[k * 3 + 1] = t_i.y; out_torque_i[k * 3 + 2] = t_i.z;
          out_torque_j[k * 3] = t_j.x; out_torque_j[k * 3 + 1] = t_j.y; out_torque_j[k * 3 + 2] = t_j.z;
        }
      } else {
        PairSum& sj = sums[j];
        sj.f[0] -= f.x; sj.f[1] -= f.y; sj.f[2] -= f.z;
        if constexpr (kRotation) { sj.t[0] += t_j.x; sj.t[1] += t_j.y; sj.t[2] += t_j.z; }
      }
    };
    // One touching pair alone (T = double): any materials and sizes, rolling resistance.
    auto one_pair = [&](std::uint32_t k, double dist2) {
      const std::size_t j = partner[k];
      double* const hist = history + static_cast<std::size_t>(k) * kHistoryDoubles;
      const PairParams& pp = params_row[material[j]];
      // R* = r_i r_j / (r_i + r_j), M* = m_i m_j / (m_i + m_j) and what the law derives from them: from the
      // material-pair table when both materials have one size, else per contact.
      const PairCoeffs& tab = coeffs_row[material[j]];
      const double rj = radius[j];
      const PairCoeffs pc = tab.uniform ? tab : Law::coeffs(pp, ri * rj / (ri + rj), mi * mass[j] / (mi + mass[j]));
      V3<double> wj{0.0, 0.0, 0.0};
      if constexpr (kRotation) wj = V3<double>{pwx[j], pwy[j], pwz[j]};
      LawHistory<double> h{{hist[0], hist[1], hist[2]}, hist[3]};
      PairOut<double> r = pair_contact<Law, kRotation>(separation(j), dist2, ri, rj, vi - V3<double>{pvx[j], pvy[j], pvz[j]},
                                                         wi, wj, pp, pc, dt, h);
      hist[0] = h.elastic.x; hist[1] = h.elastic.y; hist[2] = h.elastic.z; hist[3] = h.overlap_m;
      if constexpr (kRolling) {
        const double ii_ = inertia[i], ij_ = inertia[j];
        const Vec3 tr = rolling_torque(pp.rolling_friction, r.normal_force_n, pc.r_eff_m, Vec3(wi.x - wj.x, wi.y - wj.y, wi.z - wj.z),
                                       ii_ * ij_ / (ii_ + ij_), dt);
        r.t_i = r.t_i + V3<double>{tr.x(), tr.y(), tr.z()};
        r.t_j = r.t_j - V3<double>{tr.x(), tr.y(), tr.z()};
      }
      add(k, j, r.f, r.t_i, r.t_j);
    };
    // Two stages per chunk of i's pairs. (1) Without a branch on "touching" — about a third of the listed
    // pairs touch, scattered, so that branch was mispredicted often — the touching pairs' indices are
    // appended to a small buffer and a pair that has just come apart releases its tangential spring.
    // (2) The contact law over the buffer only, in pair order (so the sums are those of one loop), two
    // pairs at a time in lanes (lanes.hpp) when they share their materials' table entry.
    constexpr std::uint32_t kChunk = 64;
    for (std::uint32_t chunk = k_begin; chunk < k_end; chunk += kChunk) {
      const std::uint32_t chunk_end = std::min(k_end, chunk + kChunk);
      std::uint32_t touching_pairs[kChunk];
      double touching_dist2[kChunk];
      std::uint32_t touching = 0;
      for (std::uint32_t k = chunk; k < chunk_end; ++k) {
        const std::size_t j = partner[k];
        const V3<double> d = separation(j);
        const double dist2 = squared_norm(d);
        const double cut = ri + radius[j];
        const bool touches = (dist2 < cut * cut) & i_active & (active[j] != 0) & (dist2 != 0.0);
        touching_pairs[touching] = k;
        touching_dist2[touching] = dist2;
        touching += touches ? 1u : 0u;
        // Contact lost: the tangential spring is released. The history is touched only if it holds
        // anything (held byte): the apart pairs cost a byte read, not 32 bytes. Rarely true, so predictable.
        if (held[k] & static_cast<std::uint8_t>(!touches)) {
          double* const hist = history + static_cast<std::size_t>(k) * kHistoryDoubles;
          hist[0] = hist[1] = hist[2] = hist[3] = 0.0;
          held[k] = 0;
        }
        if constexpr (kStorePairs) {
          for (int c = 0; c < 3; ++c) out_force[k * 3 + c] = 0.0;
          if constexpr (kRotation)
            for (int c = 0; c < 3; ++c) out_torque_i[k * 3 + c] = out_torque_j[k * 3 + c] = 0.0;
        }
      }
      std::uint32_t q = 0;
      if constexpr (!kRolling) {
        for (; q + 2 <= touching; q += 2) {
          const std::uint32_t k0 = touching_pairs[q], k1 = touching_pairs[q + 1];
          const std::size_t j0 = partner[k0], j1 = partner[k1];
          const PairCoeffs& tab = coeffs_row[material[j0]];
          if (material[j1] != material[j0] || !tab.uniform) {
            one_pair(k0, touching_dist2[q]);
            one_pair(k1, touching_dist2[q + 1]);
            continue;
          }
          const V3<double> d0 = separation(j0), d1 = separation(j1);
          V3<Lanes2> wj2 = lanes::zero3<Lanes2>();
          if constexpr (kRotation) wj2 = V3<Lanes2>{pack(pwx[j0], pwx[j1]), pack(pwy[j0], pwy[j1]), pack(pwz[j0], pwz[j1])};
          double* const h0 = history + static_cast<std::size_t>(k0) * kHistoryDoubles;
          double* const h1 = history + static_cast<std::size_t>(k1) * kHistoryDoubles;
          LawHistory<Lanes2> h{{pack(h0[0], h1[0]), pack(h0[1], h1[1]), pack(h0[2], h1[2])}, pack(h0[3], h1[3])};
          const PairOut<Lanes2> r = pair_contact<Law, kRotation>(
              V3<Lanes2>{pack(d0.x, d1.x), pack(d0.y, d1.y), pack(d0.z, d1.z)}, pack(touching_dist2[q], touching_dist2[q + 1]),
              lanes::splat<Lanes2>(ri), pack(radius[j0], radius[j1]),
              V3<Lanes2>{lanes::splat<Lanes2>(vi.x) - pack(pvx[j0], pvx[j1]), lanes::splat<Lanes2>(vi.y) - pack(pvy[j0], pvy[j1]),
                         lanes::splat<Lanes2>(vi.z) - pack(pvz[j0], pvz[j1])},
              V3<Lanes2>{lanes::splat<Lanes2>(wi.x), lanes::splat<Lanes2>(wi.y), lanes::splat<Lanes2>(wi.z)}, wj2,
              params_row[material[j0]], tab, dt, h);
          for (int l = 0; l < 2; ++l) {
            double* const hl = l == 0 ? h0 : h1;
            hl[0] = h.elastic.x[l]; hl[1] = h.elastic.y[l]; hl[2] = h.elastic.z[l]; hl[3] = h.overlap_m[l];
            add(l == 0 ? k0 : k1, l == 0 ? j0 : j1, lanes::lane3(r.f, l), lanes::lane3(r.t_i, l), lanes::lane3(r.t_j, l));
          }
        }
      }
      for (; q < touching; ++q) one_pair(touching_pairs[q], touching_dist2[q]);
    }
    if constexpr (kStorePairs) {
      // Kept for the gather, which adds the partners' share in the same order as the direct pass.
      PairSum& si = sums[i];
      for (int c = 0; c < 3; ++c) { si.f[c] = sum_f[c]; if constexpr (kRotation) si.t[c] = sum_t[c]; }
    } else {
      // All pairs with i as `second` came earlier (their `first` is smaller): sums[i] is complete.
      PairSum& si = sums[i];
      p_.fx[i] += si.f[0] + sum_f[0];
      p_.fy[i] += si.f[1] + sum_f[1];
      p_.fz[i] += si.f[2] + sum_f[2];
      if constexpr (kRotation) {
        p_.tx[i] += si.t[0] + sum_t[0];
        p_.ty[i] += si.t[1] + sum_t[1];
        p_.tz[i] += si.t[2] + sum_t[2];
      }
      si = PairSum{};
    }
  }
}

template <bool kRotation>
void DemEngine::gather_stored_pair_forces() {
  const long long nn = static_cast<long long>(p_.size());
  const bool parallel = params_.threads > 1 && nn >= kMinParallelItems;
#pragma omp parallel for schedule(static) num_threads(params_.threads) if (parallel)
  for (long long ii = 0; ii < nn; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    // The partners' share, from zero in pair order — the order in which the direct pass adds it.
    double f[3] = {0.0, 0.0, 0.0}, t[3] = {0.0, 0.0, 0.0};
    for (std::uint32_t q = pairs_.second_start[i]; q < pairs_.second_start[i + 1]; ++q) {
      const std::uint32_t k = pairs_.second_pairs[q];
      for (int c = 0; c < 3; ++c) {
        f[c] -= pairs_.force[k * 3 + c];
        if constexpr (kRotation) t[c] += pairs_.torque_second[k * 3 + c];
      }
    }
    PairSum& si = pair_sum_[i];
    p_.fx[i] += f[0] + si.f[0];
    p_.fy[i] += f[1] + si.f[1];
    p_.fz[i] += f[2] + si.f[2];
    if constexpr (kRotation) {
      p_.tx[i] += t[0] + si.t[0];
      p_.ty[i] += t[1] + si.t[1];
      p_.tz[i] += t[2] + si.t[2];
    }
    si = PairSum{};
  }
}

void DemEngine::wrap_periodic_z() {
  const PeriodicZ& pz = params_.periodic_z;
  const double period = pz.length_m();
  double* const z = p_.z.data();
  const std::size_t n = p_.size();
  // One period at most per step (a step moves far less than the period).
  for (std::size_t i = 0; i < n; ++i) {
    if (z[i] >= pz.max_m) z[i] -= period;
    else if (z[i] < pz.min_m) z[i] += period;
  }
}
void DemEngine::compute_forces() {
  const auto t0 = Clock::now();
  walls_.set_time(time_s_);
  using Fn = void (DemEngine::*)();
  // Dispatch table over the effect combination (law × rotation × rolling).
  static constexpr Fn table[2][2][2] = {
      {{&DemEngine::compute_forces_impl<HertzThornton, false, false>, &DemEngine::compute_forces_impl<HertzThornton, false, true>},
       {&DemEngine::compute_forces_impl<HertzThornton, true, false>, &DemEngine::compute_forces_impl<HertzThornton, true, true>}},
      {{&DemEngine::compute_forces_impl<LinearSpringDashpot, false, false>, &DemEngine::compute_forces_impl<LinearSpringDashpot, false, true>},
       {&DemEngine::compute_forces_impl<LinearSpringDashpot, true, false>, &DemEngine::compute_forces_impl<LinearSpringDashpot, true, true>}}};
  const int law = params_.model == ContactModel::kHertzThornton ? 0 : 1;
  (this->*table[law][params_.rotation ? 1 : 0][params_.rolling ? 1 : 0])();
  stats_.forces_s += seconds_since(t0);
}

void DemEngine::kick(double dt) {
  // v += Δt (F/m + g), ω += Δt T/I with the stored 1/m, 1/I (no division per particle per step).
  const std::size_t n = p_.size();
  const Vec3 g = params_.gravity_m_s2;
  for (std::size_t i = 0; i < n; ++i) {
    if (!p_.active[i]) continue;
    const double inv_m = p_.inv_mass_kg[i];
    p_.vx[i] += dt * (p_.fx[i] * inv_m + g.x());
    p_.vy[i] += dt * (p_.fy[i] * inv_m + g.y());
    p_.vz[i] += dt * (p_.fz[i] * inv_m + g.z());
  }
  kick_spin(dt);
}

void DemEngine::kick_spin(double dt) {
  if (!p_.with_spin) return;
  const std::size_t n = p_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!p_.active[i]) continue;
    const double inv_i = p_.inv_inertia_kg_m2[i];
    p_.wx[i] += dt * p_.tx[i] * inv_i;
    p_.wy[i] += dt * p_.ty[i] * inv_i;
    p_.wz[i] += dt * p_.tz[i] * inv_i;
  }
}

void DemEngine::kick_drift(double dt_kick, double dt_drift) {
  // kick(dt_kick), then x += dt_drift v for every particle: one pass over the arrays.
  const std::size_t n = p_.size();
  const Vec3 g = params_.gravity_m_s2;
  double* const x = p_.x.data(); double* const y = p_.y.data(); double* const z = p_.z.data();
  double* const vx = p_.vx.data(); double* const vy = p_.vy.data(); double* const vz = p_.vz.data();
  const double* const fx = p_.fx.data(); const double* const fy = p_.fy.data(); const double* const fz = p_.fz.data();
  const double* const inv_mass = p_.inv_mass_kg.data();
  const std::uint8_t* const active = p_.active.data();
  for (std::size_t i = 0; i < n; ++i) {
    if (active[i]) {
      const double inv_m = inv_mass[i];
      vx[i] += dt_kick * (fx[i] * inv_m + g.x());
      vy[i] += dt_kick * (fy[i] * inv_m + g.y());
      vz[i] += dt_kick * (fz[i] * inv_m + g.z());
    }
    x[i] += dt_drift * vx[i];
    y[i] += dt_drift * vy[i];
    z[i] += dt_drift * vz[i];
  }
  kick_spin(dt_kick);
}

void DemEngine::collect() {
  const auto t0 = Clock::now();
  const std::size_t n = p_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!p_.active[i]) continue;
    bool remove = false;
    if (collector_.enabled) {
      const double dx = p_.x[i] - collector_.axis_point_m.x(), dy = p_.y[i] - collector_.axis_point_m.y();
      if (dx * dx + dy * dy > collector_.radius_m * collector_.radius_m) {
        LaunchRecord rec;
        rec.time_s = time_s_;
        rec.residence_s = time_s_ - p_.birth_time_s[i];
        rec.position_m = p_.position(i);
        rec.velocity_m_s = p_.velocity(i);
        rec.spin_rad_s = p_.spin(i);
        rec.diameter_m = 2.0 * p_.radius_m[i];
        rec.mass_kg = p_.mass_kg[i];
        rec.material = p_.material[i];
        rec.id = p_.id[i];
        launches_.push_back(rec);
        if (monolithic_.enabled) {
          fl_x_.push_back(p_.x[i]); fl_y_.push_back(p_.y[i]); fl_z_.push_back(p_.z[i]);
          fl_vx_.push_back(p_.vx[i]); fl_vy_.push_back(p_.vy[i]); fl_vz_.push_back(p_.vz[i]);
          fl_d_.push_back(2.0 * p_.radius_m[i]); fl_m_.push_back(p_.mass_kg[i]);
        }
        remove = true;
      }
    }
    if (!remove && p_.z[i] < collector_.lost_below_z_m) {
      ++stats_.lost;
      remove = true;
    }
    if (remove) {
      p_.active[i] = 0;
      ++inactive_;
    }
  }
  stats_.collector_s += seconds_since(t0);
}

void DemEngine::fly_monolithic() {
  if (fl_x_.empty()) return;
  const auto t0 = Clock::now();
  const double dt = dt_s_;
  const Vec3 g = params_.gravity_m_s2;
  std::size_t k = 0;
  while (k < fl_x_.size()) {
    // Drag, Eq. 27 with C_D of Eq. 32, in still air; symplectic Euler at Δt_c as the DEM itself.
    const double speed = std::sqrt(fl_vx_[k] * fl_vx_[k] + fl_vy_[k] * fl_vy_[k] + fl_vz_[k] * fl_vz_[k]);
    double ax = g.x(), ay = g.y(), az = g.z();
    if (speed > 0.0) {
      const double re = monolithic_.air_density_kg_m3 * fl_d_[k] * speed / monolithic_.air_viscosity_pa_s;
      const double cd = flight::drag_coefficient(re);
      const double c = 0.5 * monolithic_.air_density_kg_m3 * cd * 0.25 * kPi * fl_d_[k] * fl_d_[k] * speed / fl_m_[k];
      ax -= c * fl_vx_[k]; ay -= c * fl_vy_[k]; az -= c * fl_vz_[k];
    }
    fl_vx_[k] += dt * ax; fl_vy_[k] += dt * ay; fl_vz_[k] += dt * az;
    fl_x_[k] += dt * fl_vx_[k]; fl_y_[k] += dt * fl_vy_[k]; fl_z_[k] += dt * fl_vz_[k];
    ++stats_.flight_particle_steps;
    if (fl_z_[k] <= monolithic_.ground_z_m) {
      landings_.emplace_back(fl_x_[k], fl_y_[k], fl_z_[k]);
      ++stats_.landed_monolithic;
      for (auto* v : {&fl_x_, &fl_y_, &fl_z_, &fl_vx_, &fl_vy_, &fl_vz_, &fl_d_, &fl_m_}) {
        (*v)[k] = v->back();
        v->pop_back();
      }
      continue;
    }
    ++k;
  }
  stats_.monolithic_flight_s += seconds_since(t0);
}

void DemEngine::step() {
  if (monitor_ != nullptr) monitor_->begin_step(*this);
  if (params_.integrator == Integrator::kSymplecticEuler) {
    maintain_lists();
    compute_forces();
    const auto t0 = Clock::now();
    kick_drift(dt_s_, dt_s_);  // Eq. 41: v from the forces at t, then x with the new v
    stats_.integrate_s += seconds_since(t0);
  } else if (params_.integrator != Integrator::kVelocityVerlet) {
    // Gear: predict to t + Δt, one force evaluation there, correct (gear_predictor_corrector.hpp).
    if (gear_.needs_start(p_)) {  // particles were added: start values from the forces now
      maintain_lists();
      compute_forces();
      gear_.start(p_, params_.gravity_m_s2, dt_s_);
    }
    auto t0 = Clock::now();
    gear_.predict(p_, dt_s_);
    stats_.integrate_s += seconds_since(t0);
    time_s_ += dt_s_;
    maintain_lists();
    compute_forces();
    time_s_ -= dt_s_;
    t0 = Clock::now();
    gear_.correct(p_, params_.gravity_m_s2, dt_s_);
    stats_.integrate_s += seconds_since(t0);
  } else {
    if (!forces_valid_) {
      maintain_lists();
      compute_forces();
    }
    auto t0 = Clock::now();
    kick_drift(0.5 * dt_s_, dt_s_);
    stats_.integrate_s += seconds_since(t0);
    time_s_ += dt_s_;
    maintain_lists();
    compute_forces();
    time_s_ -= dt_s_;
    t0 = Clock::now();
    kick(0.5 * dt_s_);
    stats_.integrate_s += seconds_since(t0);
    forces_valid_ = true;
  }
  if (params_.periodic_z.enabled) wrap_periodic_z();
  stats_.particle_steps += active_count();
  ++stats_.steps;
  time_s_ += dt_s_;
  if (monitor_ != nullptr) monitor_->end_step(*this);  // before the collector removes launched particles
  collect();
  if (monolithic_.enabled) fly_monolithic();
}

void DemEngine::drop_on_disc_particles() {
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (p_.active[i]) {
      p_.active[i] = 0;
      ++inactive_;
    }
  lists_dirty_ = true;
}

void DemEngine::run_until(double t_s) {
  while (time_s_ + 0.5 * dt_s_ < t_s) step();
}

}  // namespace spread::dem
