#pragma once
// DM1, active diagnostic trouble codes (ISO 11783-12 / SAE J1939-73, PGN 0xFECA): every ECU broadcasts
// its active faults once a second. Layout: byte 0 lamp status (2 bits each, from the top: malfunction
// indicator, red stop, amber warning, protect; 00 off, 01 on), byte 1 lamp flash (0xFF: no flashing),
// then 4 bytes per DTC: SPN bits 0-7, SPN bits 8-15, SPN bits 16-18 in the top 3 bits with the FMI in the
// low 5, then the conversion-method bit (0) above a 7-bit occurrence count. No active fault is one DTC of
// zeros; a message over 8 bytes goes by BAM (transport_protocol.hpp).
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace spread::isobus {

inline constexpr std::uint32_t kDm1Pgn = 0xFECA;
inline constexpr std::uint8_t kDm1Priority = 6;
// SPNs 520192-524287 are left to the manufacturer (SAE J1939-71 proprietary range).
inline constexpr std::uint32_t kProprietarySpnBase = 520192;

// Failure mode identifiers used here (SAE J1939-73 Table 5).
enum class Fmi : std::uint8_t {
  kDataErratic = 2,            // a value out of its range or not a number
  kAbnormalUpdateRate = 9,     // a periodic input stopped
  kReceivedNetworkDataError = 19,
  kConditionExists = 31,
};

struct Dtc {
  std::uint32_t spn = 0;          // 19 bits
  Fmi fmi = Fmi::kConditionExists;
  std::uint8_t occurrences = 0;   // 0-126 (127: not available)
};

struct Lamps {
  bool malfunction = false;
  bool red_stop = false;
  bool amber_warning = false;
  bool protect = false;
};

std::vector<std::uint8_t> encode_dm1(const Lamps& lamps, std::span<const Dtc> active);

struct Dm1 {
  Lamps lamps;
  std::vector<Dtc> active;  // empty for the all-zero "no active fault" DTC
};
// nullopt when the length is not 2 + 4 n (n >= 1).
std::optional<Dm1> decode_dm1(std::span<const std::uint8_t> bytes);

}  // namespace spread::isobus
