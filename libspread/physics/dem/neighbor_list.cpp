#include "libspread/physics/dem/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace spread::dem {

namespace {
std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  return a < b ? (static_cast<std::uint64_t>(a) << 32) | b : (static_cast<std::uint64_t>(b) << 32) | a;
}
}  // namespace

double max_displacement2(const ParticleArrays& p, const PeriodicZ& periodic) {
  double m = 0.0;
  const double period = periodic.length_m();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double dx = p.x[i] - p.x0[i], dy = p.y[i] - p.y0[i];
    double dz = p.z[i] - p.z0[i];
    if (periodic.enabled) dz = minimum_image_z(dz, period);  // a wrap is not a move
    m = std::max(m, dx * dx + dy * dy + dz * dz);
  }
  return m;
}

void build_pair_list(ParticleArrays& p, double skin_m, PairList& list, const PeriodicZ& periodic) {
  const std::size_t n = p.size();
  // Old history in ascending key order, for the transfer below. The list is built in ascending (i, j)
  // order and ids ascend with the index unless particles were reordered, so it is usually sorted
  // already: then it is taken over as it is (no sort, no copy).
  // The old arrays trade places with those of the build before (kept in the list for their storage): a
  // build allocates nothing new for them, so fresh pages (a page fault each) are not zeroed every time.
  std::vector<std::uint64_t>& old_keys = list.previous_key;
  std::vector<double>& old_hist = list.previous_history;
  if (std::is_sorted(list.key.begin(), list.key.end())) {
    old_keys.swap(list.key);
    old_hist.swap(list.history);
  } else {
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
  list.first.clear();
  list.second.clear();
  list.key.clear();
  list.history.clear();
  for (std::size_t i = 0; i < n; ++i) { p.x0[i] = p.x[i]; p.y0[i] = p.y[i]; p.z0[i] = p.z[i]; }

  double rmax = 0.0;
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (!p.active[i]) continue;
    any = true;
    rmax = std::max(rmax, p.radius_m[i]);
    const Vec3 q = p.position(i);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  list.first_start.assign(n + 1, 0);
  list.second_start.assign(n + 1, 0);
  list.second_pairs.clear();
  if (any) {
    double cell = 2.0 * rmax + skin_m;
    const double period = periodic.length_m();
    if (periodic.enabled && !(period >= 2.0 * cell)) {
      std::ostringstream os;
      os << "periodic z axis: period " << period << " m is shorter than twice the pair-search cut-off 2 r_max + skin = "
         << cell << " m (a pair would meet more than one image)";
      throw std::invalid_argument(os.str());
    }
    Vec3 ext = hi - lo;
    if (periodic.enabled) { lo.z() = periodic.min_m; ext.z() = period; }
    // Periodic z: a whole number of cells spans the period (each at least the cut-off wide), so the
    // cells at both ends are neighbours.
    auto cells_z = [&](double c) { return periodic.enabled ? std::max(1, static_cast<int>(period / c)) : static_cast<int>(ext.z() / c) + 1; };
    while ((ext.x() / cell + 1) * (ext.y() / cell + 1) * cells_z(cell) > 8.0 * static_cast<double>(n) + 64) cell *= 1.3;
    const int nx = static_cast<int>(ext.x() / cell) + 1, ny = static_cast<int>(ext.y() / cell) + 1, nz = cells_z(cell);
    const double cell_z = periodic.enabled ? period / nz : cell;
    const std::size_t ncell = static_cast<std::size_t>(nx) * ny * nz;
    std::vector<std::uint32_t> cell_of(n), start(ncell + 1, 0), items;
    auto cell_index = [&](std::size_t i, int& ix, int& iy, int& iz) {
      ix = std::min(nx - 1, static_cast<int>((p.x[i] - lo.x()) / cell));
      iy = std::min(ny - 1, static_cast<int>((p.y[i] - lo.y()) / cell));
      if (periodic.enabled) {
        // Positions are wrapped once per step; a predictor may carry one a little past either end.
        iz = static_cast<int>(std::floor((p.z[i] - lo.z()) / cell_z)) % nz;
        if (iz < 0) iz += nz;
      } else {
        iz = std::min(nz - 1, static_cast<int>((p.z[i] - lo.z()) / cell_z));
      }
    };
    for (std::size_t i = 0; i < n; ++i) {
      if (!p.active[i]) continue;
      int ix, iy, iz;
      cell_index(i, ix, iy, iz);
      cell_of[i] = static_cast<std::uint32_t>((static_cast<std::size_t>(iz) * ny + iy) * nx + ix);
      ++start[cell_of[i] + 1];
    }
    for (std::size_t c = 1; c <= ncell; ++c) start[c] += start[c - 1];
    items.resize(start[ncell]);
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      if (p.active[i]) items[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);  // ascending slot order per cell

    // z layers to scan around layer iz: the three neighbours, wrapped when periodic (fewer than three
    // layers in the period: each layer once, the minimum image then picks the near copy).
    int layers[3];
    auto neighbour_layers = [&](int iz) {
      int count = 0;
      if (periodic.enabled && nz < 3) {
        for (int c = 0; c < nz; ++c) layers[count++] = c;
      } else {
        for (int dz = -1; dz <= 1; ++dz) {
          int cz = iz + dz;
          if (periodic.enabled) cz = (cz + nz) % nz;
          else if (cz < 0 || cz >= nz) continue;
          layers[count++] = cz;
        }
      }
      return count;
    };
    std::vector<std::uint32_t> mine;
    for (std::size_t i = 0; i < n; ++i) {
      list.first_start[i] = static_cast<std::uint32_t>(list.first.size());
      if (!p.active[i]) continue;
      int ix, iy, iz;
      cell_index(i, ix, iy, iz);
      mine.clear();
      const int nlayers = neighbour_layers(iz);
      for (int l = 0; l < nlayers; ++l)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int cx = ix + dx, cy = iy + dy, cz = layers[l];
            if (cx < 0 || cy < 0 || cx >= nx || cy >= ny) continue;
            const std::size_t c = (static_cast<std::size_t>(cz) * ny + cy) * nx + cx;
            for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) {
              const std::uint32_t j = items[k];
              if (j <= i) continue;
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
  }
  list.first_start[n] = static_cast<std::uint32_t>(list.first.size());
  const std::size_t np = list.size();
  list.history.assign(np * kHistoryDoubles, 0.0);
  list.held.assign(np, 0);
  // Each new pair takes its old history, if it had one. New keys in ascending order (the usual case, see
  // above) are matched by one merge walk over the old keys; otherwise each is looked up. (A binary search
  // per pair was half the cost of a rebuild on the 20,250-bead drum.)
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
    if (o < old_keys.size() && old_keys[o] == key) {
      for (int h = 0; h < kHistoryDoubles; ++h) {
        list.history[k * kHistoryDoubles + h] = old_hist[o * kHistoryDoubles + h];
        if (old_hist[o * kHistoryDoubles + h] != 0.0) list.held[k] = 1;
      }
    }
  }
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

}  // namespace spread::dem
