#include "libspread/physics/dem/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "libspread/physics/dem/contact_kernel.hpp"

namespace spread::dem {

namespace {
std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  return a < b ? (static_cast<std::uint64_t>(a) << 32) | b : (static_cast<std::uint64_t>(b) << 32) | a;
}
}  // namespace

double max_displacement2(const ParticleArrays& p, const PeriodicZ& periodic) {
  return max_displacement2(p, p.x0, p.y0, p.z0, periodic);
}

double max_displacement2(const ParticleArrays& p, const std::vector<double>& x_ref, const std::vector<double>& y_ref,
                         const std::vector<double>& z_ref, const PeriodicZ& periodic) {
  double m = 0.0;
  const double period = periodic.length_m();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double dx = p.x[i] - x_ref[i], dy = p.y[i] - y_ref[i];
    double dz = p.z[i] - z_ref[i];
    if (periodic.enabled) dz = minimum_image_z(dz, period);  // a wrap is not a move
    m = std::max(m, dx * dx + dy * dy + dz * dz);
  }
  return m;
}

void build_near_list(const ParticleArrays& p, double inner_skin_m, PairList& list, NearList& near, const PeriodicZ& periodic) {
  const std::size_t n = p.size();
  const double period = periodic.length_m();
  near.inner_skin_m = inner_skin_m;
  near.start.assign(n + 1, 0);
  near.pairs.clear();
  near.first.clear();
  near.second.clear();
  near.held.clear();
  for (std::size_t i = 0; i < n; ++i) {
    near.start[i] = static_cast<std::uint32_t>(near.pairs.size());
    for (std::uint32_t k = list.first_start[i]; k < list.first_start[i + 1]; ++k) {
      const std::uint32_t j = list.second[k];
      const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
      double dz = p.z[i] - p.z[j];
      if (periodic.enabled) dz = minimum_image_z(dz, period);
      const double cut = p.radius_m[i] + p.radius_m[j] + inner_skin_m;
      if (dx * dx + dy * dy + dz * dz < cut * cut) {
        near.pairs.push_back(k);
        near.first.push_back(static_cast<std::uint32_t>(i));
        near.second.push_back(j);
        near.held.push_back(list.held[k]);
      } else if (list.held[k] != 0) {
        clear_history(list.history.data() + static_cast<std::size_t>(k) * kHistoryDoubles);
        list.held[k] = 0;
      }
    }
  }
  near.start[n] = static_cast<std::uint32_t>(near.pairs.size());
  near.held.resize(near.held.size() + kNearHeldPadding, 0);
  near.held_synced = true;
  near.x0 = p.x;
  near.y0 = p.y;
  near.z0 = p.z;
  near.moved_since_pair_build_m = std::sqrt(max_displacement2(p, periodic));
}

namespace {

// The previous build's history in ascending key order, in list.previous_key / previous_history. The list is
// built in ascending (i, j) order and ids ascend with the index unless particles were reordered, so it is
// usually sorted already: then its arrays trade places with the previous build's (kept for their storage:
// a build allocates nothing new for them, so fresh pages — a page fault each — are not zeroed every time).
void take_old_history(PairList& list) {
  std::vector<std::uint64_t>& old_keys = list.previous_key;
  std::vector<double>& old_hist = list.previous_history;
  if (std::is_sorted(list.key.begin(), list.key.end())) {
    old_keys.swap(list.key);
    old_hist.swap(list.history);
    return;
  }
  std::vector<std::size_t> old_order(list.size());
  for (std::size_t k = 0; k < old_order.size(); ++k) old_order[k] = k;
  std::sort(old_order.begin(), old_order.end(), [&](std::size_t a, std::size_t b) { return list.key[a] < list.key[b]; });
  old_keys.resize(old_order.size());
  old_hist.resize(old_order.size() * kHistoryDoubles);
  for (std::size_t k = 0; k < old_order.size(); ++k) {
    old_keys[k] = list.key[old_order[k]];
    for (int h = 0; h < kHistoryDoubles; ++h) old_hist[k * kHistoryDoubles + h] = list.history[old_order[k] * kHistoryDoubles + h];
  }
}

// The active particles' bounding box and largest radius; false when none is active.
bool active_bounds(const ParticleArrays& p, double& rmax, Vec3& lo, Vec3& hi) {
  rmax = 0.0;
  lo = Vec3::Constant(1e300);
  hi = Vec3::Constant(-1e300);
  bool any = false;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.active[i]) continue;
    any = true;
    rmax = std::max(rmax, p.radius_m[i]);
    const Vec3 q = p.position(i);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  return any;
}

// The active particles binned into cells at least the cut-off 2 r_max + skin wide (CSR: the slots of cell c
// are items[start[c] .. start[c + 1]), ascending).
struct CellGrid {
  int nx = 0, ny = 0, nz = 0;
  double cell = 0.0, cell_z = 0.0;
  Vec3 lo = Vec3::Zero();
  bool periodic = false;
  std::vector<std::uint32_t> start, items;

