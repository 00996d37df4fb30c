#include "libspread/io/tables/sample_codec.hpp"

#include <array>
#include <bit>
#include <cstddef>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace spread::tables {
namespace {

static_assert(sizeof(float) == 4 && std::numeric_limits<float>::is_iec559, "float32 must be IEEE 754");

std::array<float, kSampleFloats> to_fields(const LaunchSample& s) {
  return {s.x_m,     s.y_m,     s.z_m,     s.t_s,     s.vx_norm,    s.vy_norm,
          s.vz_norm, s.wx_norm, s.wy_norm, s.wz_norm, s.diameter_m, s.mass_kg};
}

LaunchSample from_fields(const std::array<float, kSampleFloats>& f) {
  return LaunchSample{f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8], f[9], f[10], f[11]};
}

}  // namespace

std::vector<std::uint8_t> encode_samples(std::span<const LaunchSample> samples) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(samples.size() * kSampleBytes);
  for (const LaunchSample& sample : samples) {
    for (float value : to_fields(sample)) {
      const auto bits = std::bit_cast<std::uint32_t>(value);
      for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<std::uint8_t>(bits >> shift));
    }
  }
  return bytes;
}

void decode_samples_into(std::span<const std::uint8_t> bytes, std::span<LaunchSample> out) {
  if (bytes.size() % kSampleBytes != 0 || out.size() != bytes.size() / kSampleBytes) {
    throw std::invalid_argument("decode_samples: byte count is not the record size times the sample count");
  }
  // On a little-endian host with LaunchSample's fields in the layout's order and no padding, the file's
  // bytes are the samples' bytes; elsewhere each float is put together from its four bytes.
  if constexpr (std::endian::native == std::endian::little && sizeof(LaunchSample) == kSampleBytes &&
                offsetof(LaunchSample, mass_kg) == kSampleBytes - 4 && offsetof(LaunchSample, x_m) == 0) {
    if (!bytes.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
    return;
  }
  std::array<float, kSampleFloats> fields{};
  for (std::size_t k = 0; k < out.size(); ++k) {
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const std::uint8_t* b = bytes.data() + k * kSampleBytes + 4 * i;
      const std::uint32_t bits = static_cast<std::uint32_t>(b[0]) | (static_cast<std::uint32_t>(b[1]) << 8) |
                                 (static_cast<std::uint32_t>(b[2]) << 16) |
                                 (static_cast<std::uint32_t>(b[3]) << 24);
      fields[i] = std::bit_cast<float>(bits);
    }
    out[k] = from_fields(fields);
  }
}

std::vector<LaunchSample> decode_samples(std::span<const std::uint8_t> bytes) {
  if (bytes.size() % kSampleBytes != 0) {
    throw std::invalid_argument("decode_samples: byte count is not a multiple of the record size");
  }
  std::vector<LaunchSample> samples(bytes.size() / kSampleBytes);
  decode_samples_into(bytes, samples);
  return samples;
}

}  // namespace spread::tables
