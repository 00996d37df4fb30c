// The headline stage of predict() (predictor.hpp; docs/metrics.md "Effective working width"): the widest
// band of bout widths whose lowest CV meets the target at 95 % confidence over the launch samples
// (CV + 1.96 SE <= target); a band the samples do not establish is reported but not taken. Bands whose gap
// the samples do not show above the target (its peak CV − 1.96 SE <= target) count as one: a band that
// splits near the target in one draw of the granules and not in another must not take the headline metres
// away. When none is established, the first band. Then the CVs reported and the views of the pattern.
#include <cmath>
#include <limits>
#include <span>

#include "libspread/analysis/predict/prediction_context.hpp"
#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

void Predictor::choose_headline(Context& c) const {
  Prediction& p = c.out;
  const PredictionRequest& request = c.request;
  PredictedBand* const band_out[2] = {p.bands_to_and_fro, p.bands_racetrack};
  const metrics::WorkingWidth* const overlap_widths[2] = {&c.w.widths_.to_and_fro, &c.w.widths_.racetrack};
  for (int o = 0; o < 2; ++o) {
    const int stored = overlap_widths[o]->stored_bands();
    bool group_established = false;
    for (int b = 0; b < stored; ++b) {
      PredictedBand& band = band_out[o][b];
      const metrics::WidthBand& in = *c.w.band_extras_[static_cast<std::size_t>(o * kMaxBands + b)].band;
      if (in.lowest_cv_trays == in.trays_below) band.lowest_cv_se = band.cv_se;
      band.established = request.standard_errors
                             ? band.lowest_cv + kConfidence95 * band.lowest_cv_se <= request.cv_target
                             : band.lowest_cv <= request.cv_target;
      band.joins_previous = request.standard_errors && std::isfinite(band.gap_peak_cv) &&
                            band.gap_peak_cv - kConfidence95 * band.gap_peak_cv_se <= request.cv_target;
      group_established = band.established || (band.joins_previous && group_established);
      if (group_established) c.headline[o] = b;
    }
    if (c.headline[o] < 0 && stored > 0) c.headline[o] = 0;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double* const widths_out[2] = {&p.working_width_to_and_fro_m, &p.working_width_racetrack_m};
  double* const widths_se_out[2] = {&p.working_width_to_and_fro_se_m, &p.working_width_racetrack_se_m};
  for (int o = 0; o < 2; ++o) {
    const PredictedBand* h = c.headline[o] >= 0 ? &band_out[o][c.headline[o]] : nullptr;
    *widths_out[o] = h != nullptr ? h->upper_m : 0.0;
    *widths_se_out[o] = h != nullptr ? h->upper_se_m : nan;
  }
  p.headline_band_to_and_fro = c.headline[0];
  p.headline_band_racetrack = c.headline[1];
  p.cv_crossings_to_and_fro = overlap_widths[0]->crossings;
  p.cv_crossings_racetrack = overlap_widths[1]->crossings;
  p.band_count_to_and_fro = overlap_widths[0]->band_count;
  p.band_count_racetrack = overlap_widths[1]->band_count;
  p.first_band_width_to_and_fro_m = overlap_widths[0]->first_band_upper_m();
  p.first_band_width_racetrack_m = overlap_widths[1]->first_band_upper_m();
  report_cvs(c);
}

void Predictor::report_cvs(Context& c) const {
  // The CVs: at the requested bout, or without one at the to-and-fro headline band's widest whole-tray
  // bout (the working width itself lies between two whole-tray widths, where no CV is defined). Then R̄ and
  // ξ of the left disc and the views of the trays and landings.
  Prediction& p = c.out;
  const std::size_t n = c.landed.left_landings, landings = c.landed.landings;
  if (c.request_bout_trays > 0) {
    p.bout_width_m = c.request_bout_trays * c.trays.tray_width_m;
    p.cv_to_and_fro = c.request_cv[0];
    p.cv_racetrack = c.request_cv[1];
    p.cv_to_and_fro_se = c.request_cv_se[0];
    p.cv_racetrack_se = c.request_cv_se[1];
  } else if (c.headline[0] >= 0) {
    const PredictedBand& h = p.bands_to_and_fro[c.headline[0]];
    const PredictorWorkspace::BandExtra& extra = c.w.band_extras_[static_cast<std::size_t>(c.headline[0])];
    p.bout_width_m = h.bout_width_m;
    p.cv_to_and_fro = h.cv;
    p.cv_to_and_fro_se = h.cv_se;
    p.cv_racetrack = extra.racetrack_cv;
    p.cv_racetrack_se = extra.racetrack_cv_se;
  } else {
    p.bout_width_m = 0.0;
    p.cv_to_and_fro = p.cv_racetrack = p.cv_to_and_fro_se = p.cv_racetrack_se = std::numeric_limits<double>::quiet_NaN();
  }
  p.mean_radius_m = c.w.radial_mean_m_;
  p.radial_width_m = c.w.radial_width_m_;
  p.tray_mass_fraction = std::span(c.w.tray_mass_).first(static_cast<std::size_t>(c.trays.tray_count));
  // The return pass as the field gets it: the outgoing pattern's own span in still air, the outgoing
  // pattern mirrored where it lands as the outgoing one (return_pass.cpp), the flown one otherwise.
  p.return_pass = c.return_pass;
  p.return_tray_mass_fraction = c.return_pass == ReturnPass::kOutgoing
                                    ? p.tray_mass_fraction
                                    : std::span<const double>(std::span(c.w.return_tray_mass_).first(p.tray_mass_fraction.size()));
  p.landing_x_m = std::span(c.w.landing_x_m_).first(landings);
  p.left_landing_count = n;
  p.landing_y_m = std::span(c.w.landing_y_m_).first(landings);
  p.landing_mass_fraction = std::span(c.w.landing_weight_).first(landings);
}

}  // namespace spread::predict
