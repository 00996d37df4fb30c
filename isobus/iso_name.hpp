#pragma once
// The 64-bit NAME of an ISO 11783 control function (ISO 11783-5 §4.3, the same layout as SAE J1939-81).
// It identifies the function on the bus and, read as an unsigned number, is its priority in address
// contention: the lower NAME wins (§4.4.3.3). Sent little-endian as the 8 data bytes of PGN 0xEE00.
//   bit  63     self-configurable address
//   bits 62-60  industry group                (2 = agricultural and forestry equipment)
//   bits 59-56  device class instance
//   bits 55-49  device class                  (5 = fertilisers, within industry group 2)
//   bit  48     reserved (0)
//   bits 47-40  function                      (0-127 global; 128-254 depend on industry group + device class)
//   bits 39-35  function instance
//   bits 34-32  ECU instance
//   bits 31-21  manufacturer code
//   bits 20-0   identity number
#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace spread::isobus {

inline constexpr std::uint8_t kIndustryGroupAgriculture = 2;
inline constexpr std::uint8_t kDeviceClassFertilisers = 5;
// Functions 128-254 depend on industry group and device class (ISO 11783-1 NAME function table, kept in
// the ISOBUS data dictionary at isobus.net, "Device Class/Function"). For industry group 2, device class 5
// (fertilisers): 128 fertiliser rate control, 129 section on/off control, 130 product pressure,
// 132 fertilisers machine control. This ECU meters product to a set-point rate: 128.
inline constexpr std::uint8_t kFunctionRateControl = 128;

struct IsoName {
  bool self_configurable = false;         // may pick another address in 128-247 when it loses its own
  std::uint8_t industry_group = kIndustryGroupAgriculture;  // 3 bits
  std::uint8_t device_class_instance = 0;  // 4 bits
  std::uint8_t device_class = kDeviceClassFertilisers;  // 7 bits
  std::uint8_t function = kFunctionRateControl;  // 8 bits
  std::uint8_t function_instance = 0;  // 5 bits
  std::uint8_t ecu_instance = 0;       // 3 bits
  // No manufacturer code is assigned to this simulator; 0 keeps it from impersonating a manufacturer.
  std::uint16_t manufacturer_code = 0;  // 11 bits
  std::uint32_t identity_number = 0x1234;  // 21 bits, unique per unit of a manufacturer (a serial number)
};

// Field widths checked: a value that does not fit its field is an error naming the field ("" = fits).
std::string check_name(const IsoName& name);
// Requires check_name(name) to be empty (fields are masked to their width otherwise).
std::uint64_t encode_name(const IsoName& name);
IsoName decode_name(std::uint64_t value);

std::array<std::uint8_t, 8> name_to_bytes(std::uint64_t value);
std::uint64_t name_from_bytes(const std::uint8_t* bytes);  // 8 bytes, little-endian

// "0xA00A800000001234" or "A00A800000001234" (1 to 16 hex digits).
std::optional<std::uint64_t> parse_name_hex(const std::string& text);
// e.g. "NAME 0x200A800000001234 (self-configurable 0, industry group 2, device class 5 instance 0, ...)".
std::string describe_name(std::uint64_t value);

}  // namespace spread::isobus
