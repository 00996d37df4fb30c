#pragma once
// The object behind the opaque spread_tables handle: the predictor (tables in memory + workspace).
#include <cstddef>

#include "libspread/predict/predictor.hpp"
#include "spread/spread.h"

struct spread_tables {
  explicit spread_tables(spread::tables::TableContents contents) : predictor(std::move(contents)) {}
  spread::predict::Predictor predictor;
};

namespace spread::capi {

// Oldest struct sizes this library accepts (the first published layouts). A caller compiled against a
// newer header passes a larger struct_size; the library reads the fields it knows.
// The definition as the first release had it (up to tray_width_m), and as it is now.
inline constexpr std::size_t kPredictionDefV1Size = offsetof(spread_prediction_def, kernel_half_width_m);
inline constexpr std::size_t kPredictionDefV2Size = sizeof(spread_prediction_def);
inline constexpr std::size_t kTrajectoryDefV1Size = sizeof(spread_trajectory_def);

// Accepted integrator steps after which spread_trajectory gives up (SPREAD_ERROR_NOT_LANDED): 3072 steps
// of about 0.45 µs each keep one call near 1.4 ms (bench_capi BM_TrajectoryWorstCase).
inline constexpr int kTrajectoryMaxSteps = 3072;

}  // namespace spread::capi
