// The engine's state and its particles: construction (parameter checks, the step), adding particles,
// and the queries. The passes of a step live in files of their own (docs/dem.md, "Code map").
#include "libspread/physics/dem/engine.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "libspread/physics/dem/engine_detail.hpp"
#include "libspread/physics/dem/force_variants.hpp"
#include "libspread/physics/dem/time_step.hpp"

namespace spread::dem {

DemEngine::DemEngine(std::vector<Material> materials, std::vector<PairOverride> overrides, WallSet walls,
                     EngineParams params)
    : materials_(std::move(materials)),
      pair_table_(materials_, overrides, params.contact_law, params.linear),
      walls_(std::move(walls)),
      params_(params) {
  check_params();
  if (params_.threads < 1) params_.threads = 1;
  for (const auto& g : walls_.groups)
    if (g.material < 0 || static_cast<std::size_t>(g.material) >= materials_.size())
      throw std::invalid_argument("dem: wall group '" + g.name + "' refers to an unknown material");
  p_.with_spin = params_.has(effect::kRotation);
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
  if (!(params_.mesh_skin_m >= 0.0) || !std::isfinite(params_.mesh_skin_m))
    throw std::invalid_argument("dem: mesh_skin_m must be >= 0 (0: half the largest particle radius)");
  // Half the largest radius: measured on bench_dem's Case-1 mesh disc (docs/dem.md "Mesh walls"), between
  // lists rebuilt too often (a smaller skin) and too many triangles tested each step (a larger one).
  if (params_.has(effect::kWallContact))
    mesh_near_.configure(walls_.mesh_count(), params_.mesh_skin_m > 0.0 ? params_.mesh_skin_m : 0.5 * params_.max_particle_radius_m);
  // Without wall_contact no wall is ever looked at, so there is no wall list to keep.
  walls_fixed_in_space_ = params_.has(effect::kWallContact) && walls_stay_in_place();
  const StepChoice step = choose_time_step(materials_, pair_table_, params_, walls_.max_surface_speed_m_s());
  contact_time_s_ = step.contact_time_s;
  stable_bound_s_ = step.stable_bound_s;
  dt_s_ = step.dt_s;
}

void DemEngine::check_params() {
  if (materials_.empty()) throw std::invalid_argument("dem: at least one material is needed");
  if (materials_.size() > 65535) throw std::invalid_argument("dem: too many materials");
  if (!(params_.min_particle_radius_m > 0.0))
    throw std::invalid_argument("dem: min_particle_radius_m must be > 0 (it sets the contact time step)");
  if (params_.max_particle_radius_m <= 0.0) params_.max_particle_radius_m = params_.min_particle_radius_m;
  if (params_.max_particle_radius_m < params_.min_particle_radius_m)
    throw std::invalid_argument("dem: max_particle_radius_m must be >= min_particle_radius_m");
  if (!(params_.contact_steps >= 1.0)) throw std::invalid_argument("dem: contact_steps (N_c) must be >= 1");
  // The effects: DEM bits only, the rolling effect exactly when the law has a rolling model (the effect
  // says whether, the law says how), and each effect with what the registry says it requires.
  if ((params_.effects & ~effect::kDemEffects) != 0)
    throw std::invalid_argument("dem: effects: '" + effect::to_string(params_.effects & ~effect::kDemEffects) +
                                "' not a DEM effect (DEM effects: " + effect::names_of(effect::kDemEffects) + ")");
  if (params_.has(effect::kRolling) != (params_.contact_law.rolling != RollingModel::kNone))
    throw std::invalid_argument(params_.has(effect::kRolling)
                                    ? "dem: the 'rolling' effect is on but contact_law.rolling is 'none': name the rolling model"
                                    : "dem: contact_law has a rolling model but the 'rolling' effect is off (EngineParams::effects)");
  // The sub-models must fit together and be compiled in.
  try {
    force_variant_ = find_force_variant(params_.contact_law, params_.effects);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("dem: ") + e.what());
  }
  // What the law does not already say (a future effect's requirement): the registry's rows.
  for (const effect::Effect& e : effect::kRegistry) {
    const effect::EffectSet missing = params_.has(e.bit) ? e.requires_effects & ~params_.effects : 0;
    if (missing != 0)
      throw std::invalid_argument("dem: effect '" + std::string(e.name) + "' needs the '" + effect::to_string(missing) +
                                  "' effect");
  }
}

bool DemEngine::walls_stay_in_place() const {
  // A group's surface stays where it is when it does not turn, or when it turns about its own z axis and
  // consists only of surfaces of revolution about that axis and planes normal to it. Analytic pieces only:
  // mesh and bead queries are built for contact radii, not for radius + skin.
  bool fixed = true;
  for (const auto& g : walls_.groups) {
    if (!g.meshes.empty() || !g.bead_walls.empty()) { fixed = false; continue; }
    if (g.angular_velocity_rad_s == 0.0) continue;
    bool symmetric = true;
    for (const auto& piece : g.pieces)
      symmetric = symmetric && (piece.kind == PieceKind::kRevolution ||
                                (piece.kind == PieceKind::kPlane && piece.normal.x() == 0.0 && piece.normal.y() == 0.0));
    fixed = fixed && symmetric;
  }
  return fixed;
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
  touch_rows_kept_ = false;
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

bool DemEngine::threads_share_pairs() const {
  return params_.threads > 1 && static_cast<long long>(p_.size()) >= detail::kMinParallelItems &&
         static_cast<long long>(pairs_.size()) >= detail::kMinParallelItems;
}

double DemEngine::kinetic_energy_j() const {
  double e = 0.0;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!p_.active[i]) continue;
    e += 0.5 * p_.mass_kg[i] * p_.velocity(i).squaredNorm();
    if (p_.with_spin) e += 0.5 * p_.inertia_kg_m2[i] * p_.spin(i).squaredNorm();
  }
  return e;
}

void DemEngine::drop_on_disc_particles() {
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (p_.active[i]) {
      p_.active[i] = 0;
      ++inactive_;
    }
  lists_dirty_ = true;
  touch_rows_kept_ = false;
}

void DemEngine::run_until(double t_s) {
  while (time_s_ + 0.5 * dt_s_ < t_s) step();
}

}  // namespace spread::dem