  void index_of(const ParticleArrays& p, std::size_t i, int& ix, int& iy, int& iz) const {
    ix = std::min(nx - 1, static_cast<int>((p.x[i] - lo.x()) / cell));
    iy = std::min(ny - 1, static_cast<int>((p.y[i] - lo.y()) / cell));
    if (periodic) {
      // Positions are wrapped once per step; a predictor may carry one a little past either end.
      iz = static_cast<int>(std::floor((p.z[i] - lo.z()) / cell_z)) % nz;
      if (iz < 0) iz += nz;
    } else {
      iz = std::min(nz - 1, static_cast<int>((p.z[i] - lo.z()) / cell_z));
    }
  }
  std::size_t flat(int ix, int iy, int iz) const { return (static_cast<std::size_t>(iz) * ny + iy) * nx + ix; }
  // The z layers to scan around layer iz: its neighbours, wrapped when periodic (fewer than three layers in
  // the period: each layer once, the minimum image then picks the near copy). Returns their count.
  int neighbour_layers(int iz, int (&layers)[3]) const {
    int count = 0;
    if (periodic && nz < 3) {
      for (int c = 0; c < nz; ++c) layers[count++] = c;
      return count;
    }
    for (int dz = -1; dz <= 1; ++dz) {
      int cz = iz + dz;
      if (periodic) cz = (cz + nz) % nz;
      else if (cz < 0 || cz >= nz) continue;
      layers[count++] = cz;
    }
    return count;
  }
};

CellGrid bin_particles(const ParticleArrays& p, double rmax, Vec3 lo, const Vec3& hi, double skin_m, const PeriodicZ& periodic) {
  const std::size_t n = p.size();
  CellGrid g;
  g.cell = 2.0 * rmax + skin_m;
  g.periodic = periodic.enabled;
  const double period = periodic.length_m();
  if (periodic.enabled && !(period >= 2.0 * g.cell)) {
    std::ostringstream os;
    os << "periodic z axis: period " << period << " m is shorter than twice the pair-search cut-off 2 r_max + skin = "
       << g.cell << " m (a pair would meet more than one image)";
    throw std::invalid_argument(os.str());
  }
  Vec3 ext = hi - lo;
  if (periodic.enabled) { lo.z() = periodic.min_m; ext.z() = period; }
  // Periodic z: a whole number of cells spans the period (each at least the cut-off wide), so the cells at
  // both ends are neighbours.
  auto cells_z = [&](double c) { return periodic.enabled ? std::max(1, static_cast<int>(period / c)) : static_cast<int>(ext.z() / c) + 1; };
  while ((ext.x() / g.cell + 1) * (ext.y() / g.cell + 1) * cells_z(g.cell) > 8.0 * static_cast<double>(n) + 64) g.cell *= 1.3;
  g.nx = static_cast<int>(ext.x() / g.cell) + 1;
  g.ny = static_cast<int>(ext.y() / g.cell) + 1;
  g.nz = cells_z(g.cell);
  g.cell_z = periodic.enabled ? period / g.nz : g.cell;
  g.lo = lo;
  const std::size_t ncell = static_cast<std::size_t>(g.nx) * g.ny * g.nz;
  std::vector<std::uint32_t> cell_of(n);
  g.start.assign(ncell + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!p.active[i]) continue;
    int ix, iy, iz;
    g.index_of(p, i, ix, iy, iz);
    cell_of[i] = static_cast<std::uint32_t>(g.flat(ix, iy, iz));
    ++g.start[cell_of[i] + 1];
  }
  for (std::size_t c = 1; c <= ncell; ++c) g.start[c] += g.start[c - 1];
  g.items.resize(g.start[ncell]);
  std::vector<std::uint32_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    if (p.active[i]) g.items[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);  // ascending slot order per cell
  return g;
}

