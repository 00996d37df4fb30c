#pragma once
// For the in-tree tools only (not in spread.h, not in the shipped libraries): the handle spread_open makes,
// from a table's contents a tool has read already, so that a command reads its table file once and still
// predicts through the C API — what it prints is what an integrator gets.
#include "libspread/io/tables/table_reader.hpp"
#include "spread/spread.h"

namespace spread::capi {

// SPREAD_OK with *out_tables a live handle (spread_close frees it), or the status and detail spread_open
// gives for the same contents (SPREAD_ERROR_FILE_* for contents the Predictor refuses, out of memory).
spread_status open_contents(tables::TableContents contents, spread_tables** out_tables);

}  // namespace spread::capi
