// The worked-ground record (coverage_map.hpp).
#include "libspread/analysis/field/coverage_map.hpp"

#include <algorithm>
#include <cmath>

namespace spread::field {

CoverageMap::CoverageMap(const RateGrid& grid, double self_overlap_m)
    : x0_m_(grid.x0_m), y0_m_(grid.y0_m), cell_m_(grid.cell_m), self_overlap_m_(self_overlap_m), nx_(grid.nx),
      ny_(grid.ny), pass_(grid.mass_kg.size(), -1), along_m_(grid.mass_kg.size(), 0.0f) {}

long CoverageMap::cell_of(Point at) const {
  const double gx = std::floor((at.x_m - x0_m_) / cell_m_), gy = std::floor((at.y_m - y0_m_) / cell_m_);
  if (!(gx >= 0.0 && gy >= 0.0 && gx < static_cast<double>(nx_) && gy < static_cast<double>(ny_))) return -1;
  return static_cast<long>(gy) * nx_ + static_cast<long>(gx);
}

void CoverageMap::mark(Point from, Point to, int pass, double along_m) {
  // Samples at most half a cell apart: every cell the segment crosses is met.
  const double span_m = length(to - from);
  const int samples = std::max(1, static_cast<int>(std::ceil(2.0 * span_m / cell_m_)));
  for (int k = 0; k <= samples; ++k) {
    const long cell = cell_of(from + (static_cast<double>(k) / samples) * (to - from));
    if (cell < 0) continue;
    const auto i = static_cast<std::size_t>(cell);
    // The first pass to work a cell keeps it: a later pass over it is the overlap being avoided.
    if (pass_[i] < 0) {
      pass_[i] = pass;
      along_m_[i] = static_cast<float>(along_m);
    }
  }
}

bool CoverageMap::worked(Point at, int pass, double along_m) const {
  const long cell = cell_of(at);
  if (cell < 0) return false;
  const auto i = static_cast<std::size_t>(cell);
  if (pass_[i] < 0) return false;
  return pass_[i] != pass || along_m - static_cast<double>(along_m_[i]) > self_overlap_m_;
}

}  // namespace spread::field
