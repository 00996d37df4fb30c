// The transverse stage of predict() (predictor.hpp): the landings' weights as fractions of the machine's
// discharged mass, the kernel each landing's mass is spread over, the tray layout fitted to the landings,
// and the transverse pattern in those trays (metrics::accumulate_transverse_kernel).
#include <algorithm>
#include <cmath>
#include <span>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/mirror_fold.hpp"
#include "libspread/analysis/predict/prediction_context.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/analysis/predict/sample_influence.hpp"

namespace spread::predict {

double kernel_half_width_for(double sd_x_m, std::size_t sample_count) {
  if (sample_count == 0 || !(sd_x_m > 0.0)) return 0.0;
  return kKernelScale * sd_x_m * std::pow(static_cast<double>(sample_count), -0.2);
}

namespace {

// The automatic kernel (kernel_half_width_for) from one disc's lateral spread; with two discs the root
// mean square of both, so that the choice is the same for the wind from the left and its mirror image
// from the right. Discs at their own settings: the samples per disc on average.
double automatic_kernel_m(std::span<const double> xs, std::span<const double> weights, std::size_t left_landings,
                          bool two_discs, bool per_disc) {
  const std::size_t n = left_landings;
  double sd_m = lateral_sd_m(xs.first(n), weights.first(n));
  if (two_discs) {
    const double right_sd_m = lateral_sd_m(xs.subspan(n), weights.subspan(n));
    sd_m = std::sqrt(0.5 * (sd_m * sd_m + right_sd_m * right_sd_m));
  }
  return kernel_half_width_for(sd_m, per_disc ? (xs.size() + 1) / 2 : n);
}

}  // namespace

void Predictor::bin_transverse(Context& c) const {
  PredictorWorkspace& w = c.w;
  const std::size_t n = c.landed.left_landings, landings = c.landed.landings;
  const std::span<const double> xs = std::span(w.landing_x_m_).first(landings);
  const std::span<double> weights = std::span(w.landing_weight_).first(landings);
  if (!c.per_disc) {
    // Weights as fractions of the machine's discharged mass: the tray contents then read directly as the
    // share of the application rate per tray. (Discs at their own settings carry half each already.)
    double total_kg = 0.0;
    for (double weight : weights) total_kg += weight;
    const double scale = total_kg > 0.0 ? 1.0 / total_kg : 0.0;
    for (double& weight : weights) weight *= scale;
  }
  double kernel_m = c.request.kernel_half_width_m;
  if (std::isnan(kernel_m)) kernel_m = automatic_kernel_m(xs, weights, n, c.two_discs, c.per_disc);
  // Trays fitted to the landings plus the kernel (symmetric about the centre line), capped at the widest
  // layout.
  double half_extent_m = c.request.tray_width_m;
  for (double x : xs) {
    if (std::isfinite(x)) half_extent_m = std::max(half_extent_m, std::abs(x) + kernel_m);
  }
  half_extent_m = std::min(half_extent_m, limits_.max_half_extent_m);
  metrics::TrayLayout trays = metrics::tray_layout_covering(half_extent_m, c.request.tray_width_m);
  // Always an even number of trays: the tray edges then sit at whole multiples of the tray width from the
  // centre line wherever the outermost landing falls, so the grid never shifts by half a tray between two
  // predictions whose landings reach a little further or less far (a shift moves every tray, every CV and
  // the throw width by a fraction of a tray at once).
  const int capacity = tray_capacity(c.request.tray_width_m);
  if (trays.tray_count % 2 != 0) ++trays.tray_count;
  if (trays.tray_count > capacity) trays.tray_count = capacity - capacity % 2;
  const std::span<double> tray_mass = std::span(w.tray_mass_).first(static_cast<std::size_t>(trays.tray_count));
  std::fill(tray_mass.begin(), tray_mass.end(), 0.0);
  // The right disc mirrored (x_right = −x_left exactly: both are differences of the same two numbers) on a
  // layout symmetric about the centre line: its kernel mass is the left disc's, tray k's going to tray
  // T − 1 − k, so only the left disc's landings are spread and the trays are then folded. (Not with
  // point masses: a landing on a tray edge belongs to the tray to its right on both sides, which is not
  // mirror symmetric.)
  c.mirrored = c.two_discs && !c.fly_right_disc && kernel_m > 0.0;
  double lost = 0.0;
  if (c.mirrored) {
    lost = 2.0 * metrics::accumulate_transverse_kernel(xs.first(n), weights.first(n), trays, kernel_m, tray_mass,
                                                       w.metrics_scratch_);
    fold_mirror(tray_mass);
  } else {
    lost = metrics::accumulate_transverse_kernel(xs, weights, trays, kernel_m, tray_mass, w.metrics_scratch_);
  }
  c.kernel_half_width_m = kernel_m;
  c.trays = trays;
  c.lost_mass_fraction = std::clamp(lost, 0.0, 1.0);
}

}  // namespace spread::predict
