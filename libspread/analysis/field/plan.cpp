// Headland rounds and tramlines (plan.hpp).
#include "libspread/analysis/field/plan.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "libspread/core/error.hpp"

namespace spread::field {
namespace {

[[noreturn]] void refuse_plan(const std::string& what) { throw Error(ErrorKind::kArgument, "plan", "plan: " + what); }

Point unit(Point v) { return (1.0 / length(v)) * v; }
Point left_normal(Point d) { return {-d.y_m, d.x_m}; }

void check_settings(const Boundary& boundary, const PlanSettings& s) {
  if (!(s.bout_width_m > 0.0 && s.bout_width_m <= 100.0)) {
    refuse_plan("bout_width_m must be in (0, 100] m, got " + std::to_string(s.bout_width_m));
  }
  if (s.headland_passes < 0 || s.headland_passes > 10) {
    refuse_plan("headland_passes must be 0 to 10, got " + std::to_string(s.headland_passes));
  }
  if (s.reference_edge < -1 || s.reference_edge >= static_cast<int>(boundary.ring.size())) {
    refuse_plan("reference_edge " + std::to_string(s.reference_edge) + " is not an edge of the boundary (0 to " +
           std::to_string(boundary.ring.size() - 1) + ", or −1 for the longest)");
  }
}

int longest_edge(const Ring& ring) {
  int best = 0;
  double best_length = -1.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const double l = length(ring[(i + 1) % ring.size()] - ring[i]);
    if (l > best_length) {
      best_length = l;
      best = static_cast<int>(i);
    }
  }
  return best;
}

// Headland rounds, outermost first, each driven counter-clockwise (the field on the driver's left, the
// boundary on the right: the right-hand vector of heading f is (f_y, −f_x)) and closed.
std::vector<Pass> headland_passes(const Boundary& boundary, const PlanSettings& s) {
  std::vector<Pass> passes;
  for (int k = 1; k <= s.headland_passes; ++k) {
    const double offset_m = (k - 0.5) * s.bout_width_m;
    Ring round = offset_inward(boundary.ring, offset_m);
    if (signed_area_m2(round) <= 0.0 || first_self_intersection(round).first >= 0) {
      std::ostringstream out;
      out << "headland pass " << k << " (" << offset_m << " m inside the boundary) folds over itself: part of the "
          << "field is narrower than " << 2.0 * offset_m << " m; plan fewer headland passes";
      refuse_plan(out.str());
    }
    round.push_back(round.front());
    Pass pass;
    pass.kind = PassKind::kHeadland;
    pass.path = std::move(round);
    pass.outermost = k == 1;
    passes.push_back(std::move(pass));
  }
  return passes;
}

// Where the line origin + s·d crosses the ring: the sorted parameters s (a vertex on the line counted
// once by the half-open rule on the normal coordinate).
std::vector<double> crossings(const Ring& ring, Point origin, Point d) {
  const Point n = left_normal(d);
  std::vector<double> s;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point a = ring[i], b = ring[(i + 1) % ring.size()];
    const double ta = dot(a - origin, n), tb = dot(b - origin, n);
    if ((ta > 0.0) == (tb > 0.0)) continue;
    const double f = ta / (ta - tb);
    s.push_back(dot(a + f * (b - a) - origin, d));
  }
  std::sort(s.begin(), s.end());
  return s;
}

std::vector<Pass> tramline_passes(const Boundary& boundary, const PlanSettings& s) {
  const Ring inner = s.headland_passes > 0 ? offset_inward(boundary.ring, s.headland_passes * s.bout_width_m)
                                           : boundary.ring;
  if (signed_area_m2(inner) <= 0.0 || first_self_intersection(inner).first >= 0) {
    std::ostringstream out;
    out << "the field inside " << s.headland_passes << " headland round(s) (" << s.headland_passes * s.bout_width_m
        << " m inside the boundary) folds over itself: part of the field is narrower than "
        << 2.0 * s.headland_passes * s.bout_width_m << " m; plan fewer headland passes";
    refuse_plan(out.str());
  }
  const int e = s.reference_edge >= 0 ? s.reference_edge : longest_edge(boundary.ring);
  const Point a = boundary.ring[static_cast<std::size_t>(e)];
  const Point d = unit(boundary.ring[(static_cast<std::size_t>(e) + 1) % boundary.ring.size()] - a);
  const Point n = left_normal(d);
  double reach_m = 0.0;  // the field's extent inward from the reference edge's line
  for (const Point& v : boundary.ring) reach_m = std::max(reach_m, dot(v - a, n));
  std::vector<Pass> passes;
  for (int j = 0;; ++j) {
    const double offset_m = (s.headland_passes + j + 0.5) * s.bout_width_m;
    if (offset_m >= reach_m) break;
    const Point origin = a + offset_m * n;
    const std::vector<double> cuts = crossings(inner, origin, d);
    for (std::size_t k = 0; k + 1 < cuts.size(); k += 2) {
      Pass pass;
      pass.kind = PassKind::kTramline;
      const Point from = origin + cuts[k] * d, to = origin + cuts[k + 1] * d;
      pass.path = j % 2 == 0 ? std::vector<Point>{from, to} : std::vector<Point>{to, from};
      passes.push_back(std::move(pass));
    }
  }
  return passes;
}

}  // namespace

Ring offset_inward(const Ring& ring, double offset_m) {
  const std::size_t n = ring.size();
  Ring out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point prev = ring[(i + n - 1) % n], here = ring[i], next = ring[(i + 1) % n];
    const Point d0 = unit(here - prev), d1 = unit(next - here);
    const Point p0 = prev + offset_m * left_normal(d0), p1 = here + offset_m * left_normal(d1);
    const double denom = cross(d0, d1);
    if (std::abs(denom) < 1e-9) {  // straight through: the moved vertex
      out[i] = here + offset_m * left_normal(d1);
      continue;
    }
    // p0 + t d0 = p1 + u d1  →  t = cross(p1 − p0, d1) / cross(d0, d1)
    out[i] = p0 + (cross(p1 - p0, d1) / denom) * d0;
  }
  return out;
}

std::vector<Pass> plan_field(const Boundary& boundary, const PlanSettings& settings) {
  check_settings(boundary, settings);
  std::vector<Pass> passes = headland_passes(boundary, settings);
  std::vector<Pass> tramlines = tramline_passes(boundary, settings);
  passes.insert(passes.end(), std::make_move_iterator(tramlines.begin()), std::make_move_iterator(tramlines.end()));
  return passes;
}

}  // namespace spread::field
