#pragma once
// Tractor speed broadcasts (ISO 11783-7, 8 bytes, every 100 ms):
//   PGN 0xFE48 wheel-based speed and distance, PGN 0xFE49 ground-based speed and distance,
//   PGN 0xF022 machine selected speed (the tractor's own choice among its sources)
//   bytes 0-1 speed [mm/s] (0.001 m/s per bit, LE; 0xFB00.. = error / not available)
//   bytes 2-5 distance [mm] (LE), byte 6 (wheel-based: max. time of tractor power [min];
//   machine selected: exit/reason code), byte 7 bits 0-1 direction (00 reverse, 01 forward, 10 error,
//   11 not available); the direction sits in the same place in all three.
#include <array>
#include <cstdint>
#include <optional>

namespace spread::isobus {

inline constexpr std::uint32_t kWheelBasedSpeedPgn = 0xFE48;
inline constexpr std::uint32_t kGroundBasedSpeedPgn = 0xFE49;
inline constexpr std::uint32_t kMachineSelectedSpeedPgn = 0xF022;
inline constexpr std::uint16_t kSpeedLargestValid = 0xFAFF;  // [mm/s]; above: error / not available

enum class Direction : std::uint8_t { kReverse = 0, kForward = 1, kError = 2, kNotAvailable = 3 };

struct SpeedMessage {
  double speed_m_s = 0.0;       // [m/s]
  std::uint32_t distance_mm = 0;
  Direction direction = Direction::kNotAvailable;
};

// nullopt when the speed field says "error" or "not available".
std::optional<SpeedMessage> decode_speed(const std::array<std::uint8_t, 8>& bytes);
std::array<std::uint8_t, 8> encode_speed(double speed_m_s, std::uint32_t distance_mm, Direction direction);

}  // namespace spread::isobus
