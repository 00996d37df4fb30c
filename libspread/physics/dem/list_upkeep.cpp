// Keeping the pair list (neighbor_list.hpp) and the wall list valid: rebuilt when a particle has moved
// more than half the skin since the last build, or when particles were added or removed.
#include <cmath>
#include <cstdint>

#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"

namespace spread::dem {

using detail::Clock;
using detail::seconds_since;

// Half the skin: on the 20,250-bead drum (bench_drum), 0.2, 0.35, 0.5 and 0.75 of it gave 1.49–1.50,
// 1.49, 1.47–1.48 and 1.52–1.54 s per 1000 steps turning: a narrower near list is rebuilt more often.
double DemEngine::inner_skin_m() const { return 0.5 * skin_m_; }

void DemEngine::maintain_lists() {
  const auto t0 = Clock::now();
  if (!params_.has(effect::kParticleContact)) {
    if (inactive_ > 0) {
      mesh_near_.compact(p_.active);
      p_.compact();
      touch_rows_kept_ = false;
      inactive_ = 0;
    }
    lists_dirty_ = false;
    return;
  }
  const bool near_valid = near_.start.size() == p_.size() + 1;
  double moved2_near = moved2_since_near_;
  moved2_since_near_ = -1.0;
  if (near_valid && moved2_near < 0.0) moved2_near = max_displacement2(p_, near_.x0, near_.y0, near_.z0, params_.periodic_z);
  if (!lists_dirty_) {
    // A particle's move since the pair list's build is at most its move since the near list's build plus
    // the largest move up to that build (triangle inequality; a hair more for rounding): only when that
    // bound passes half the skin are the moves since the pair list's build measured.
    const double half = 0.5 * skin_m_;
    const bool may_have = !near_valid || (std::sqrt(moved2_near) + near_.moved_since_pair_build_m) * (1.0 + 1e-9) > half;
    if (may_have && max_displacement2(p_, params_.periodic_z) > half * half) lists_dirty_ = true;
  }
  if (!lists_dirty_ && near_valid) {
    // The near list holds while no particle has moved inner_skin / 2 since its build (a hair less, so
    // that rounding in the distances cannot let a pair through).
    const double half = 0.5 * (1.0 - 1e-9) * near_.inner_skin_m;
    if (moved2_near > half * half) {
      build_near_list(p_, near_.inner_skin_m, pairs_, near_, params_.periodic_z);
      ++stats_.near_list_builds;
      if (walls_fixed_in_space_) {
        walls_.set_time(time_s_);
        narrow_wall_list();
      }
    }
  }
  if (lists_dirty_) {
    if (inactive_ > 0) {
      // Compaction renumbers the slots; the pair history follows the particle ids.
      mesh_near_.compact(p_.active);
      p_.compact();
      touch_rows_kept_ = false;
      inactive_ = 0;
    }
    build_pair_list(p_, skin_m_, pairs_, params_.periodic_z);
    build_near_list(p_, inner_skin_m(), pairs_, near_, params_.periodic_z);
    ++stats_.pair_list_builds;
    if (walls_fixed_in_space_) {
      // Until the next build no particle moves more than skin/2, so one with no wall within its radius
      // plus the skin (and no wall history) cannot touch a wall before then: the candidates. (A centre
      // behind a one-sided wall is not reported either; it is looked at again at the next build.)
      walls_.set_time(time_s_);
      wall_candidates_.clear();
      for (std::size_t i = 0; i < p_.size(); ++i) {
        if (!p_.active[i]) continue;
        if (p_.wall_key[i * kWallSlots] != 0 || walls_.groups_within(p_.position(i), p_.radius_m[i] + skin_m_) != 0)
          wall_candidates_.push_back(static_cast<std::uint32_t>(i));
      }
      narrow_wall_list();
    }
    lists_dirty_ = false;
  }
  stats_.pair_search_s += seconds_since(t0);
}

void DemEngine::narrow_wall_list() {
  // Until the near list's next build no particle moves more than half its inner skin (maintain_lists
  // rebuilds it before), so of the candidates only those with a wall within their radius plus that can
  // touch one; per particle, the wall groups within that reach (a particle still holding a wall history
  // looks at all). On the drum at rest this keeps about 1,760 of about 2,800 candidates (docs/drum.md). The
  // walls stand at time_s_ (WallSet::set_time, by the caller).
  const double reach_m = 0.5 * near_.inner_skin_m;
  walls_near_.assign(p_.size(), 0);
  wall_listed_.clear();
  for (const std::uint32_t i : wall_candidates_) {
    if (!p_.active[i]) continue;
    walls_near_[i] = p_.wall_key[i * kWallSlots] != 0 ? ~0ull : walls_.groups_within(p_.position(i), p_.radius_m[i] + reach_m);
    if (walls_near_[i] != 0) wall_listed_.push_back(i);
  }
}

}  // namespace spread::dem
