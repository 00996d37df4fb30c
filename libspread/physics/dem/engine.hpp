#pragma once
// The disc DEM engine (seed 000 Sects. 2.1–3.1): spherical particles in flat arrays, walls (analytic
// and meshes, possibly spinning), particle–particle contacts through a Verlet pair list, the explicit
// integrators, and a cylindrical collector that records each launch-off state and removes the particle
// (the partitioned scheme hands launched particles to the flight module).
//
// Effects are chosen once, as the registry's DEM bits (libspread/core/effect_registry.hpp): the force pass
// is a template instantiated per (composed contact law, the effects that shape a pass) and picked from
// tables generated from the sub-model lists and the registry bits (force_variants.hpp); an effect that is
// off costs nothing: without particle_contact neither the pair list nor the pair pass runs, without
// wall_contact the wall pass does not run, and spin arrays exist only with rotation.
#include <any>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "libspread/core/effect_registry.hpp"
#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/gear_predictor_corrector.hpp"
#include "libspread/physics/dem/material.hpp"
#include "libspread/physics/dem/mesh_near_list.hpp"
#include "libspread/physics/dem/neighbor_list.hpp"
#include "libspread/physics/dem/particles.hpp"
#include "libspread/physics/dem/wall_set.hpp"

namespace spread::dem {

enum class Integrator : std::uint8_t {
  kSymplecticEuler,  // seed Eq. 41: v ← v + Δt F/m, then x ← x + Δt v
  kVelocityVerlet,   // half kick, drift, forces, half kick
  kGear4,            // Gear predictor–corrector, 4/5/6 values (seed 001; gear_predictor_corrector.hpp)
  kGear5,
  kGear6,
};

struct EngineParams {
  ContactLaw contact_law = kHertzThorntonLaw;  // sub-models (contact_law.hpp); rolling resistance is its rolling model
  LinearSprings linear;                // linear normal and tangential models only
  Integrator integrator = Integrator::kSymplecticEuler;
  // The DEM effects that run (registry bits of effect::kDemEffects; flight bits are refused). rolling
  // needs rotation (the registry's requirement) and a rolling model in contact_law, which names how it
  // is evaluated; contact_law.rolling without the rolling effect is refused too.
  effect::EffectSet effects = effect::kDefault & effect::kDemEffects;
  double dt_s = 0.0;                   // 0: Δt = t_c / contact_steps (Sect. 3.1); else refused above the stable bound (NaN, < 0: refused)
  double contact_steps = 20.0;         // N_c
  double impact_speed_m_s = 0.0;       // v in t_c; 0: fastest wall surface speed + 5 m/s
  double min_particle_radius_m = 0.0;  // smallest radius to be added (sets t_c); required
  double max_particle_radius_m = 0.0;  // largest (0: = min)
  double skin_m = 0.0;                 // pair-list skin; 0: the largest radius
  double mesh_skin_m = 0.0;            // mesh walls' near-list skin (mesh_near_list.hpp); 0: half the largest radius
  Vec3 gravity_m_s2 = Vec3(0.0, 0.0, -kStandardGravity_m_s2);
  int threads = 1;                     // OpenMP threads; results are identical for any count
  PeriodicZ periodic_z;                // periodic boundary along z (period >= 2 (2 r_max + skin)); off by default

