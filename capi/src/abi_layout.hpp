#pragma once
// The published layouts of the C API's structs, and how the library tells them apart
// (docs/c-api.md "ABI rules"). A caller's struct_size is the sizeof() of the header it was compiled
// with; the library reads a definition field, and writes the result fields of the same version, only
// when struct_size covers the definition's version whole.
#include <cstddef>
#include <cstdint>

#include "spread/spread.h"

namespace spread::capi {

// Each constant is the end of the last field of one published version, oldest first. The first of
// each struct is the smallest struct_size accepted; a struct_size between two constants is read as the
// older version (only whole fields are read).
// spread_prediction_def: 0.1 ended with tray_width_m; 0.2 appended kernel_half_width_m; 0.3 result_size,
// reserved and drop_point_turn_rad; 0.4 disc_rpm and disc_drop_point_turn_rad; 0.5 fly_outside_domain and
// reserved2.
inline constexpr std::size_t kPredictionDefV1Size = offsetof(spread_prediction_def, kernel_half_width_m);
inline constexpr std::size_t kPredictionDefV2Size =
    offsetof(spread_prediction_def, kernel_half_width_m) + sizeof(double);
inline constexpr std::size_t kPredictionDefV3Size = offsetof(spread_prediction_def, drop_point_turn_rad) + sizeof(double);
inline constexpr std::size_t kPredictionDefV4Size =
    offsetof(spread_prediction_def, disc_drop_point_turn_rad) + sizeof(double[2]);
inline constexpr std::size_t kPredictionDefV5Size = offsetof(spread_prediction_def, reserved2) + sizeof(uint32_t);
// spread_trajectory_def: 0.1 ended with effects. `reserved` filled its trailing padding later; where the
// ABI had no such padding (4-byte aligned doubles) that made the struct larger, hence two sizes.
inline constexpr std::size_t kTrajectoryDefV1Size = offsetof(spread_trajectory_def, reserved);
inline constexpr std::size_t kTrajectoryDefReservedSize = offsetof(spread_trajectory_def, reserved) + sizeof(uint32_t);
// The results: up to 0.2 their version is the definition's; from 0.3 on the definition's result_size
// says how much of the result the caller has.
inline constexpr std::size_t kPredictionV1Size = offsetof(spread_prediction, sample_count);
inline constexpr std::size_t kPredictionV2Size = offsetof(spread_prediction, band_count_to_and_fro);
inline constexpr std::size_t kPredictionV3Size = offsetof(spread_prediction, bands_racetrack) + sizeof(spread_band[SPREAD_MAX_BANDS]);
inline constexpr std::size_t kPredictionV4Size = offsetof(spread_prediction, disc_drop_point_turn_rad) + sizeof(double[2]);

// Versions are told apart by size alone, so each published size differs from the one before.
static_assert(kPredictionDefV1Size < kPredictionDefV2Size && kPredictionDefV2Size < kPredictionDefV3Size &&
              kPredictionDefV3Size < kPredictionDefV4Size && kPredictionDefV4Size < kPredictionDefV5Size);
static_assert(kTrajectoryDefV1Size < kTrajectoryDefReservedSize);
static_assert(kPredictionV1Size < kPredictionV2Size && kPredictionV2Size < kPredictionV3Size &&
              kPredictionV3Size < kPredictionV4Size);
// No published struct ends in padding: a field appended next must lie beyond the sizeof() of this
// header, or a caller of this header would pass a struct_size that covers its padding as that field.
// The right-hand sides name each struct's last field: appending one means updating these lines.
static_assert(sizeof(spread_prediction_def) == kPredictionDefV5Size);
static_assert(sizeof(spread_trajectory_def) == kTrajectoryDefReservedSize);
static_assert(sizeof(spread_prediction) == kPredictionV4Size);
static_assert(sizeof(spread_band) == offsetof(spread_band, limited_by_layout) + sizeof(int32_t));
static_assert(sizeof(spread_landing) == offsetof(spread_landing, reserved) + sizeof(int32_t));
static_assert(sizeof(spread_edge_def) == offsetof(spread_edge_def, min_edge_rate_percent) + sizeof(double));
static_assert(sizeof(spread_edge_result) == offsetof(spread_edge_result, tray_left_edge_m) + sizeof(double));

}  // namespace spread::capi
