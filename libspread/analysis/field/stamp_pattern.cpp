// Product-kernel binning of landings into the stamp's cells (the kernel's CDF: metrics::epanechnikov_cdf).
#include "libspread/analysis/field/stamp_pattern.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::field {
namespace {

// The kernel's weight of each cell [k c, (k + 1) c) in [first, last] for a landing at `at_m`.
struct AxisWeights {
  long first = 0;
  std::vector<double> weight;
};
AxisWeights axis_weights(double at_m, double h_m, double cell_m) {
  AxisWeights out;
  if (!(h_m > 0.0)) {
    out.first = static_cast<long>(std::floor(at_m / cell_m));
    out.weight = {1.0};
    return out;
  }
  out.first = static_cast<long>(std::floor((at_m - h_m) / cell_m));
  const long last = static_cast<long>(std::floor((at_m + h_m) / cell_m));
  for (long k = out.first; k <= last; ++k) {
    const double lower = metrics::epanechnikov_cdf((static_cast<double>(k) * cell_m - at_m) / h_m);
    const double upper = metrics::epanechnikov_cdf((static_cast<double>(k + 1) * cell_m - at_m) / h_m);
    out.weight.push_back(upper - lower);
  }
  return out;
}

StampPattern bin(const predict::Prediction& p, std::size_t first, std::size_t end, double cell_m) {
  if (!(cell_m > 0.0) || !std::isfinite(cell_m)) throw std::invalid_argument("stamp_pattern: cell_m must be > 0");
  // Ordered by (row, column): the stamp's cell order, and so its sums, do not depend on hashing.
  std::map<std::pair<long, long>, double> cells;
  const double h_m = p.kernel_half_width_m;
  for (std::size_t i = first; i < end; ++i) {
    const double x = p.landing_x_m[i], y = p.landing_y_m[i], m = p.landing_mass_fraction[i];
    if (!std::isfinite(x) || !std::isfinite(y) || !(m > 0.0)) continue;
    const AxisWeights wx = axis_weights(x, h_m, cell_m), wy = axis_weights(y, h_m, cell_m);
    for (std::size_t j = 0; j < wy.weight.size(); ++j) {
      for (std::size_t k = 0; k < wx.weight.size(); ++k) {
        const double w = wx.weight[k] * wy.weight[j];
        if (w > 0.0) cells[{wy.first + static_cast<long>(j), wx.first + static_cast<long>(k)}] += m * w;
      }
    }
  }
  StampPattern out;
  out.cell_m = cell_m;
  for (const auto& [cell, fraction] : cells) {
    out.x_m.push_back((static_cast<double>(cell.second) + 0.5) * cell_m);
    out.y_m.push_back((static_cast<double>(cell.first) + 0.5) * cell_m);
    out.fraction.push_back(fraction);
    out.landed_fraction += fraction;
  }
  return out;
}

}  // namespace

StampPattern stamp_pattern(const predict::Prediction& prediction, double cell_m) {
  return bin(prediction, 0, prediction.landing_x_m.size(), cell_m);
}

StampPattern stamp_pattern_of_disc(const predict::Prediction& prediction, int disc, double cell_m) {
  const std::size_t split = prediction.left_landing_count;
  return disc == predict::kLeftDisc ? bin(prediction, 0, split, cell_m)
                                    : bin(prediction, split, prediction.landing_x_m.size(), cell_m);
}

double disc_share(const predict::Prediction& prediction, int disc) {
  const std::size_t split = prediction.left_landing_count;
  const std::size_t first = disc == predict::kLeftDisc ? 0 : split;
  const std::size_t end = disc == predict::kLeftDisc ? split : prediction.landing_mass_fraction.size();
  double share = 0.0;
  for (std::size_t i = first; i < end; ++i) share += prediction.landing_mass_fraction[i];
  return share;
}

StampPattern combine_discs(const StampPattern& field_side, double field_share, const StampPattern& edge_side,
                           double edge_share, double edge_flow_fraction) {
  StampPattern out;
  out.cell_m = field_side.cell_m;
  out.metered_fraction = field_share + edge_flow_fraction * edge_share;
  if (!(out.metered_fraction > 0.0)) return out;
  const auto add = [&](const StampPattern& from, double scale) {
    for (std::size_t i = 0; i < from.size(); ++i) {
      out.x_m.push_back(from.x_m[i]);
      out.y_m.push_back(from.y_m[i]);
      out.fraction.push_back(from.fraction[i] * scale);
      out.landed_fraction += from.fraction[i] * scale;
    }
  };
  add(field_side, 1.0 / out.metered_fraction);
  add(edge_side, edge_flow_fraction / out.metered_fraction);
  return out;
}

}  // namespace spread::field