  constexpr bool has(effect::EffectSet bit) const { return (effects & bit) != 0; }
};

// Cylinder about the vertical axis through axis_point_m: a particle whose horizontal distance from
// the axis exceeds radius_m has launched.
struct Collector {
  bool enabled = false;
  Vec3 axis_point_m = Vec3::Zero();
  double radius_m = 0.0;
  // Particles falling below this are removed and counted as lost; −∞ (the default): no loss plane.
  double lost_below_z_m = -std::numeric_limits<double>::infinity();
};

struct LaunchRecord {
  double time_s = 0.0;
  double residence_s = 0.0;        // time since release
  Vec3 position_m = Vec3::Zero();
  Vec3 velocity_m_s = Vec3::Zero();
  Vec3 spin_rad_s = Vec3::Zero();
  double diameter_m = 0.0;
  double mass_kg = 0.0;
  int material = 0;
  std::uint32_t id = 0;
};

// Pair-force sums of one particle (force N, torque N m); all zero between force passes. One 64-byte
// record per particle: adding a partner's share touches one cache line instead of six arrays.
struct alignas(64) PairSum {
  double f[3];
  double t[3];
};

class EnergyMonitor;  // energy_monitor.hpp
struct ForcePassTables;  // engine_detail.hpp: the passes' instantiation tables

struct EngineStats {
  std::uint64_t steps = 0;
  std::uint64_t particle_steps = 0;       // Σ over steps of particles on the disc
  std::uint64_t pair_list_builds = 0;
  std::uint64_t near_list_builds = 0;  // between pair-list builds (neighbor_list.hpp NearList)
  std::uint64_t wall_contacts_dropped = 0;  // beyond kWallSlots at once
  std::uint64_t lost = 0;
  double pair_search_s = 0.0;
  double forces_s = 0.0;
  double walls_s = 0.0;  // the wall pass, part of forces_s
  double integrate_s = 0.0;
  double collector_s = 0.0;
};

namespace pairs {
template <class Law>
struct PairPassArrays;  // the pair pass's context (pair_pass_context.hpp)
}  // namespace pairs

class DemEngine {
 public:
  // Throws std::invalid_argument naming the bad parameter (materials, radii, a dt above the bound, a contact
  // law whose sub-models do not fit together or that needs the rotation effect).
  DemEngine(std::vector<Material> materials, std::vector<PairOverride> overrides, WallSet walls, EngineParams params);

  // Adds a particle; returns its id. Radius must be within [min, max] particle radius.
  std::uint32_t add_particle(const Vec3& position_m, const Vec3& velocity_m_s, double radius_m, int material,
                             const Vec3& spin_rad_s = Vec3::Zero());
  // True when a sphere there would overlap an active particle.
  bool overlaps_particle(const Vec3& position_m, double radius_m) const;

  void step();
  // n steps, the state read only after the last: the same bits as n calls of step(). With velocity Verlet,
  // and nothing run between steps (no energy monitor, collector, loss plane or periodic wrap), each step's
  // opening half kick and drift go with the previous step's particle–particle pass, as each particle's
  // sums complete, instead of a pass of their own over every particle.
  void steps(std::size_t n);
  void run_until(double t_s);
  // Removes every particle still on the disc (end of a run whose launched particles fly on).
  void drop_on_disc_particles();

  void set_collector(const Collector& c) { collector_ = c; }
  // Energy/penetration diagnostics called every step (nullptr: off, the default); not owned.
  void set_energy_monitor(EnergyMonitor* monitor) { monitor_ = monitor; }

  double time_s() const { return time_s_; }
  double dt_s() const { return dt_s_; }
  double contact_time_s() const { return contact_time_s_; }   // t_c behind the automatic step
  double stable_step_bound_s() const { return stable_bound_s_; }
  const ParticleArrays& particles() const { return p_; }
  std::size_t active_count() const;
  const std::vector<LaunchRecord>& launches() const { return launches_; }
  const EngineStats& stats() const { return stats_; }
  const EngineParams& params() const { return params_; }
  const std::vector<Material>& materials() const { return materials_; }
  const WallSet& walls() const { return walls_; }
  std::size_t pair_count() const { return pairs_.size(); }
  const PairList& pair_list() const { return pairs_; }

  // The pass-shaping effects (force_variants.hpp, kPassEffects) the passes that run were instantiated with:
  // an effect outside it has no code in them.
  effect::EffectSet pass_effects() const;

  // Total kinetic energy (translation + rotation) of the active particles (J).
  double kinetic_energy_j() const;