// Every pair (i, j > i) of active particles closer than r_i + r_j + skin, grouped by i, j ascending.
void search_pairs(const ParticleArrays& p, const CellGrid& g, double skin_m, const PeriodicZ& periodic, PairList& list) {
  const std::size_t n = p.size();
  const double period = periodic.length_m();
  std::vector<std::uint32_t> mine;
  for (std::size_t i = 0; i < n; ++i) {
    list.first_start[i] = static_cast<std::uint32_t>(list.first.size());
    if (!p.active[i]) continue;
    int ix, iy, iz, layers[3];
    g.index_of(p, i, ix, iy, iz);
    mine.clear();
    const int nlayers = g.neighbour_layers(iz, layers);
    for (int l = 0; l < nlayers; ++l)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int cx = ix + dx, cy = iy + dy;
          if (cx < 0 || cy < 0 || cx >= g.nx || cy >= g.ny) continue;
          const std::size_t c = g.flat(cx, cy, layers[l]);
          // A cell's slots ascend: those up to i are passed over without a look at their positions (a
          // cell below i in the packing order holds none above it).
          const std::uint32_t end = g.start[c + 1];
          std::uint32_t k = g.start[c];
          if (k == end || g.items[end - 1] <= i) continue;
          while (g.items[k] <= i) ++k;
          for (; k < end; ++k) {
            const std::uint32_t j = g.items[k];
            const double cut = p.radius_m[i] + p.radius_m[j] + skin_m;
            const double ddx = p.x[j] - p.x[i], ddy = p.y[j] - p.y[i];
            double ddz = p.z[j] - p.z[i];
            if (periodic.enabled) ddz = minimum_image_z(ddz, period);
            if (ddx * ddx + ddy * ddy + ddz * ddz < cut * cut) mine.push_back(j);
          }
        }
    std::sort(mine.begin(), mine.end());
    for (std::uint32_t j : mine) {
      list.first.push_back(static_cast<std::uint32_t>(i));
      list.second.push_back(j);
      list.key.push_back(pair_key(p.id[i], p.id[j]));
    }
  }
  list.first_start[n] = static_cast<std::uint32_t>(list.first.size());
}

// Each new pair takes its old history, if it had one. New keys in ascending order (the usual case, see
// take_old_history) are matched by one merge walk over the old keys; otherwise each is looked up. (A binary
// search per pair was half the cost of a rebuild on the 20,250-bead drum.)
void transfer_history(PairList& list) {
  const std::vector<std::uint64_t>& old_keys = list.previous_key;
  const std::vector<double>& old_hist = list.previous_history;
  const std::size_t np = list.size();
  // Sized only (the storage is an earlier build's): every entry is written below, once.
  list.history.resize(np * kHistoryDoubles);
  list.held.resize(np);
  const bool new_sorted = std::is_sorted(list.key.begin(), list.key.end());
  std::size_t walk = 0;
  for (std::size_t k = 0; k < np; ++k) {
    const std::uint64_t key = list.key[k];
    std::size_t o;
    if (new_sorted) {
      while (walk < old_keys.size() && old_keys[walk] < key) ++walk;
      o = walk;
    } else {
      o = static_cast<std::size_t>(std::lower_bound(old_keys.begin(), old_keys.end(), key) - old_keys.begin());
    }
    double* const h = list.history.data() + k * kHistoryDoubles;
    std::uint8_t held = 0;
    if (o < old_keys.size() && old_keys[o] == key) {
      for (int c = 0; c < kHistoryDoubles; ++c) {
        h[c] = old_hist[o * kHistoryDoubles + c];
        if (h[c] != 0.0) held = 1;
      }
    } else {
      for (int c = 0; c < kHistoryDoubles; ++c) h[c] = 0.0;
    }
    list.held[k] = held;
  }
}

// The gather index (pairs by `second`, CSR) and the per-pair output arrays.
void index_by_second(std::size_t n, PairList& list) {
  const std::size_t np = list.size();
  list.second_start.assign(n + 1, 0);
  for (std::size_t k = 0; k < np; ++k) ++list.second_start[list.second[k] + 1];
  for (std::size_t i = 1; i <= n; ++i) list.second_start[i] += list.second_start[i - 1];
  list.second_pairs.resize(np);
  std::vector<std::uint32_t> fill(list.second_start.begin(), list.second_start.end() - 1);
  for (std::size_t k = 0; k < np; ++k) list.second_pairs[fill[list.second[k]]++] = static_cast<std::uint32_t>(k);
  // Sized only: the passes that use them write every entry (new entries start at zero).
  list.force.resize(np * 3, 0.0);
  list.torque_first.resize(np * 3, 0.0);
  list.torque_second.resize(np * 3, 0.0);
}

}  // namespace

void build_pair_list(ParticleArrays& p, double skin_m, PairList& list, const PeriodicZ& periodic) {
  const std::size_t n = p.size();
  take_old_history(list);
  list.first.clear();
  list.second.clear();
  list.key.clear();
  for (std::size_t i = 0; i < n; ++i) { p.x0[i] = p.x[i]; p.y0[i] = p.y[i]; p.z0[i] = p.z[i]; }
  list.first_start.assign(n + 1, 0);
  double rmax;
  Vec3 lo, hi;
  if (active_bounds(p, rmax, lo, hi)) search_pairs(p, bin_particles(p, rmax, lo, hi, skin_m, periodic), skin_m, periodic, list);
  transfer_history(list);
  list.stored_pairs_ready = false;
}

void prepare_stored_pairs(std::size_t n, PairList& list) {
  if (list.stored_pairs_ready) return;
  index_by_second(n, list);
  list.stored_pairs_ready = true;
}

}  // namespace spread::dem
