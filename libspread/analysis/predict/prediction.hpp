#pragma once
// What a prediction answers (Prediction): the throw width, the working widths and their bands, the CVs,
// R̄ and ξ, each with its standard error, and views of the trays and landings it was read from.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/interpolation_error.hpp"
#include "libspread/analysis/predict/prediction_request.hpp"
#include "libspread/physics/flight/flight.hpp"

namespace spread::predict {


// The automatic kernel half-width (m) for N launch samples whose landings (one disc) have lateral
// standard deviation sd_x_m: h = kKernelScale · sd_x · N^(−1/5) (the rate of Silverman's rule; the
// constant is the accuracy–cost study's, docs/metrics.md "Predicted patterns").
inline constexpr double kKernelScale = 0.5;
double kernel_half_width_for(double sd_x_m, std::size_t sample_count);

// One band of bout widths whose CV meets the target (metrics::WidthBand), as predicted, with the
// standard errors over the launch samples.
struct PredictedBand {
  double lower_m = 0.0;             // narrowest bout width of the band
  double upper_m = 0.0;             // widest, interpolated between whole trays (the layout's edge if limited)
  double upper_se_m = 0.0;          // NaN when limited by the layout
  double bout_width_m = 0.0;        // the widest whole-tray bout inside the band
  double cv = 0.0;                  // CV there (fraction)
  double cv_se = 0.0;               // its standard error (fraction)
  double lowest_cv = 0.0;           // the band's lowest CV (fraction) and its bout width
  double lowest_cv_se = 0.0;
  double lowest_cv_bout_width_m = 0.0;
  bool limited_by_layout = false;   // CV stays within the target up to the widest layout
  // lowest_cv + kConfidence95 · lowest_cv_se <= target: the launch samples establish the band (the
  // headline rule takes the widest established band).
  bool established = false;
  // The gap before this band, between the previous band's upper end and this band's lower end: its
  // highest CV at a whole-tray bout and that CV's standard error (NaN for the first band, when the band
  // before is not stored, or without standard errors).
  double gap_peak_cv = std::numeric_limits<double>::quiet_NaN();
  double gap_peak_cv_se = std::numeric_limits<double>::quiet_NaN();
  // gap_peak_cv − kConfidence95 · gap_peak_cv_se <= target: the launch samples do not show the gap above
  // the target, so the headline rule takes this band and the one before as one (an established band
  // makes the bands joined to it established).
  bool joins_previous = false;
};
inline constexpr int kMaxBands = metrics::kMaxWidthBands;
// Two-sided 95 % normal quantile: the intervals the tools print and the headline rule's confidence.
inline constexpr double kConfidence95 = 1.96;

// How the to-and-fro figures were read (docs/metrics.md "To-and-fro in wind"). The return pass meets the
// wind from the other side; its pattern in its own machine frame is laid down mirrored.
enum class ReturnPass : std::uint8_t {
  kOutgoing,    // still air: the return pass is the outgoing pattern (each bout mirror-symmetric)
  kRacetrack,   // a lateral wind on discs that are (or on the way back become) mirror images: the return
                // pass lands where the outgoing one does, so to-and-fro overlaps as racetrack does
  kFlown,       // the return pass flown in its own wind and settings; CVs over two bouts
};

struct Prediction {
  double throw_width_m = 0.0;               // 99 % of the mass
  // The headline working width (docs/metrics.md "Effective working width"): the upper end of the widest
  // band of bout widths with CV <= target whose lowest CV meets the target at 95 % confidence, or that is
  // joined to such a band by gaps the samples do not show above the target (the first band when none
  // is), PredictedBand::established and joins_previous; 0 = no width meets the target.
  double working_width_to_and_fro_m = 0.0;
  double working_width_racetrack_m = 0.0;
  double bout_width_m = 0.0;                // where the CVs below were evaluated
  double cv_to_and_fro = 0.0;               // fraction; NaN when bout_width_m == 0
  double cv_racetrack = 0.0;                // fraction; NaN when bout_width_m == 0
  double mean_radius_m = 0.0;               // R̄ of the left disc about its centre, Eq. 51
  double radial_width_m = 0.0;              // ξ, Eq. 52
  double disc_height_m = 0.0;               // as used
  DiscSetting discs[2];                     // each disc's setting as used (kLeftDisc, kRightDisc)
  double lost_mass_fraction = 0.0;          // outside the trays or not landed
  metrics::TrayLayout trays;
  int flights = 0;                          // trajectories integrated (0: landings from the landing grid)
  // Monte Carlo uncertainty (docs/metrics.md "Uncertainty"): the standard errors of the estimates above
  // over the table's launch samples, by the delta method (the influence of each sample, linear in the
  // samples: no resampling). NaN where the estimate has no derivative (no width meets the target, or
  // the CV is infinite).
  double throw_width_se_m = 0.0;
  double working_width_to_and_fro_se_m = 0.0;
  double working_width_racetrack_se_m = 0.0;
  double cv_to_and_fro_se = 0.0;            // fraction
  double cv_racetrack_se = 0.0;             // fraction
  // Between DEM rows the standard errors above include the interpolation's own error
  // (interpolation_error.hpp), in quadrature; here that part alone (0 on a row, between rows that
  // interpolate sample by sample, and without standard errors).
  InterpolatedFigures interpolation_se;
  // Times CV(W) crosses the target between two trays and the layout width: more than 1 means more than
  // one band (a bout width between two bands does not meet the target; say so to the user).
  int cv_crossings_to_and_fro = 0;
  int cv_crossings_racetrack = 0;
  // Every band of bout widths within the target (the first kMaxBands − 1 and the widest are kept), each
  // with its CV and standard error at its widest whole-tray bout; headline_band_*: the index of the band
  // whose upper end is the working width above (−1: none). first_band_width_*_m: the narrowest band's
  // upper end (the first rise of CV(W) above the target).
  int band_count_to_and_fro = 0;
  int band_count_racetrack = 0;
  int headline_band_to_and_fro = -1;
  int headline_band_racetrack = -1;
  PredictedBand bands_to_and_fro[kMaxBands];
  PredictedBand bands_racetrack[kMaxBands];
  double first_band_width_to_and_fro_m = 0.0;
  double first_band_width_racetrack_m = 0.0;
  int stored_bands_to_and_fro() const { return band_count_to_and_fro < kMaxBands ? band_count_to_and_fro : kMaxBands; }
  int stored_bands_racetrack() const { return band_count_racetrack < kMaxBands ? band_count_racetrack : kMaxBands; }
  std::size_t sample_count = 0;             // independent launch samples behind the estimate
  flight::EffectSet effects = 0;            // the flight effects that ran
  double kernel_half_width_m = 0.0;         // as used
  // Views into the predictor's workspace, valid until the next predict():
  std::span<const double> tray_mass_fraction;  // per tray, of the machine's total discharged mass
  // The return pass's pattern in its own machine frame on the same trays (what to-and-fro lays down
  // mirrored on every other pass): tray_mass_fraction itself (the same span) in still air.
  std::span<const double> return_tray_mass_fraction;
  ReturnPass return_pass = ReturnPass::kOutgoing;
  // Landings of the whole machine in the machine frame (both discs; the left disc's first), with the
  // fraction of the total mass each stands for. Not-landed granules have x = y = NaN.
  std::span<const double> landing_x_m, landing_y_m, landing_mass_fraction;
  std::size_t left_landing_count = 0;  // the left disc's landings come first, the right disc's after them
};

}  // namespace spread::predict
