// One force evaluation: the passes of the engine's force variant (composed contact law × rotation,
// force_variants.hpp), taken from tables generated from the sub-model lists, so the passes carry no
// per-contact branch or virtual call on them.
#include "libspread/dem/engine.hpp"
#include "libspread/dem/engine_detail.hpp"

namespace spread::dem {

using detail::Clock;
using detail::seconds_since;

void DemEngine::compute_forces() {
  const auto t0 = Clock::now();
  walls_.set_time(time_s_);
  if (coeffs_dirty_) (this->*kCoeffUpdates[force_variant_])();
  (this->*kWallPasses[force_variant_])();  // sets the sums: walls first
  if (params_.particle_contact) (this->*kParticlePasses[force_variant_])();
  stats_.forces_s += seconds_since(t0);
}

}  // namespace spread::dem
