// The uncertainty stages of predict() (predictor.hpp). sample_standard_errors: the standard errors the
// metrics stage queued, over the table's launch samples by the delta method (the influence of each sample,
// linear in the samples: no resampling; docs/metrics.md "Uncertainty"). add_interpolation_error: between
// DEM rows, the interpolation's own error (interpolation_error.hpp), in quadrature.
#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/interpolation_error.hpp"
#include "libspread/analysis/predict/mirror_fold.hpp"
#include "libspread/analysis/predict/prediction_context.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/analysis/predict/sample_influence.hpp"

namespace spread::predict {

namespace {

// What the gradients of the queued estimates are made from, and the buffers they are made in.
struct GradientInput {
  std::span<const double> tray_mass;
  std::span<const double> return_trays;  // the flown return pass (ReturnPass::kFlown); empty otherwise
  const metrics::TrayLayout& trays;
  const metrics::ThrowExtent& extent;
  double cv_target = 0.0;
  std::span<double> scratch, return_gradient, cv_scratch;
};

// ∂CV/∂(outgoing tray) at `bout_trays` trays. To-and-fro with a flown return pass the CV depends on both
// patterns, and each launch sample lands in both: its return landing is taken as its outgoing one
// mirrored (x → −x; exact for mirror-image discs in a lateral wind, to first order in the difference
// otherwise), so the return pattern's gradient joins the outgoing one folded: g_k + g'_{T−1−k}.
void cv_gradient_of(const GradientInput& in, metrics::Overlap overlap, int bout_trays, std::span<double> grad) {
  if (overlap == metrics::Overlap::kRacetrack || in.return_trays.empty()) {
    metrics::cv_gradient(in.tray_mass, in.trays, bout_trays, overlap, grad, in.cv_scratch);
    return;
  }
  metrics::cv_gradient(in.tray_mass, in.return_trays, in.trays, bout_trays, grad, in.return_gradient, in.cv_scratch);
  const std::size_t t = grad.size();
  for (std::size_t k = 0; k < t; ++k) grad[k] += in.return_gradient[t - 1 - k];
}

// The gradient over trays of one queued estimate: the CV at `trays` trays, or (width_band set) that
// band's interpolated upper end W* = (n + (t − c_n)/(c_{n+1} − c_n))·w, whose gradient combines the
// gradients of the two CVs around the crossing, or (throw_width) the throw width. False: the estimate has
// no derivative (no density at a quantile).
bool estimate_gradient(metrics::Overlap overlap, int trays_at, const metrics::WidthBand* width_band, bool throw_width,
                       const GradientInput& in, std::span<double> grad) {
  if (throw_width) return throw_width_gradient(in.tray_mass, in.trays, in.extent, 0.99, grad);
  if (width_band == nullptr) {
    cv_gradient_of(in, overlap, trays_at, grad);
    return true;
  }
  const metrics::WidthBand& band = *width_band;
  const double span = band.cv_above - band.cv_below;
  const double d_below = -in.trays.tray_width_m * (band.cv_above - in.cv_target) / (span * span);
  const double d_above = -in.trays.tray_width_m * (in.cv_target - band.cv_below) / (span * span);
  cv_gradient_of(in, overlap, band.trays_below, grad);
  cv_gradient_of(in, overlap, band.trays_below + 1, in.scratch);
  for (std::size_t k = 0; k < grad.size(); ++k) grad[k] = d_below * grad[k] + d_above * in.scratch[k];
  return true;
}

}  // namespace

void Predictor::sample_standard_errors(Context& c) const {
  PredictorWorkspace& w = c.w;
  const std::size_t n = c.landed.left_landings, tray_count = static_cast<std::size_t>(c.trays.tray_count);
  const std::span<const double> xs = std::span(w.landing_x_m_).first(c.landed.landings);
  const std::span<const double> weights = std::span(w.landing_weight_).first(c.landed.landings);
  const std::span<const double> tray_mass = std::span(w.tray_mass_).first(tray_count);
  // With the right disc mirrored a sample's two landings x and −x contribute Σ_k g_k K_k(x) + Σ_k g_k
  // K_k(−x) = Σ_k (g_k + g_{T−1−k}) K_k(x): the folded gradient at the left landing alone, half the pass.
  // Each gradient is made in the workspace's one gradient buffer and handed to the pass, which keeps what
  // it needs of it (its prefix sums) in the metrics' scratch — all but the tail that cv_gradient uses,
  // which is free at those moments (the binning and the working widths are done).
  const std::span<double> metrics_scratch(w.metrics_scratch_);
  const std::span<double> cv_scratch = metrics_scratch.last(w.cv_scratch_size_);
  const std::span<double> pass_scratch = metrics_scratch.first(metrics_scratch.size() - w.cv_scratch_size_);
  const SampleInfluence influence{xs, weights, c.landed.samples, c.two_discs ? 2u : 1u, c.trays, c.kernel_half_width_m,
                                  std::span<const SampleBlock>(w.sample_blocks_.data(), w.sample_block_count_),
                                  pass_scratch};
  const SampleInfluence left_influence{xs.first(n), weights.first(n), n, 1u, c.trays, c.kernel_half_width_m, {},
                                       pass_scratch};
  const SampleInfluence& pass_influence = c.mirrored ? left_influence : influence;
  const std::span<double> grad = std::span(w.gradients_).first(tray_count);
  const bool flown_return = c.return_pass == ReturnPass::kFlown;
  const GradientInput gradient_input{tray_mass,
                                     flown_return ? c.return_trays : std::span<const double>{},
                                     c.trays,
                                     c.extent,
                                     c.request.cv_target,
                                     std::span(w.gradient_scratch_).first(tray_count),
                                     std::span(w.return_gradient_).first(flown_return ? tray_count : 0),
                                     cv_scratch};
  // Without standard errors (a search comparing settings) the passes are skipped: about half the cost.
  const std::size_t task_count = c.request.standard_errors ? c.se_task_count : 0;
  const std::size_t per_pass = InfluencePass::capacity(pass_influence);
  if (task_count > 0 && per_pass == 0) {
    throw std::logic_error("Predictor: the workspace's scratch holds no gradient of " + std::to_string(tray_count) +
                           " trays");
  }
  for (std::size_t first = 0; first < task_count; first += per_pass) {
    const std::size_t count = std::min(task_count - first, per_pass);
    InfluencePass pass(pass_influence, count);
    for (std::size_t g = 0; g < count; ++g) {
      const PredictorWorkspace::SeTask& task = w.se_tasks_[first + g];
      if (!estimate_gradient(task.overlap, task.trays, task.width_band, task.throw_width, gradient_input, grad)) {
        pass.set_gradient(g, {});  // no density at a quantile: NaN
        continue;
      }
      if (c.mirrored) fold_mirror(grad);
      pass.set_gradient(g, grad);
    }
    double pass_se[SampleInfluence::kMaxGradients];
    pass.standard_errors(std::span(pass_se, count));
    for (std::size_t g = 0; g < count; ++g) *w.se_tasks_[first + g].out = pass_se[g];
  }
}

void Predictor::add_interpolation_error(Context& c) const {
  PredictorWorkspace& w = c.w;
  Prediction& p = c.out;
  InterpolationErrorInput in;
  in.x_m = std::span(w.landing_x_m_).first(c.landed.landings);
  in.weight = std::span(w.landing_weight_).first(c.landed.landings);
  in.discs[kLeftDisc] = c.landed.row_parts[kLeftDisc];
  in.discs[kRightDisc] = c.landed.row_parts[kRightDisc];
  in.disc_count = c.two_discs ? 2 : 1;
  if (!interpolates_by_cells(in)) return;
  in.mirrored = c.mirrored;
  in.trays = p.trays;
  in.kernel_half_width_m = p.kernel_half_width_m;
  in.upper_weight = c.landed.upper_weight;
  in.cv_target = c.request.cv_target;
  in.return_trays = c.return_pass == ReturnPass::kFlown ? c.return_trays : std::span<const double>{};
  in.to_and_fro_as_racetrack = c.return_pass == ReturnPass::kRacetrack;
  in.bout_trays = p.bout_width_m > 0.0 ? static_cast<int>(std::lround(p.bout_width_m / p.trays.tray_width_m)) : 0;
  const PredictedBand* const bands[2] = {p.bands_to_and_fro, p.bands_racetrack};
  for (int o = 0; o < 2; ++o) {
    if (c.headline[o] < 0) continue;
    in.headline_lower_m[o] = bands[o][c.headline[o]].lower_m;
    in.headline_upper_m[o] = bands[o][c.headline[o]].upper_m;
  }
  InterpolatedFigures answer;
  answer.throw_width_m = p.throw_width_m;
  answer.working_width_m[0] = p.working_width_to_and_fro_m;
  answer.working_width_m[1] = p.working_width_racetrack_m;
  answer.cv[0] = p.cv_to_and_fro;
  answer.cv[1] = p.cv_racetrack;
  // The standard errors' buffers are free by now (their passes are done, the bands copied out).
  const std::size_t tray_count = static_cast<std::size_t>(p.trays.tray_count);
  const InterpolationErrorScratch scratch{std::span(w.gradients_).first(tray_count),
                                          std::span(w.gradient_scratch_).first(tray_count), w.metrics_scratch_,
                                          &w.widths_};
  const InterpolatedFigures e = interpolation_error(in, answer, scratch);
  p.interpolation_se = e;
  const auto combine = [](double& se, double error) {
    if (!std::isnan(error)) se = std::hypot(se, error);
  };
  combine(p.throw_width_se_m, e.throw_width_m);
  combine(p.working_width_to_and_fro_se_m, e.working_width_m[0]);
  combine(p.working_width_racetrack_se_m, e.working_width_m[1]);
  combine(p.cv_to_and_fro_se, e.cv[0]);
  combine(p.cv_racetrack_se, e.cv[1]);
}

}  // namespace spread::predict
