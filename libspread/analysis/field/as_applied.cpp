// A field run's stages (as_applied.hpp).
#include "libspread/analysis/field/as_applied.hpp"

#include <algorithm>
#include <cmath>

#include "libspread/core/error.hpp"

namespace spread::field {
namespace {

[[noreturn]] void refuse_run(const std::string& what) {
  throw Error(ErrorKind::kArgument, "field run", "field run: " + what);
}

void check(const std::vector<Pass>& passes, std::span<const StampPattern> patterns, const RunSettings& s) {
  if (!(s.target_rate_kg_ha > 0.0) || !std::isfinite(s.target_rate_kg_ha)) refuse_run("target_rate_kg_ha must be > 0");
  if (!(s.bout_width_m > 0.0) || !std::isfinite(s.bout_width_m)) refuse_run("bout_width_m must be > 0");
  if (!(s.step_m > 0.0) || !std::isfinite(s.step_m)) refuse_run("step_m must be > 0");
  if (patterns.empty()) refuse_run("no ground pattern to stamp");
  for (const StampPattern& p : patterns) {
    if (p.cell_m != patterns[0].cell_m) refuse_run("the ground patterns have different cell sizes");
  }
  for (std::size_t i = 0; i < passes.size(); ++i) {
    const int setting = passes[i].setting;
    if (setting < 0 || setting >= static_cast<int>(patterns.size())) {
      refuse_run("pass " + std::to_string(i) + " runs at setting " + std::to_string(setting) + ", of which there is no pattern");
    }
  }
}

// The grid: the boundary and every pass, plus the farthest any pattern throws from the machine.
RateGrid fit_grid(const Boundary& boundary, const std::vector<Pass>& passes, std::span<const StampPattern> patterns) {
  double reach_m = 0.0;
  for (const StampPattern& pattern : patterns) reach_m = std::max(reach_m, pattern_reach_m(pattern));
  return grid_for(boundary, passes, reach_m, patterns[0].cell_m);
}

}  // namespace

double pattern_reach_m(const StampPattern& pattern) {
  double reach_m = 0.0;
  for (std::size_t i = 0; i < pattern.size(); ++i) reach_m = std::max(reach_m, std::hypot(pattern.x_m[i], pattern.y_m[i]));
  return reach_m;
}

RateGrid grid_for(const Boundary& boundary, const std::vector<Pass>& passes, double reach_m, double cell_m) {
  double min_x = boundary.min_x_m, max_x = boundary.max_x_m, min_y = boundary.min_y_m, max_y = boundary.max_y_m;
  for (const Pass& pass : passes) {
    for (const Point& p : pass.path) {
      min_x = std::min(min_x, p.x_m);
      max_x = std::max(max_x, p.x_m);
      min_y = std::min(min_y, p.y_m);
      max_y = std::max(max_y, p.y_m);
    }
  }
  return grid_covering(min_x, min_y, max_x, max_y, reach_m + 2.0 * cell_m, cell_m);
}

void cut_into_steps(const Pass& pass, double step_m, std::vector<Step>& steps) {
  for (std::size_t k = 1; k < pass.path.size(); ++k) {
    const Point a = pass.path[k - 1], b = pass.path[k];
    const double segment_m = length(b - a);
    if (!(segment_m > 0.0)) continue;
    const Point forward = (1.0 / segment_m) * (b - a);
    const auto pieces = static_cast<std::size_t>(std::ceil(segment_m / step_m - 1e-9));
    const double piece_m = segment_m / static_cast<double>(pieces);
    for (std::size_t i = 0; i < pieces; ++i) {
      const Point mid = a + ((static_cast<double>(i) + 0.5) * piece_m) * forward;
      steps.push_back({mid.x_m, mid.y_m, forward.x_m, forward.y_m, piece_m});
    }
  }
}

AsApplied spread_passes(const Boundary& boundary, const std::vector<Pass>& passes,
                        std::span<const StampPattern> patterns, const RunSettings& settings) {
  check(passes, patterns, settings);
  AsApplied out;
  out.grid = fit_grid(boundary, passes, patterns);
  // kg per metre travelled at the full flow: rate (kg/m²) times the bout width.
  const double kg_per_m = settings.target_rate_kg_ha / 1e4 * settings.bout_width_m;
  std::vector<std::vector<Step>> steps(passes.size());
  std::size_t total = 0;
  for (std::size_t i = 0; i < passes.size(); ++i) {
    cut_into_steps(passes[i], settings.step_m, steps[i]);
    total += steps[i].size();
  }
  std::size_t done = 0;
  for (std::size_t i = 0; i < passes.size(); ++i) {
    const StampPattern& pattern = patterns[static_cast<std::size_t>(passes[i].setting)];
    for (Step step : steps[i]) {
      out.spread_length_m += step.mass_kg;
      step.mass_kg *= kg_per_m * passes[i].flow_fraction * pattern.metered_fraction;
      out.metered_kg += step.mass_kg;
      out.not_landed_kg += step.mass_kg * std::max(0.0, 1.0 - pattern.landed_fraction);  // rounding: Σ may pass 1
      stamp(out.grid, pattern, step);
      if (++done % kProgressSteps == 0 && settings.progress) settings.progress(done, total);
    }
  }
  out.steps = total;
  if (settings.progress) settings.progress(total, total);
  return out;
}

}  // namespace spread::field
