// One force evaluation: the passes of the engine's force variant (composed contact law × the effects
// that shape a pass, force_variants.hpp), taken from tables generated from the sub-model lists and the
// registry bits, so the passes carry no per-contact branch or virtual call on them. The contact effects
// decide whether a pass runs at all: one that is off is not entered.
#include <algorithm>

#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"

namespace spread::dem {

using detail::Clock;
using detail::seconds_since;

void DemEngine::compute_forces() {
  const auto t0 = Clock::now();
  walls_.set_time(time_s_);
  if (coeffs_dirty_) (this->*kCoeffUpdates[force_variant_])();
  if (params_.has(effect::kWallContact)) {
    const auto t_walls = Clock::now();
    (this->*kWallPasses[force_variant_])();  // sets the sums: walls first
    stats_.walls_s += seconds_since(t_walls);
  } else if (!sums_cleared_) {
    clear_forces();
  }
  sums_cleared_ = false;
  if (params_.has(effect::kParticleContact)) (this->*kParticlePasses[force_variant_])();
  stats_.forces_s += seconds_since(t0);
}

effect::EffectSet DemEngine::pass_effects() const { return kForceVariants[force_variant_].effects(); }

void DemEngine::clear_forces() {
  const std::size_t n = p_.size();
  std::fill_n(p_.fx.begin(), n, 0.0);
  std::fill_n(p_.fy.begin(), n, 0.0);
  std::fill_n(p_.fz.begin(), n, 0.0);
  if (!p_.with_spin) return;
  std::fill_n(p_.tx.begin(), n, 0.0);
  std::fill_n(p_.ty.begin(), n, 0.0);
  std::fill_n(p_.tz.begin(), n, 0.0);
}

}  // namespace spread::dem
