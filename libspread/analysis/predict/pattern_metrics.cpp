// The metrics stage of predict() (predictor.hpp): from the transverse pattern, the throw width, both
// working widths with every band of bout widths within the target (metrics::working_widths, O(T log T)),
// the CVs at the requested bout, and the standard errors these need, queued for the uncertainty stage.
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <span>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/prediction_context.hpp"
#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

void Predictor::measure_pattern(Context& c) const {
  PredictorWorkspace& w = c.w;
  const std::span<const double> tray_mass = std::span(w.tray_mass_).first(static_cast<std::size_t>(c.trays.tray_count));
  // Written into `out` in place (every request check is behind us): a Prediction with its bands is over
  // a kilobyte, and the C API's stack budget has no room for a second one.
  Prediction& p = c.out;
  std::construct_at(&p);  // reset in place: no temporary Prediction on the stack, also unoptimised
  p.trays = c.trays;
  p.flights = c.landed.flights + c.return_flights;
  p.disc_height_m = c.height_m;
  p.lost_mass_fraction = c.lost_mass_fraction;
  p.sample_count = c.landed.samples;
  p.discs[kLeftDisc] = c.settings[kLeftDisc];
  p.discs[kRightDisc] = c.two_discs ? c.settings[kRightDisc]
                                    : DiscSetting{std::numeric_limits<double>::quiet_NaN(),
                                                  std::numeric_limits<double>::quiet_NaN()};
  p.effects = c.effects;
  p.kernel_half_width_m = c.kernel_half_width_m;
  c.extent = metrics::throw_extent(tray_mass, c.trays, 0.99);
  p.throw_width_m = c.extent.right_m - c.extent.left_m;
  // Both working widths in O(T log T) (metrics::working_widths): the whole-tray scan is O(T²), 0.13 s at
  // 4,000 trays of 5 cm. In the workspace, as the bookkeeping of the standard errors: the bands make them
  // hundreds of bytes, and the C API's stack budget holds in an unoptimised build too.
  // To-and-fro with the return pass where it is flown (return_pass.cpp), as racetrack where it lands as
  // the outgoing pass does.
  const std::span<double> scratch(w.metrics_scratch_);
  if (c.return_pass == ReturnPass::kFlown) {
    ::new (static_cast<void*>(&w.widths_)) metrics::WorkingWidths(
        metrics::working_widths(tray_mass, c.return_trays, c.trays, c.request.cv_target, scratch));
  } else {
    ::new (static_cast<void*>(&w.widths_))
        metrics::WorkingWidths(metrics::working_widths(tray_mass, c.trays, c.request.cv_target, scratch));
    if (c.return_pass == ReturnPass::kRacetrack) w.widths_.to_and_fro = w.widths_.racetrack;
  }
  // The standard errors to compute, in this order: the CVs at the requested bout, each band's, the throw
  // width's (all share passes over the landings: uncertainty.cpp).
  c.se_task_count = 0;
  request_bout_cvs(c);
  copy_bands(c);
  p.throw_width_se_m = std::numeric_limits<double>::quiet_NaN();
  if (p.throw_width_m > 0.0) {
    w.se_tasks_[c.se_task_count++] = {&p.throw_width_se_m, metrics::Overlap::kToAndFro, 0, nullptr, true};
  }
}

double Predictor::bout_cv(const Context& c, metrics::Overlap overlap, int bout_trays) const {
  const std::span<const double> tray_mass = std::span(c.w.tray_mass_).first(static_cast<std::size_t>(c.trays.tray_count));
  const std::span<double> scratch(c.w.metrics_scratch_);
  // To-and-fro with the return pass: the outgoing pattern's own span (the one-pattern CV, bit for bit)
  // unless the return pass was flown.
  return overlap == metrics::Overlap::kToAndFro ? metrics::cv_at_trays(tray_mass, c.return_trays, c.trays, bout_trays, scratch)
                                                : metrics::cv_at_trays(tray_mass, c.trays, bout_trays, overlap, scratch);
}

void Predictor::request_bout_cvs(Context& c) const {
  c.request_bout_trays = c.request.bout_width_m > 0.0 ? metrics::bout_tray_count(c.trays, c.request.bout_width_m) : 0;
  if (c.request_bout_trays == 0) return;
  for (int o = 0; o < 2; ++o) {
    c.request_cv[o] = bout_cv(c, c.overlap(o), c.request_bout_trays);
    if (std::isfinite(c.request_cv[o])) {
      c.w.se_tasks_[c.se_task_count++] = {&c.request_cv_se[o], c.overlap(o), c.request_bout_trays, nullptr};
    }
  }
}

