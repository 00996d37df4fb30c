// One force evaluation: the contact law and the effects (rotation, rolling) chosen once per call from
// a table of instantiations, so the passes carry no per-contact branch on them.
#include "libspread/dem/contact_laws.hpp"
#include "libspread/dem/engine.hpp"
#include "libspread/dem/engine_detail.hpp"

namespace spread::dem {

using detail::Clock;
using detail::seconds_since;

template <class Law, bool kRotation, bool kRolling>
void DemEngine::compute_forces_impl() {
  if (coeffs_dirty_) update_pair_coeffs<Law>();
  wall_forces<Law, kRotation, kRolling>();  // sets the sums: walls first
  if (params_.particle_contact) particle_forces<Law, kRotation, kRolling>();
}

void DemEngine::compute_forces() {
  const auto t0 = Clock::now();
  walls_.set_time(time_s_);
  using Fn = void (DemEngine::*)();
  // Dispatch table over the effect combination, in SPREAD_DEM_FORCE_VARIANTS' order: law, then
  // rotation, then rolling.
#define SPREAD_ENTRY(Law, kRotation, kRolling) &DemEngine::compute_forces_impl<Law, kRotation, kRolling>,
  static constexpr Fn table[8] = {SPREAD_DEM_FORCE_VARIANTS(SPREAD_ENTRY)};
#undef SPREAD_ENTRY
  const int law = params_.model == ContactModel::kHertzThornton ? 0 : 1;
  (this->*table[law * 4 + (params_.rotation ? 2 : 0) + (params_.rolling ? 1 : 0)])();
  stats_.forces_s += seconds_since(t0);
}

}  // namespace spread::dem
