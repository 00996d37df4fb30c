#include "libspread/analysis/predict/launch_quantile_cells.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace spread::predict {

QuantileCellCounts quantile_cells_for(std::size_t smallest_row_count) {
  // 64 cells of ≥ 32 samples need 2048 samples; below, halve the primary groups first (the throw width
  // lives in the primary key's tails, so it keeps the most resolution), then the secondary cells.
  // Halve the primary groups first (while there are more of them than secondary cells), then both.
  QuantileCellCounts counts{16, 4};
  while (counts.cells() > 1 && static_cast<std::size_t>(counts.cells()) * 32 > smallest_row_count) {
    if (counts.primary > counts.secondary) {
      counts.primary /= 2;
    } else {
      counts.secondary /= 2;
    }
  }
  return counts;
}

namespace {

// Cuts order[begin, end) (sorted) into `parts` runs of ~equal mass; calls cut(r, part) for every rank.
template <typename Cut>
void cut_by_mass(std::span<const std::uint32_t> order, std::span<const double> mass_kg, int parts, Cut cut) {
  double total_kg = 0.0;
  for (std::uint32_t i : order) total_kg += mass_kg[i];
  double before_kg = 0.0;
  for (std::size_t r = 0; r < order.size(); ++r) {
    const double m = mass_kg[order[r]];
    const double midpoint = (before_kg + 0.5 * m) / total_kg;
    cut(r, std::min(parts - 1, static_cast<int>(midpoint * parts)));
    before_kg += m;
  }
}

}  // namespace

void assign_quantile_cells(std::span<const double> primary_key, std::span<const double> secondary_key,
                           std::span<const double> mass_kg, QuantileCellCounts counts,
                           std::span<std::uint32_t> order, std::span<CellIndex> cell_of_sample) {
  const std::size_t n = mass_kg.size();
  if (n == 0) throw std::invalid_argument("assign_quantile_cells: empty row");
  if (primary_key.size() != n || secondary_key.size() != n || order.size() != n || cell_of_sample.size() != n) {
    throw std::invalid_argument("assign_quantile_cells: keys, masses, scratch and cells differ in size");
  }
  if (n > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("assign_quantile_cells: more than 2^32 - 1 samples in one row");
  }
  if (counts.primary < 1 || counts.secondary < 1 || counts.primary > 256 || counts.cells() > 256) {
    throw std::invalid_argument("assign_quantile_cells: cell counts must be >= 1 and at most 256 cells (CellIndex)");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(primary_key[i]) || !std::isfinite(secondary_key[i])) {
      throw std::invalid_argument("assign_quantile_cells: key of sample " + std::to_string(i) + " is not finite");
    }
    if (!(mass_kg[i] > 0.0) || !std::isfinite(mass_kg[i])) {
      throw std::invalid_argument("assign_quantile_cells: mass of sample " + std::to_string(i) +
                                  " is not finite and > 0");
    }
    order[i] = static_cast<std::uint32_t>(i);
  }
  // Index breaks ties: deterministic, and std::sort does not allocate.
  const auto by = [](std::span<const double> key) {
    return [key](std::uint32_t a, std::uint32_t b) { return key[a] != key[b] ? key[a] < key[b] : a < b; };
  };
  std::sort(order.begin(), order.end(), by(primary_key));
  // Groups along the primary key are contiguous in that order; find each and cut it along the secondary.
  std::size_t group_begin = 0;
  int group = 0;
  auto finish_group = [&](std::size_t end) {
    const std::span<std::uint32_t> members = order.subspan(group_begin, end - group_begin);
    std::sort(members.begin(), members.end(), by(secondary_key));
    cut_by_mass(members, mass_kg, counts.secondary, [&](std::size_t r, int cell) {
      cell_of_sample[members[r]] = static_cast<CellIndex>(group * counts.secondary + cell);
    });
  };
  cut_by_mass(order, mass_kg, counts.primary, [&](std::size_t r, int g) {
    if (g != group) {
      finish_group(r);
      group_begin = r;
      group = g;
    }
  });
  finish_group(n);
}

void quantile_cell_means(std::span<const tables::LaunchSample> samples, std::span<const CellIndex> cell_of_sample,
                         std::span<tables::LaunchSample> cell_mean) {
  if (cell_of_sample.size() != samples.size()) {
    throw std::invalid_argument("quantile_cell_means: cell_of_sample differs in size from the row");
  }
  // Sums in double (a row holds thousands of float samples), then one division per cell. One pass per
  // cell: O(cells · n), once per row at table load.
  constexpr std::size_t kFields = 9;  // x y z, vx vy vz, wx wy wz: the kinematic fields
  for (auto& mean : cell_mean) mean = tables::LaunchSample{};
  auto fields = [](const tables::LaunchSample& s, std::size_t k) -> float {
    const float all[kFields] = {s.x_m, s.y_m, s.z_m, s.vx_norm, s.vy_norm, s.vz_norm, s.wx_norm, s.wy_norm, s.wz_norm};
    return all[k];
  };
  for (std::size_t c = 0; c < cell_mean.size(); ++c) {
    double sum[kFields] = {};
    double mass_kg = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (cell_of_sample[i] != c) continue;
      const double m = samples[i].mass_kg;
      mass_kg += m;
      for (std::size_t k = 0; k < kFields; ++k) sum[k] += m * static_cast<double>(fields(samples[i], k));
    }
    if (mass_kg == 0.0) continue;
    tables::LaunchSample& mean = cell_mean[c];
    float* out[kFields] = {&mean.x_m, &mean.y_m, &mean.z_m, &mean.vx_norm, &mean.vy_norm, &mean.vz_norm,
                           &mean.wx_norm, &mean.wy_norm, &mean.wz_norm};
    for (std::size_t k = 0; k < kFields; ++k) *out[k] = static_cast<float>(sum[k] / mass_kg);
    mean.mass_kg = static_cast<float>(mass_kg);
  }
}

}  // namespace spread::predict
