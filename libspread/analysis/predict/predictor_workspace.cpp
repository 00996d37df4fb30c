#include "libspread/analysis/predict/predictor_workspace.hpp"

#include <algorithm>
#include <cmath>

#include "libspread/analysis/metrics/wide_kernel.hpp"
#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

PredictorWorkspace::PredictorWorkspace(const Predictor& predictor, std::pmr::memory_resource* memory)
    : samples_(memory),
      sample_weight_kg_(memory),
      granules_(memory),
      launches_(memory),
      landings_(memory),
      landing_x_m_(memory),
      landing_y_m_(memory),
      landing_weight_(memory),
      tray_mass_(memory),
      return_tray_mass_(memory),
      gradients_(memory),
      gradient_scratch_(memory),
      return_gradient_(memory),
      metrics_scratch_(memory),
      chunk_landing_x_m_(memory),
      chunk_landing_y_m_(memory),
      stencil_block_(memory),
      cell_target_(memory),
      search_buffer_(memory) {
  const std::size_t pair = predictor.largest_pair();
  const PredictorLimits& limits = predictor.limits();
  sample_capacity_ = pair;
  samples_.resize(kFlightChunk);
  sample_weight_kg_.resize(kFlightChunk);
  // Two discs, each flown (lateral wind) or mirrored: at most two landings per sample.
  landing_x_m_.resize(2 * pair);
  landing_y_m_.resize(2 * pair);
  landing_weight_.resize(2 * pair);
  granules_.resize(kFlightChunk);
  launches_.resize(kFlightChunk);
  landings_.resize(kFlightChunk);
  chunk_landing_x_m_.resize(kFlightChunk);
  chunk_landing_y_m_.resize(kFlightChunk);
  stencil_block_.resize(1);
  cell_target_.resize(predictor.most_cells());
  const int widest = predictor.tray_capacity(limits.min_tray_width_m);
  tray_capacity_ = static_cast<std::size_t>(widest);
  tray_mass_.resize(tray_capacity_);
  return_tray_mass_.resize(tray_capacity_);
  gradients_.resize(tray_capacity_);
  gradient_scratch_.resize(tray_capacity_);
  return_gradient_.resize(tray_capacity_);
  // The widest bout a request may ask for, in the narrowest trays, plus its cut edge tray: cv_gradient's
  // scratch, at the metrics scratch's end.
  const auto widest_bout = static_cast<std::size_t>(std::ceil(limits.max_bout_width_m / limits.min_tray_width_m)) + 2;
  cv_scratch_size_ = widest_bout;
  // Also a wide kernel's difference arrays (wide_kernel.hpp), which working_widths' FFT scratch exceeds;
  // and during the standard errors' passes (InfluencePass) the prefix sums of their gradients before
  // cv_gradient's tail: SampleInfluence::kMaxGradients gradients of up to ~800 trays in one pass (a wider
  // layout takes more), in the room a buffer of each gradient would take otherwise.
  const metrics::TrayLayout widest_layout{limits.min_tray_width_m, widest};
  metrics_scratch_.resize(std::max({metrics::working_widths_scratch_size(widest), widest_bout, tray_capacity_ + 2,
                                    metrics::wide_kernel_scratch_size(widest_layout)}) +
                          (SampleInfluence::kMaxGradients - 1) * tray_capacity_);
  search_buffer_.resize(4 * tray_capacity_ + widest_bout);
}

std::size_t PredictorWorkspace::bytes() const {
  return samples_.size() * sizeof(tables::LaunchSample) + granules_.size() * sizeof(flight::Granule) +
         launches_.size() * sizeof(flight::State) + landings_.size() * sizeof(flight::Landing) +
         sizeof(double) * (sample_weight_kg_.size() + landing_x_m_.size() + landing_y_m_.size() +
                           landing_weight_.size() + tray_mass_.size() + return_tray_mass_.size() + gradients_.size() +
                           gradient_scratch_.size() + return_gradient_.size() + metrics_scratch_.size() + chunk_landing_x_m_.size() +
                           chunk_landing_y_m_.size() + search_buffer_.size()) +
         sizeof(LandingGrid::StencilBlock) * stencil_block_.size() +
         sizeof(tables::LaunchSample) * cell_target_.size();
}

}  // namespace spread::predict
