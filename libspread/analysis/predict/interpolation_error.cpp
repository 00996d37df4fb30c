#include "libspread/analysis/predict/interpolation_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>

#include "libspread/analysis/predict/mirror_fold.hpp"

namespace spread::predict {

namespace {

enum class RowPart { kLower, kUpper };

// The trays of the answer's pattern with every interpolating disc's landings taken from one row's part
// only, that part scaled to carry the disc's whole mass (a disc on a row keeps its landings).
void part_trays(const InterpolationErrorInput& in, RowPart part, const InterpolationErrorScratch& s) {
  std::fill(s.part_trays.begin(), s.part_trays.end(), 0.0);
  const int binned_discs = in.mirrored ? 1 : in.disc_count;
  for (int d = 0; d < binned_discs; ++d) {
    const DiscRowParts& disc = in.discs[d];
    std::size_t first = disc.lower_first, count = disc.lower_count;
    if (disc.interpolated() && part == RowPart::kUpper) {
      first = disc.upper_first;
      count = disc.upper_count;
    }
    const auto mass_of = [&in](std::size_t from, std::size_t n) {
      double sum = 0.0;
      for (std::size_t i = from; i < from + n; ++i) sum += in.weight[i];
      return sum;
    };
    const double disc_mass = mass_of(disc.lower_first, disc.lower_count) + mass_of(disc.upper_first, disc.upper_count);
    const double part_mass = mass_of(first, count);
    if (!(part_mass > 0.0)) continue;
    std::fill(s.disc_trays.begin(), s.disc_trays.end(), 0.0);
    metrics::accumulate_transverse_kernel(in.x_m.subspan(first, count), in.weight.subspan(first, count), in.trays,
                                          in.kernel_half_width_m, s.disc_trays, s.scratch);
    const double scale = disc_mass / part_mass;
    for (std::size_t k = 0; k < s.part_trays.size(); ++k) s.part_trays[k] += scale * s.disc_trays[k];
  }
  if (in.mirrored) fold_mirror(s.part_trays);
}

// The part's working width read as the answer's: the upper end of its band that overlaps the answer's
// headline band most (0 when none does: the part does not meet the target there).
double matching_width(const metrics::WorkingWidth& width, double lower_m, double upper_m) {
  double best_overlap = 0.0, best_upper = 0.0;
  for (int b = 0; b < width.stored_bands(); ++b) {
    const metrics::WidthBand& band = width.bands[b];
    const double overlap = std::min(band.upper_m, upper_m) - std::max(band.lower_m, lower_m);
    if (overlap > best_overlap) {
      best_overlap = overlap;
      best_upper = band.upper_m;
    }
  }
  return best_upper;
}

// The answer's figures read off a pattern's trays on the answer's layout.
InterpolatedFigures figures_of(const InterpolationErrorInput& in, std::span<const double> trays,
                               const InterpolationErrorScratch& s) {
  InterpolatedFigures f;
  const metrics::ThrowExtent extent = metrics::throw_extent(trays, in.trays, 0.99);
  f.throw_width_m = extent.right_m - extent.left_m;
  // Constructed in place (no temporary of over half a kilobyte on the stack, also unoptimised).
  // To-and-fro as the answer reads it (return_pass.cpp): with the flown return pass, or as racetrack.
  const std::span<const double> return_trays = in.return_trays.empty() ? trays : in.return_trays;
  ::new (static_cast<void*>(s.widths))
      metrics::WorkingWidths(metrics::working_widths(trays, return_trays, in.trays, in.cv_target, s.scratch));
  if (in.to_and_fro_as_racetrack) s.widths->to_and_fro = s.widths->racetrack;
  const metrics::WorkingWidth* widths[2] = {&s.widths->to_and_fro, &s.widths->racetrack};
  for (int o = 0; o < 2; ++o) {
    f.working_width_m[o] = matching_width(*widths[o], in.headline_lower_m[o], in.headline_upper_m[o]);
    const bool to_and_fro = o == 0 && !in.to_and_fro_as_racetrack;
    f.cv[o] = in.bout_trays <= 0 ? std::numeric_limits<double>::quiet_NaN()
              : to_and_fro       ? metrics::cv_at_trays(trays, return_trays, in.trays, in.bout_trays, s.scratch)
                                 : metrics::cv_at_trays(trays, in.trays, in.bout_trays, metrics::Overlap::kRacetrack, s.scratch);
  }
  return f;
}

InterpolatedFigures part_figures(const InterpolationErrorInput& in, RowPart part, const InterpolationErrorScratch& s) {
  part_trays(in, part, s);
  return figures_of(in, s.part_trays, s);
}

double spread_about(double answer, double lower, double upper, double t) {
  if (std::isnan(answer)) return answer;
  if (!std::isfinite(lower) || !std::isfinite(upper)) return std::numeric_limits<double>::infinity();
  return std::sqrt((1.0 - t) * (lower - answer) * (lower - answer) + t * (upper - answer) * (upper - answer));
}

}  // namespace

bool interpolates_by_cells(const InterpolationErrorInput& input) {
  for (int d = 0; d < input.disc_count; ++d) {
    if (input.discs[d].interpolated()) return true;
  }
  return false;
}

InterpolatedFigures interpolation_error(const InterpolationErrorInput& input, const InterpolatedFigures& answer,
                                        const InterpolationErrorScratch& scratch) {
  const InterpolatedFigures lower = part_figures(input, RowPart::kLower, scratch);
  const InterpolatedFigures upper = part_figures(input, RowPart::kUpper, scratch);
  const double t = input.upper_weight;
  InterpolatedFigures e;
  e.throw_width_m = spread_about(answer.throw_width_m, lower.throw_width_m, upper.throw_width_m, t);
  for (int o = 0; o < 2; ++o) {
    // No working width in the answer: no error to give it (its standard error is NaN too).
    e.working_width_m[o] = answer.working_width_m[o] > 0.0
                               ? spread_about(answer.working_width_m[o], lower.working_width_m[o],
                                              upper.working_width_m[o], t)
                               : std::numeric_limits<double>::quiet_NaN();
    e.cv[o] = spread_about(answer.cv[o], lower.cv[o], upper.cv[o], t);
  }
  return e;
}

}  // namespace spread::predict
