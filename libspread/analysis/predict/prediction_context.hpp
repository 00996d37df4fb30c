#pragma once
// The context predict()'s stages share (Predictor::Context; the stages are listed in predictor.hpp): the
// request and the answer being written, the workspace, and what each stage leaves for the ones after it.
// Every field is named and grouped by the stage that writes it; a stage reads only the groups above its
// own. Lives on predict()'s stack: a few hundred bytes, the bulky parts stay in the workspace.
#include <cstddef>
#include <limits>
#include <span>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/physics/flight/flight.hpp"

namespace spread::predict {

// The two overlaps every width and CV is read for, in the order the Prediction's pairs keep them.
inline constexpr metrics::Overlap kOverlaps[2] = {metrics::Overlap::kToAndFro, metrics::Overlap::kRacetrack};

struct Predictor::Context {
  // The overlap the figures of overlap o (0 to-and-fro, 1 racetrack) are read with: to-and-fro reads as
  // racetrack where the return pass lands as the outgoing one (ReturnPass::kRacetrack).
  metrics::Overlap overlap(int o) const {
    return o == 1 || return_pass == ReturnPass::kRacetrack ? metrics::Overlap::kRacetrack : metrics::Overlap::kToAndFro;
  }

  Context(const PredictionRequest& request_in, Prediction& out_in, PredictorWorkspace& w_in)
      : request(request_in), out(out_in), w(w_in) {}

  const PredictionRequest& request;
  Prediction& out;
  PredictorWorkspace& w;

  // check_request
  double height_m = 0.0;               // the disc height used (the machine's when the request gives none)
  const MaterialRows* rows = nullptr;  // the material's rows
  DiscSetting settings[2]{};           // each disc's speed and drop point (kLeftDisc, kRightDisc)
  bool two_discs = false;
  bool per_disc = false;               // the discs at settings of their own: each gets its own samples
  DiscRows disc_rows[2]{};             // the rows around each disc's speed (both the left disc's unless per_disc)
  flight::EffectSet effects = 0;       // the flight effects that run
  flight::Air air;
  bool fly_right_disc = false;         // the right disc flown (own setting, lateral wind), not mirrored

  // land_discs
  Landed landed;

  // bin_transverse
  double kernel_half_width_m = 0.0;
  metrics::TrayLayout trays;
  // The right disc is the left one's mirror image on a layout symmetric about the centre line: its kernel
  // mass is the left disc's folded (fold_mirror), so only the left disc's landings are binned.
  bool mirrored = false;
  double lost_mass_fraction = 0.0;

  // return_pass_of, fly_return_pass, align_return_pass
  ReturnPass return_pass = ReturnPass::kOutgoing;
  int return_tray_count = 0;           // the return pass's own layout (kFlown), before alignment
  int return_flights = 0;
  std::span<const double> return_trays;  // on `trays`: the outgoing pattern's own span unless kFlown/kRacetrack

  // measure_pattern
  metrics::ThrowExtent extent;
  int request_bout_trays = 0;          // the requested bout in whole trays (0: none requested)
  double request_cv[2] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  double request_cv_se[2] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  std::size_t se_task_count = 0;       // standard errors queued in the workspace (w.se_tasks_)

  // choose_headline
  int headline[2] = {-1, -1};          // the headline band of each overlap (to-and-fro, racetrack)
};

}  // namespace spread::predict
