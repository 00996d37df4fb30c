#include "libspread/analysis/predict/landing_data_codec.hpp"

#include <bit>
#include <cstdio>
#include <cstring>

namespace spread::predict {

namespace {

void append_le(std::vector<std::uint8_t>& out, std::uint64_t value, int size) {
  for (int i = 0; i < size; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

std::uint64_t load_le(const std::uint8_t* p, int size) {
  std::uint64_t value = 0;
  for (int i = 0; i < size; ++i) value |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return value;
}

std::string settings_text(const flight::Settings& s) {
  char text[256];
  std::snprintf(text, sizeof text, "scheme %d dt %.17g rtol %.17g atol %.17g max_time %.17g max_steps %d lift %d g %.17g",
                static_cast<int>(s.scheme), s.dt_s, s.rel_tol, s.abs_tol, s.max_time_s, s.max_steps,
                static_cast<int>(s.lift), s.gravity_m_s2);
  return text;
}

}  // namespace

std::string landing_data_model(const LandingDomain& domain, const flight::Settings& grid_settings,
                               const flight::Settings& key_settings) {
  char text[160];
  std::snprintf(text, sizeof text, "landing data %d; grid nodes %u %u %u %u, heights %.17g-%.17g m, wind %.17g m/s",
                kLandingDataVersion, kGridNodes[0], kGridNodes[1], kGridNodes[2], kGridNodes[3],
                domain.min_disc_height_m, domain.max_disc_height_m, domain.max_wind_m_s);
  return std::string(text) + ", flights " + settings_text(grid_settings) + "; cell keys " + settings_text(key_settings);
}

void LandingDataWriter::u32(std::uint32_t value) { append_le(bytes_, value, 4); }
void LandingDataWriter::f64(double value) { append_le(bytes_, std::bit_cast<std::uint64_t>(value), 8); }
void LandingDataWriter::f32s(std::span<const float> values) {
  bytes_.reserve(bytes_.size() + 4 * values.size());
  for (float value : values) append_le(bytes_, std::bit_cast<std::uint32_t>(value), 4);
}
void LandingDataWriter::bytes(std::span<const std::uint8_t> values) {
  bytes_.insert(bytes_.end(), values.begin(), values.end());
}

bool LandingDataReader::u32(std::uint32_t& value) {
  if (bytes_.size() - offset_ < 4) return false;
  value = static_cast<std::uint32_t>(load_le(bytes_.data() + offset_, 4));
  offset_ += 4;
  return true;
}
bool LandingDataReader::f64(double& value) {
  if (bytes_.size() - offset_ < 8) return false;
  value = std::bit_cast<double>(load_le(bytes_.data() + offset_, 8));
  offset_ += 8;
  return true;
}
bool LandingDataReader::f32s(std::span<float> values) {
  if ((bytes_.size() - offset_) / 4 < values.size()) return false;
  if constexpr (std::endian::native == std::endian::little) {  // the stored order: one copy
    std::memcpy(values.data(), bytes_.data() + offset_, values.size_bytes());
    offset_ += values.size_bytes();
    return true;
  }
  for (float& value : values) {
    value = std::bit_cast<float>(static_cast<std::uint32_t>(load_le(bytes_.data() + offset_, 4)));
    offset_ += 4;
  }
  return true;
}
bool LandingDataReader::bytes(std::size_t count, std::span<const std::uint8_t>& values) {
  if (bytes_.size() - offset_ < count) return false;
  values = bytes_.subspan(offset_, count);
  offset_ += count;
  return true;
}

}  // namespace spread::predict