 private:
  friend struct ForcePassTables;
  // One force evaluation (force_dispatch.cpp): the passes of force variant force_variant_.
  void compute_forces();
  // The passes are templates over one force variant V (force_variants.hpp, PassVariant: V::Law, the
  // pass-shaping effects V::kEffects).
  // Walls (wall_pass.cpp): sets each particle's force (and torque) sums to its wall contacts' share. When
  // the opening kick has left the sums at zero (sums_cleared_) and the wall list is current, only the
  // particles on the wall list are visited.
  template <class V>
  void wall_forces();
  // One particle's wall contacts (groups: the wall groups to look at; wall_coeffs: the law's coefficients
  // per material pair; wc: this thread's contact scratch): its sums, zero on entry, set to their share;
  // `dropped` counts contacts past its kWallSlots.
  template <class V>
  void wall_particle(std::size_t i, std::uint64_t groups, const typename V::Law::Coeffs* wall_coeffs, WallContact* wc,
                     std::uint64_t& dropped);
  // Without wall_contact: the sums start at zero instead (force_dispatch.cpp).
  void clear_forces();
  // Particle–particle contacts (pair_pass.cpp), added to the sums the wall pass started: the pass over the
  // CSR half list either adds each pair straight into the sums (one thread; several where the processor
  // has AVX-512) or stores the pairs' results, which are then gathered (several threads without AVX-512, an
  // energy monitor). All add in the same order, so the results are bit-identical.
  template <class V>
  void particle_forces();
  // particle_forces' stages (pair_pass.cpp): the pass's context filled by name, the batched pass's rows, the
  // next step's drift handed to the pass, and the stored form's pass and gather.
  template <class V>
  pairs::PairPassArrays<typename V::Law> pair_pass_arrays();
  template <class V>
  void pair_pass_rows(pairs::PairPassArrays<typename V::Law>& a);
  template <class Law>
  void pair_pass_drift(pairs::PairPassArrays<Law>& a, bool measure_near);
  template <class V>
  void run_stored_pair_pass(pairs::PairPassArrays<typename V::Law>& a);
  // Whether threads share the particles' pairs: more than one thread, and particles and listed pairs
  // enough to share. The pair pass then takes consecutive ranges of particles, one a thread, and the
  // opening kick and drift (kick_drift_pass) take the same particles, so that each thread finds them in
  // its own cache; the two must agree.
  bool threads_share_pairs() const;
  template <bool kRotation>
  void gather_stored_pair_forces();
  // Law::coeffs per material pair (pair_coeffs_table.cpp).
  template <class Law>
  void update_pair_coeffs();
  // Pair list and wall list rebuilt when needed (list_upkeep.cpp).
  void maintain_lists();
  // Construction's parts: every parameter and effect checked (the force variant chosen), and whether the
  // walls stay where they are (walls_fixed_in_space_).
  void check_params();
  bool walls_stay_in_place() const;
  void narrow_wall_list();
  double inner_skin_m() const;  // the near list's skin (m)
  // The integrator families (integrators.cpp).
  void step_symplectic_euler();
  void step_velocity_verlet();
  void step_gear();
  void forces_at_next_time();  // forces at the positions just predicted or drifted to t + Δt
  void kick(double dt);
  void kick_spin(double dt);  // ω += Δt T/I (rotation only); kick() and kick_drift() end with it
  // kick(dt_kick), then the drift x += dt_drift v, in one pass over the particles, which also measures the
  // largest move since the near list's last build (moved2_since_near_). clear_sums: the force and torque
  // sums, read by the kick, are left at zero for the force evaluation that follows (sums_cleared_), so
  // that the wall pass need not visit the particles away from the walls.
  void kick_drift(double dt_kick, double dt_drift, bool clear_sums);
  // Whether velocity Verlet's opening kick leaves the sums at zero (kick_drift's clear_sums): on one thread,
  // without wall contacts or with the walls on the wall list.
  bool opening_kick_clears_sums() const;
  template <bool kSpin, bool kClearSums>
  void kick_drift_pass(double dt_kick, double dt_drift);
  void wrap_periodic_z();
  // Launched and lost particles leave (launch_collector.cpp); collects(): whether any can.
  void collect();
  bool collects() const;

