#pragma once
// The C status of a predictor's refusal: one mapping for every entry point that predicts.
#include "libspread/analysis/predict/predictor.hpp"
#include "spread/spread.h"

namespace spread::capi {

inline spread_status status_of(spread::predict::PredictStatus status) {
  using S = spread::predict::PredictStatus;
  switch (status) {
    case S::kOk: return SPREAD_OK;
    case S::kNotFinite: return SPREAD_ERROR_NOT_FINITE;
    case S::kOutOfRange: return SPREAD_ERROR_OUT_OF_RANGE;
    case S::kUnknownEffect: return SPREAD_ERROR_UNKNOWN_EFFECT;
    case S::kUnknownMaterial: return SPREAD_ERROR_UNKNOWN_MATERIAL;
    case S::kRpmOutsideTable: return SPREAD_ERROR_RPM_OUTSIDE_TABLE;
    case S::kOutsideDomain: return SPREAD_ERROR_OUTSIDE_DOMAIN;
  }
  return SPREAD_ERROR_INTERNAL;
}

}  // namespace spread::capi
