#include "libspread/dem/neighbor_list.hpp"

#include <algorithm>
#include <cmath>

namespace spread::dem {

namespace {
std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  return a < b ? (static_cast<std::uint64_t>(a) << 32) | b : (static_cast<std::uint64_t>(b) << 32) | a;
}
}  // namespace

double max_displacement2(const ParticleArrays& p) {
  double m = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double dx = p.x[i] - p.x0[i], dy = p.y[i] - p.y0[i], dz = p.z[i] - p.z0[i];
    m = std::max(m, dx * dx + dy * dy + dz * dz);
  }
  return m;
}

void build_pair_list(ParticleArrays& p, double skin_m, PairList& list) {
  const std::size_t n = p.size();
  // Old history, sorted by key, for transfer.
  std::vector<std::size_t> old_order(list.size());
  for (std::size_t k = 0; k < old_order.size(); ++k) old_order[k] = k;
  std::sort(old_order.begin(), old_order.end(), [&](std::size_t a, std::size_t b) { return list.key[a] < list.key[b]; });
  std::vector<std::uint64_t> old_keys(old_order.size());
  std::vector<double> old_hist(old_order.size() * kHistoryDoubles);
  for (std::size_t k = 0; k < old_order.size(); ++k) {
    old_keys[k] = list.key[old_order[k]];
    for (int h = 0; h < kHistoryDoubles; ++h) old_hist[k * kHistoryDoubles + h] = list.history[old_order[k] * kHistoryDoubles + h];
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
    const Vec3 ext = hi - lo;
    while ((ext.x() / cell + 1) * (ext.y() / cell + 1) * (ext.z() / cell + 1) > 8.0 * static_cast<double>(n) + 64) cell *= 1.3;
    const int nx = static_cast<int>(ext.x() / cell) + 1, ny = static_cast<int>(ext.y() / cell) + 1,
              nz = static_cast<int>(ext.z() / cell) + 1;
    const std::size_t ncell = static_cast<std::size_t>(nx) * ny * nz;
    std::vector<std::uint32_t> cell_of(n), start(ncell + 1, 0), items;
    auto cell_index = [&](std::size_t i, int& ix, int& iy, int& iz) {
      ix = std::min(nx - 1, static_cast<int>((p.x[i] - lo.x()) / cell));
      iy = std::min(ny - 1, static_cast<int>((p.y[i] - lo.y()) / cell));
      iz = std::min(nz - 1, static_cast<int>((p.z[i] - lo.z()) / cell));
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

    std::vector<std::uint32_t> mine;
    for (std::size_t i = 0; i < n; ++i) {
      list.first_start[i] = static_cast<std::uint32_t>(list.first.size());
      if (!p.active[i]) continue;
      int ix, iy, iz;
      cell_index(i, ix, iy, iz);
      mine.clear();
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int cx = ix + dx, cy = iy + dy, cz = iz + dz;
            if (cx < 0 || cy < 0 || cz < 0 || cx >= nx || cy >= ny || cz >= nz) continue;
            const std::size_t c = (static_cast<std::size_t>(cz) * ny + cy) * nx + cx;
            for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) {
              const std::uint32_t j = items[k];
              if (j <= i) continue;
              const double cut = p.radius_m[i] + p.radius_m[j] + skin_m;
              const double ddx = p.x[j] - p.x[i], ddy = p.y[j] - p.y[i], ddz = p.z[j] - p.z[i];
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
  for (std::size_t k = 0; k < np; ++k) {
    auto it = std::lower_bound(old_keys.begin(), old_keys.end(), list.key[k]);
    if (it != old_keys.end() && *it == list.key[k]) {
      const std::size_t o = static_cast<std::size_t>(it - old_keys.begin());
      for (int h = 0; h < kHistoryDoubles; ++h) list.history[k * kHistoryDoubles + h] = old_hist[o * kHistoryDoubles + h];
    }
  }
  for (std::size_t k = 0; k < np; ++k) ++list.second_start[list.second[k] + 1];
  for (std::size_t i = 1; i <= n; ++i) list.second_start[i] += list.second_start[i - 1];
  list.second_pairs.resize(np);
  std::vector<std::uint32_t> fill(list.second_start.begin(), list.second_start.end() - 1);
  for (std::size_t k = 0; k < np; ++k) list.second_pairs[fill[list.second[k]]++] = static_cast<std::uint32_t>(k);
  list.force.assign(np * 3, 0.0);
  list.torque_first.assign(np * 3, 0.0);
  list.torque_second.assign(np * 3, 0.0);
}

}  // namespace spread::dem