  std::vector<Material> materials_;
  PairTable pair_table_;
  WallSet walls_;
  EngineParams params_;
  ParticleArrays p_;
  PairList pairs_;
  NearList near_;  // the pairs the direct force pass looks at (neighbor_list.hpp)
  Collector collector_;
  EnergyMonitor* monitor_ = nullptr;
  GearPredictorCorrector gear_;  // Gear integrators only
  std::vector<LaunchRecord> launches_;
  std::vector<PairSum> pair_sum_;
  // x, y, z, r per particle from a 32-byte boundary, r NaN for an inactive particle: what the batched pass's
  // touch test reads of a body, in one load (pair_pass.cpp); vx, vy, vz, wx, wy, wz, r, I per particle from
  // a 64-byte boundary: what its law reads of a body (written before a pass, or kept by the fused drift).
  std::vector<double> touch_rows_;
  std::vector<double> law_rows_;
  // The last pass's drift brought both kinds of rows to the particles' positions and velocities
  // (drifted_in_pass_ too): nothing has moved, added or renumbered a particle since.
  bool touch_rows_kept_ = false;
  std::vector<WallContact> wall_scratch_;  // (kWallSlots + 2) per thread: no per-particle construction
  // Per particle and mesh wall, the triangles near it (mesh_near_list.hpp); off without mesh walls.
  MeshNearLists mesh_near_;
  // Wall list: per particle, bit g set when wall group g was within radius + half the near list's inner
  // skin at the last near-list build (WallSet::groups_within; 0: no wall, the wall test is skipped until the
  // next build; the others are not looked at). Used only when every wall group's surface is fixed in space
  // (walls_fixed_in_space_); empty otherwise.
  std::vector<std::uint64_t> walls_near_;
  std::vector<std::uint32_t> wall_listed_;  // the particles whose walls_near_ is not 0, ascending
  // The particles that may touch a wall before the next pair-list build (within radius + skin, or holding
  // a wall history, at the build), ascending; walls_near_ is narrowed from them at each near-list build.
  std::vector<std::uint32_t> wall_candidates_;
  bool walls_fixed_in_space_ = false;
  // Law::coeffs per material pair (a·M + b), for particle pairs (pair_coeffs_) and particle–wall contacts
  // (wall_coeffs_, R* = r, M* = m): valid (uniform) when every particle of the particle materials has the
  // same radius and mass; refreshed after particles are added (coeffs_dirty_). Each holds a
  // std::vector<Law::Coeffs> of the engine's law (the type is the law's; the passes take it out once).
  std::any pair_coeffs_, wall_coeffs_;
  std::size_t force_variant_ = 0;  // position in kForceVariants (force_variants.hpp), chosen at construction
  bool coeffs_dirty_ = true;
  // Every material's particles have one radius and mass (update_pair_coeffs): the batched pass's law runs
  // eight pairs a register, and its touch test then too (touch_rows_).
  bool one_size_per_material_ = false;
  EngineStats stats_;
  double time_s_ = 0.0;
  double dt_s_ = 0.0;
  double contact_time_s_ = 0.0;
  double stable_bound_s_ = 0.0;
  double skin_m_ = 0.0;
  std::uint32_t next_id_ = 1;
  bool lists_dirty_ = true;
  bool forces_valid_ = false;
  // Velocity Verlet's closing half kick, handed to the particle–particle pass (Δt/2, 0: none); the pass
  // says whether it applied it.
  double kick_in_pass_dt_s_ = 0.0;
  // Largest squared move since the near list's last build (m²), measured by the last drift; < 0: unknown
  // (positions changed since in another way), maintain_lists measures it itself.
  double moved2_since_near_ = -1.0;
  bool kicked_in_pass_ = false;
  // The next step's opening kick and drift handed to the same pass too (steps(): the state between the two
  // steps is not read), and whether the pass gave them; the next step then starts with the force evaluation.
  bool fuse_next_step_ = false;
  bool drifted_in_pass_ = false;
  // The force and torque sums are zero (the opening kick left them so) and nothing has been added yet.
  bool sums_cleared_ = false;
  std::size_t inactive_ = 0;
};

}  // namespace spread::dem
