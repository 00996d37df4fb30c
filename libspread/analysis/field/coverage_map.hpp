#pragma once
// The task controller's record of worked ground (ISO 11783-10 section control): which ground the machine's
// sections have already spread, on the field grid's cells. A section that is actually spreading marks its
// strip across the driving direction at the ground its granules reach (the pattern's mass centre behind the
// machine: the section offset a task controller is given for a spreader); section control then switches a
// section off where the ground ahead of its strip is marked.
//
// A pass does not switch itself off: a cell marked by the pass now driven counts as worked only once the
// machine has driven `self_overlap_m` beyond where it marked it (a headland round closing on its start).
#include <cstdint>
#include <vector>

#include "libspread/analysis/field/field_geometry.hpp"
#include "libspread/analysis/field/rate_grid.hpp"

namespace spread::field {

class CoverageMap {
 public:
  // Over the cells of `grid` (its origin, cell size and extent).
  CoverageMap(const RateGrid& grid, double self_overlap_m);

  // Marks the segment [from, to] (a section's strip across the driving direction) as worked by pass
  // `pass` at `along_m` metres driven along it. Points off the grid are ignored.
  void mark(Point from, Point to, int pass, double along_m);
  // Whether the cell under `at` is worked, seen from pass `pass` at `along_m` metres driven.
  bool worked(Point at, int pass, double along_m) const;

 private:
  long cell_of(Point at) const;  // -1: off the grid

  double x0_m_, y0_m_, cell_m_, self_overlap_m_;
  long nx_, ny_;
  std::vector<std::int32_t> pass_;  // -1: not worked
  std::vector<float> along_m_;
};

}  // namespace spread::field
