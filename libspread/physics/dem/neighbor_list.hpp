#pragma once
// Particle–particle contact search: cell binning into a uniform grid, a Verlet pair list with a skin
// (rebuilt when any particle has moved more than skin/2), and the per-pair tangential history carried
// across rebuilds by the pair's particle ids (flat arrays keyed by pair, no object per contact).
// Built only when particle–particle contact is on.
//
// Layout (CSR half list): the pairs of slot i as `first` are pairs [first_start[i], first_start[i+1]),
// their partners in `second` (ascending), and each pair's history sits at the same index — the force
// pass walks i, then its partners, and finds the history next to the pair without any lookup.
//
// Optional periodic axis along z: the search sees the periodic images (cells wrap in z) and every pair
// vector uses the minimum image, so a pair across the boundary is found and treated as in the interior.
#include <cmath>
#include <cstdint>
#include <vector>

#include "libspread/physics/dem/particles.hpp"

namespace spread::dem {

// Periodic boundary along z: positions live in [min_m, max_m) and z + (max_m − min_m) is the same point.
struct PeriodicZ {
  bool enabled = false;
  double min_m = 0.0;
  double max_m = 0.0;
  double length_m() const { return max_m - min_m; }
};

// Minimum-image z separation for |dz| < 1.5 L (positions are wrapped every step, so |dz| < L + a step).
inline double minimum_image_z(double dz_m, double period_m) {
  const double half = 0.5 * period_m;
  if (dz_m > half) return dz_m - period_m;
  if (dz_m < -half) return dz_m + period_m;
  return dz_m;
}

// z mapped into [min_m, max_m) (any distance away).
inline double wrap_into_period(double z_m, const PeriodicZ& periodic) {
  const double rel = z_m - periodic.min_m, period = periodic.length_m();
  return periodic.min_m + (rel - period * std::floor(rel / period));
}

struct PairList {
  // Half list: first < second (slots); pairs grouped by `first` in slot order, `second` ascending.
  std::vector<std::uint32_t> first, second;
  std::vector<std::uint64_t> key;      // (id_low << 32) | id_high
  std::vector<double> history;         // kHistoryDoubles per pair; all zero while the pair is not touching
  // 1 when the pair's history may hold something (it touched at its last evaluation): the force pass
  // tests this byte for the ~2/3 of listed pairs that are apart instead of loading their 32-byte history.
  std::vector<std::uint8_t> held;
  // Gather index: pairs where a slot is `second`, CSR (start has size()+1 entries). Built with the per-pair
  // outputs below on demand (prepare_stored_pairs): only the force pass that stores pairs reads them.
  std::vector<std::uint32_t> second_start, second_pairs;
  std::vector<std::uint32_t> first_start;  // CSR start of each slot's pairs as `first`
  // Per-pair outputs of the force pass (force on `first`, torques on both). Written only when the
  // engine stores per-pair results (several threads, or an energy monitor attached); the single-thread
  // pass adds each pair straight into the particles' sums instead. Zero for pairs not touching.
  std::vector<double> force, torque_first, torque_second;
  bool stored_pairs_ready = false;  // the gather index and the per-pair outputs fit this build
  // The previous build's keys and history: build_pair_list's scratch, kept for their storage.
  std::vector<std::uint64_t> previous_key;
  std::vector<double> previous_history;

  std::size_t size() const { return first.size(); }
};

// Rebuilds `list` for the active particles of `p`; keeps the history of pairs present before.
// Also stores the build positions (x0,y0,z0) in `p`. With a periodic z axis the period must be at least
// twice the search cut-off 2 r_max + skin (one image per pair); throws std::invalid_argument otherwise.
void build_pair_list(ParticleArrays& p, double skin_m, PairList& list, const PeriodicZ& periodic = {});
// The gather index and the per-pair outputs for the list's current build (n: the particle slots), if not
// built yet.
void prepare_stored_pairs(std::size_t n, PairList& list);

// Largest squared displacement since the last build (m²), active particles only (minimum image in z).
double max_displacement2(const ParticleArrays& p, const PeriodicZ& periodic = {});
// The same against other reference positions (the near list's).
double max_displacement2(const ParticleArrays& p, const std::vector<double>& x_ref, const std::vector<double>& y_ref,
                         const std::vector<double>& z_ref, const PeriodicZ& periodic);

// The near list: the listed pairs closer than r_i + r_j + inner_skin_m (inner_skin_m < skin), per first slot
// as CSR over pair indices, ascending. While no particle has moved more than inner_skin_m / 2 since its build,
// a pair left out is at least r_i + r_j apart and cannot touch, so the force pass need look at the near
// pairs only — about a third of a list built with a skin of r_max in a packed bed, most of them touching.
// Built from the pair list (a distance per listed pair, no search): after every pair-list build and
// whenever a particle has moved inner_skin_m / 2 since the near list's last build. A pair left out that
// still holds a spring is apart, and is released here, as the force pass would release it this step.
struct NearList {
  std::vector<std::uint32_t> start, pairs;  // start: slots + 1 entries
  std::vector<std::uint32_t> first, second;  // per entry: the pair's bodies (the batched pass's touch test)
  // Per entry, a copy of its pair's PairList::held that the batched pass keeps with it (eight entries' in one
  // load), and kNearHeldPadding zeros after the last; held_synced: equal to the pairs' (a pass that updates
  // only those clears it).
  std::vector<std::uint8_t> held;
  bool held_synced = false;
  std::vector<double> x0, y0, z0;           // positions at the build (m)
  double inner_skin_m = 0.0;
  double moved_since_pair_build_m = 0.0;    // largest move from the pair list's build to this one (m)
};
inline constexpr std::size_t kNearHeldPadding = 8;
void build_near_list(const ParticleArrays& p, double inner_skin_m, PairList& list, NearList& near,
                     const PeriodicZ& periodic = {});

}  // namespace spread::dem
