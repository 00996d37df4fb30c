#include "isobus/speed_messages.hpp"

#include <cmath>

namespace spread::isobus {

std::optional<SpeedMessage> decode_speed(const std::array<std::uint8_t, 8>& b) {
  const auto raw = static_cast<std::uint16_t>(b[0] | (std::uint16_t{b[1]} << 8));
  if (raw > kSpeedLargestValid) return std::nullopt;
  SpeedMessage m;
  m.speed_m_s = raw * 1e-3;
  m.distance_mm = std::uint32_t{b[2]} | (std::uint32_t{b[3]} << 8) | (std::uint32_t{b[4]} << 16) |
                  (std::uint32_t{b[5]} << 24);
  m.direction = static_cast<Direction>(b[7] & 0x03u);
  return m;
}

std::array<std::uint8_t, 8> encode_speed(double speed_m_s, std::uint32_t distance_mm, Direction direction) {
  std::array<std::uint8_t, 8> b{};
  double mm_s = std::round(speed_m_s * 1e3);
  if (!(mm_s >= 0.0)) mm_s = 0xFFFF;  // NaN or negative: "not available"
  if (mm_s > 0xFFFF) mm_s = 0xFFFF;
  const auto raw = static_cast<std::uint16_t>(mm_s);
  b[0] = static_cast<std::uint8_t>(raw & 0xFFu);
  b[1] = static_cast<std::uint8_t>(raw >> 8);
  for (int i = 0; i < 4; ++i) b[static_cast<std::size_t>(2 + i)] = static_cast<std::uint8_t>(distance_mm >> (8 * i));
  b[6] = 0xFF;
  b[7] = static_cast<std::uint8_t>(0xFCu | static_cast<std::uint8_t>(direction));  // other bits not available
  return b;
}

}  // namespace spread::isobus
