#pragma once
// Particle–particle contact search: cell binning into a uniform grid, a Verlet pair list with a skin
// (rebuilt when any particle has moved more than skin/2), and the per-pair tangential history carried
// across rebuilds by the pair's particle ids (flat arrays keyed by pair, no object per contact).
// Built only when particle–particle contact is on.
#include <cstdint>
#include <vector>

#include "libspread/dem/particles.hpp"

namespace spread::dem {

struct PairList {
  // Half list: first < second (slots); pairs grouped by `first` in slot order, `second` ascending.
  std::vector<std::uint32_t> first, second;
  std::vector<std::uint64_t> key;      // (id_low << 32) | id_high
  std::vector<double> history;         // kHistoryDoubles per pair
  // Gather index: pairs where a slot is `second`, CSR (start has size()+1 entries).
  std::vector<std::uint32_t> second_start, second_pairs;
  std::vector<std::uint32_t> first_start;  // CSR start of each slot's pairs as `first`
  // Per-pair outputs of the force pass (force on `first`, torques on both).
  std::vector<double> force, torque_first, torque_second;

  std::size_t size() const { return first.size(); }
};

// Rebuilds `list` for the active particles of `p`; keeps the history of pairs present before.
// Also stores the build positions (x0,y0,z0) in `p`.
void build_pair_list(ParticleArrays& p, double skin_m, PairList& list);

// Largest squared displacement since the last build (m²), active particles only.
double max_displacement2(const ParticleArrays& p);

}  // namespace spread::dem
