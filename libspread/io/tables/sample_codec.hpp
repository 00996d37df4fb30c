#pragma once
// Launch samples <-> the little-endian float32 BLOB of the `runs.samples` column (docs/design.md §4).
// Byte order is written out explicitly (bit_cast + shifts), so files move between hosts unchanged.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "libspread/io/tables/table_format.hpp"

namespace spread::tables {

inline constexpr std::size_t kSampleBytes = static_cast<std::size_t>(kSampleFloats) * 4;

// kSampleBytes per sample, fields in the order of kSampleLayout.
std::vector<std::uint8_t> encode_samples(std::span<const LaunchSample> samples);

// bytes.size() must be a multiple of kSampleBytes (the reader checks the size before calling).
std::vector<LaunchSample> decode_samples(std::span<const std::uint8_t> bytes);

// The same into caller storage of bytes.size() / kSampleBytes samples: the reader decodes a run straight
// into the block that keeps it, with no vector in between.
void decode_samples_into(std::span<const std::uint8_t> bytes, std::span<LaunchSample> out);

}  // namespace spread::tables
