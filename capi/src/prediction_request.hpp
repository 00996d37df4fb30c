#pragma once
// A C prediction definition as the library's request, and why a request is refused: one reading and one
// set of refusals for every entry point that takes a spread_prediction_def (spread_predict,
// spread_workspace_predict, spread_compensate_wind, the two edge functions), so that a cause has one status
// and one detail naming the field wherever it is found. Neither allocates.
#include "libspread/analysis/predict/predictor.hpp"
#include "spread/spread.h"

namespace spread::capi {

// The definition's fields of its version (struct_size) into `request`: SPREAD_OK, or the refusal (with the
// detail) of a struct_size older than the first published one, a NULL material or a flag that is neither 0
// nor 1. `def` is not NULL.
spread_status read_request(const char* function, const spread_prediction_def& def,
                           spread::predict::PredictionRequest& request);

// The result the library writes for this definition: SPREAD_OK, or SPREAD_ERROR_OUT_OF_RANGE when the
// definition says (result_size, from 0.3 on) that the caller's result is smaller than the smallest result
// written for it (0.2's: every result field up to and including kernel_half_width_m).
spread_status check_result_size(const char* function, const spread_prediction_def& def);

// What Predictor::predict would refuse in `request`, found without predicting (validation, the material,
// every disc's speed against its rows, the landing grid's domain — in predict's order): SPREAD_OK, or the
// status with the detail of refused().
spread_status check_request(const char* function, const spread::predict::Predictor& predictor,
                            const spread_prediction_def& def, const spread::predict::PredictionRequest& request);

// The refusal of `request` (read from `def`) with `status`: the detail names the field as the definition
// names it, its value and its range. Returns `status`.
spread_status refused(const char* function, spread_status status, const spread::predict::Predictor& predictor,
                      const spread_prediction_def& def, const spread::predict::PredictionRequest& request);

}  // namespace spread::capi
