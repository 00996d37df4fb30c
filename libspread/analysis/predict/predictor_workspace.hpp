#pragma once
// PredictorWorkspace: everything one Predictor::predict call writes — launch samples at the requested
// setting, flights, landings, trays, gradients and the metrics' scratch — sized once for one Predictor, so
// that predict() never allocates. One per thread that predicts.
#include <array>
#include <cstddef>
#include <limits>
#include <memory_resource>
#include <span>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/landing_grid.hpp"
#include "libspread/analysis/predict/prediction.hpp"
#include "libspread/analysis/predict/sample_influence.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/physics/flight/flight.hpp"

namespace spread::predict {

class Predictor;

// Flights per flight::fly_many call in predict(): the workspace holds launch samples, launches and
// landings for this many, not for every flight (the samples of the default table's largest pair of rows
// alone would be 0.5 MB per workspace).
inline constexpr std::size_t kFlightChunk = 128;

// Everything one predict() call writes: launch samples at the requested rpm, flights, landings, trays,
// gradients and the metrics' scratch. Sized for one Predictor; one per thread that predicts.
class PredictorWorkspace {
 public:
  // Allocates from `memory` (which must outlive the workspace); the Predictor is only read.
  explicit PredictorWorkspace(const Predictor& predictor,
                              std::pmr::memory_resource* memory = std::pmr::get_default_resource());
  // Bytes of the buffers it holds.
  std::size_t bytes() const;
  // Room for a search that combines each disc's trays between predictions (wind_compensation.hpp): four
  // arrays of the widest layout's trays and a bout of the widest bout width. predict() never touches it.
  std::span<double> search_buffer() { return search_buffer_; }

 private:
  friend class Predictor;
  std::size_t sample_capacity_ = 0;  // launch samples of the largest pair of rows it was sized for
  std::size_t tray_capacity_ = 0;
  // One chunk of launch samples at the request's setting and their weights (kg), and of flights
  // (kFlightChunk): the left disc's, then the right disc's when flown.
  std::pmr::vector<tables::LaunchSample> samples_;
  std::pmr::vector<double> sample_weight_kg_;
  std::pmr::vector<flight::Granule> granules_;
  std::pmr::vector<flight::State> launches_;
  std::pmr::vector<flight::Landing> landings_;
  std::pmr::vector<double> landing_x_m_, landing_y_m_, landing_weight_;  // machine frame, both discs
  std::pmr::vector<double> tray_mass_;
  std::pmr::vector<double> return_tray_mass_;  // the return pass's pattern (return_pass.cpp)
  // Per tray, for the standard errors: the gradient being made for a pass (InfluencePass keeps its prefix
  // sums), and one more for the width gradients' second CV.
  std::pmr::vector<double> gradients_, gradient_scratch_;
  std::pmr::vector<double> return_gradient_;  // a flown return pass's share of a gradient (uncertainty.cpp)
  // metrics::working_widths' scratch, also the bout buffer of cv_at_trays / cv_gradient (up to the widest
  // requested bout at the narrowest trays, its last cv_scratch_size_ values), so that no bout is built on
  // the stack, and during the standard errors' passes the gradients' prefix sums (before that tail).
  std::pmr::vector<double> metrics_scratch_;
  std::size_t cv_scratch_size_ = 0;  // the metrics scratch's tail that cv_gradient uses during the passes
  // The landing grid's landings of one chunk (kFlightChunk: both discs land half a chunk of samples each)
  // and its stencils' set-up.
  std::pmr::vector<double> chunk_landing_x_m_, chunk_landing_y_m_;
  std::pmr::vector<LandingGrid::StencilBlock> stencil_block_;
  std::pmr::vector<tables::LaunchSample> cell_target_;  // Predictor::cell_targets
  std::pmr::vector<double> search_buffer_;
  // predict()'s bookkeeping of the bands and their standard errors (kept here, not on the caller's stack):
  // one standard error to compute — of the CV at `trays` trays, or (width_band set) of that band's upper
  // end, or (throw_width) of the throw width —, and per band the racetrack CV at a to-and-fro band's bout.
  struct SeTask {
    double* out;
    metrics::Overlap overlap;
    int trays;
    const metrics::WidthBand* width_band;
    bool throw_width = false;
  };
  struct BandExtra {
    const metrics::WidthBand* band = nullptr;
    double racetrack_cv = std::numeric_limits<double>::quiet_NaN();
    double racetrack_cv_se = std::numeric_limits<double>::quiet_NaN();
  };
  std::array<SeTask, 3 + 2 * kMaxBands * 5> se_tasks_{};
  // The discs' launch samples by source (SampleInfluence), when each disc has its own setting.
  std::array<SampleBlock, kMaxSampleBlocks> sample_blocks_{};
  std::size_t sample_block_count_ = 0;
  std::array<BandExtra, 2 * kMaxBands> band_extras_{};
  metrics::WorkingWidths widths_;
  double radial_mean_m_ = 0.0;  // R̄, ξ of the last fly_launches()
  double radial_width_m_ = 0.0;
};

}  // namespace spread::predict
