#pragma once
// The object behind the opaque spread_tables handle: the predictor (tables in memory + workspace).
#include <cstddef>

#include "capi/src/abi_layout.hpp"
#include "libspread/predict/predictor.hpp"
#include "spread/spread.h"

struct spread_tables {
  explicit spread_tables(spread::tables::TableContents contents) : predictor(std::move(contents)) {}
  spread::predict::Predictor predictor;
};