void Predictor::copy_bands(Context& c) const {
  // The bands (metrics::WorkingWidth) with the standard errors the headline rule needs
  // (docs/metrics.md "Effective working width"): per band the CV at its widest whole-tray bout, its
  // lowest CV and its upper end; per to-and-fro band also the racetrack CV at that bout (the CVs a
  // request without a bout width reports are at the headline band's widest bout), kept beside its
  // PredictedBand in the workspace (BandExtra).
  PredictorWorkspace& w = c.w;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double tray_width_m = c.trays.tray_width_m;
  w.band_extras_.fill(PredictorWorkspace::BandExtra{});
  PredictedBand* const band_out[2] = {c.out.bands_to_and_fro, c.out.bands_racetrack};
  const metrics::WorkingWidth* const overlap_widths[2] = {&w.widths_.to_and_fro, &w.widths_.racetrack};
  for (int o = 0; o < 2; ++o) {
    const metrics::WorkingWidth& ww = *overlap_widths[o];
    for (int b = 0; b < ww.stored_bands(); ++b) {
      const metrics::WidthBand& in = ww.bands[b];
      PredictorWorkspace::BandExtra& extra = w.band_extras_[static_cast<std::size_t>(o * kMaxBands + b)];
      PredictedBand& band = band_out[o][b];
      extra.band = &in;
      band.lower_m = in.lower_m;
      band.upper_m = in.upper_m;
      band.upper_se_m = nan;
      band.bout_width_m = in.trays_below * tray_width_m;
      band.cv = in.cv_below;
      band.cv_se = nan;
      band.lowest_cv = in.lowest_cv;
      band.lowest_cv_se = nan;
      band.lowest_cv_bout_width_m = in.lowest_cv_trays * tray_width_m;
      band.limited_by_layout = in.limited_by_layout;
      w.se_tasks_[c.se_task_count++] = {&band.cv_se, c.overlap(o), in.trays_below, nullptr};
      if (in.lowest_cv_trays != in.trays_below) {
        w.se_tasks_[c.se_task_count++] = {&band.lowest_cv_se, c.overlap(o), in.lowest_cv_trays, nullptr};
      }
      if (!in.limited_by_layout && std::isfinite(in.cv_above) && in.cv_above > in.cv_below) {
        w.se_tasks_[c.se_task_count++] = {&band.upper_se_m, c.overlap(o), in.trays_below, &in};
      }
      queue_gap_peak(c, o, b);
      if (o == 0 && c.request_bout_trays == 0) {
        const std::span<const double> tray_mass = std::span(w.tray_mass_).first(static_cast<std::size_t>(c.trays.tray_count));
        extra.racetrack_cv = metrics::cv_at_trays(tray_mass, c.trays, in.trays_below, metrics::Overlap::kRacetrack,
                                                  std::span(w.metrics_scratch_));
        if (std::isfinite(extra.racetrack_cv)) {
          w.se_tasks_[c.se_task_count++] = {&extra.racetrack_cv_se, metrics::Overlap::kRacetrack, in.trays_below, nullptr};
        }
      }
    }
  }
}

void Predictor::queue_gap_peak(Context& c, int o, int b) const {
  // The gap before band b (when the band before is its neighbour: the last stored band follows the one
  // before it only when every band is stored): its highest CV over the whole-tray bouts between. Only
  // with standard errors: without them no gap can join two bands (a search's predictions skip it).
  const metrics::WorkingWidth& ww = o == 0 ? c.w.widths_.to_and_fro : c.w.widths_.racetrack;
  PredictedBand& band = (o == 0 ? c.out.bands_to_and_fro : c.out.bands_racetrack)[b];
  band.gap_peak_cv = std::numeric_limits<double>::quiet_NaN();
  band.gap_peak_cv_se = std::numeric_limits<double>::quiet_NaN();
  if (!c.request.standard_errors || b == 0 || (b >= kMaxBands - 1 && ww.band_count != ww.stored_bands())) return;
  const int first = ww.bands[b - 1].trays_below + 1;
  const int last = static_cast<int>(std::ceil(ww.bands[b].lower_m / c.trays.tray_width_m - 1e-9)) - 1;
  int peak_trays = first;
  double peak = -std::numeric_limits<double>::infinity();
  for (int gap_trays = first; gap_trays <= last; ++gap_trays) {
    const double cv = bout_cv(c, c.overlap(o), gap_trays);
    if (!(cv <= peak)) {
      peak = cv;
      peak_trays = gap_trays;
    }
  }
  if (last < first) return;
  band.gap_peak_cv = peak;
  if (std::isfinite(peak)) c.w.se_tasks_[c.se_task_count++] = {&band.gap_peak_cv_se, c.overlap(o), peak_trays, nullptr};
}

}  // namespace spread::predict
