// Keeping the pair list (neighbor_list.hpp) and the wall list valid: rebuilt when a particle has moved
// more than half the skin since the last build, or when particles were added or removed.
#include <cstdint>

#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"

namespace spread::dem {

using detail::Clock;
using detail::seconds_since;

void DemEngine::maintain_lists() {
  const auto t0 = Clock::now();
  if (!params_.has(effect::kParticleContact)) {
    if (inactive_ > 0) { p_.compact(); inactive_ = 0; }
    lists_dirty_ = false;
    return;
  }
  if (!lists_dirty_) {
    const double half = 0.5 * skin_m_;
    const double moved2 = moved2_since_build_ >= 0.0 ? moved2_since_build_ : max_displacement2(p_, params_.periodic_z);
    if (moved2 > half * half) lists_dirty_ = true;
  }
  moved2_since_build_ = -1.0;
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

}  // namespace spread::dem
