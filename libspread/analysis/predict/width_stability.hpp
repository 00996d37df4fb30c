#pragma once
// How firmly the launch samples hold the headline working width: the bootstrap (Efron 1979; Efron &
// Tibshirani 1993, ch. 6) over the table's launch samples. Each resample draws every row's samples with
// replacement (as many as the row has, from a deterministic generator seeded by `seed`), builds a
// Predictor of the resampled rows and predicts the request: the headline as it would be had the DEM run
// drawn those granules. The delta-method ± of a width (Prediction::working_width_to_and_fro_se_m) is
// local: it cannot see a band that splits near the target and takes the headline metres away; the
// bootstrap sees it.
//
// A table's derived landing data is not resampled (each resample derives its own), so a resample costs
// a Predictor's construction and one prediction: about a second for the main job's table. For tools and
// studies, not for a control loop.
#include <cstdint>

#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace spread::predict {

struct WidthStability {
  int resamples = 0;
  double headline_m = 0.0;      // the request's headline to-and-fro working width on the table itself
  double interval_m = 0.0;      // its 95 % interval, 1.96 SE (NaN when it has none)
  // Of the resamples: the share whose headline lies outside headline_m ± interval_m, and the share more
  // than 1 m away.
  double outside_interval_fraction = 0.0;
  double beyond_1m_fraction = 0.0;
  double quantile_025_m = 0.0, quantile_975_m = 0.0;  // of the resamples' headlines
  double lowest_m = 0.0, highest_m = 0.0;
};

// `contents`: the table as read (its samples in each Run, not pooled). `request`: as for predict(), with
// standard errors. Throws std::invalid_argument for resamples < 2 or a request the predictor refuses.
WidthStability width_stability(const tables::TableContents& contents, const PredictionRequest& request, int resamples,
                               std::uint64_t seed = 1);

}  // namespace spread::predict
