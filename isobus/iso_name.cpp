#include "isobus/iso_name.hpp"

#include <charconv>
#include <cstdio>

namespace spread::isobus {
namespace {

struct Field {
  unsigned shift;
  unsigned bits;
};
constexpr Field kSelfConfigurable{63, 1};
constexpr Field kIndustryGroup{60, 3};
constexpr Field kDeviceClassInstance{56, 4};
constexpr Field kDeviceClass{49, 7};
constexpr Field kFunction{40, 8};
constexpr Field kFunctionInstance{35, 5};
constexpr Field kEcuInstance{32, 3};
constexpr Field kManufacturerCode{21, 11};
constexpr Field kIdentityNumber{0, 21};

constexpr std::uint64_t mask(Field f) { return (std::uint64_t{1} << f.bits) - 1; }
std::uint64_t put(Field f, std::uint64_t value) { return (value & mask(f)) << f.shift; }
std::uint64_t get(Field f, std::uint64_t name) { return (name >> f.shift) & mask(f); }

}  // namespace

std::string check_name(const IsoName& n) {
  auto fits = [](Field f, std::uint64_t v) { return v <= mask(f); };
  if (!fits(kIndustryGroup, n.industry_group)) return "industry group above 7";
  if (!fits(kDeviceClassInstance, n.device_class_instance)) return "device class instance above 15";
  if (!fits(kDeviceClass, n.device_class)) return "device class above 127";
  if (!fits(kFunctionInstance, n.function_instance)) return "function instance above 31";
  if (!fits(kEcuInstance, n.ecu_instance)) return "ECU instance above 7";
  if (!fits(kManufacturerCode, n.manufacturer_code)) return "manufacturer code above 2047";
  if (!fits(kIdentityNumber, n.identity_number)) return "identity number above 2097151";
  return "";
}

std::uint64_t encode_name(const IsoName& n) {
  return put(kSelfConfigurable, n.self_configurable ? 1 : 0) | put(kIndustryGroup, n.industry_group) |
         put(kDeviceClassInstance, n.device_class_instance) | put(kDeviceClass, n.device_class) |
         put(kFunction, n.function) | put(kFunctionInstance, n.function_instance) |
         put(kEcuInstance, n.ecu_instance) | put(kManufacturerCode, n.manufacturer_code) |
         put(kIdentityNumber, n.identity_number);
}

IsoName decode_name(std::uint64_t v) {
  IsoName n;
  n.self_configurable = get(kSelfConfigurable, v) != 0;
  n.industry_group = static_cast<std::uint8_t>(get(kIndustryGroup, v));
  n.device_class_instance = static_cast<std::uint8_t>(get(kDeviceClassInstance, v));
  n.device_class = static_cast<std::uint8_t>(get(kDeviceClass, v));
  n.function = static_cast<std::uint8_t>(get(kFunction, v));
  n.function_instance = static_cast<std::uint8_t>(get(kFunctionInstance, v));
  n.ecu_instance = static_cast<std::uint8_t>(get(kEcuInstance, v));
  n.manufacturer_code = static_cast<std::uint16_t>(get(kManufacturerCode, v));
  n.identity_number = static_cast<std::uint32_t>(get(kIdentityNumber, v));
  return n;
}

std::array<std::uint8_t, 8> name_to_bytes(std::uint64_t value) {
  std::array<std::uint8_t, 8> out{};
  for (std::size_t i = 0; i < 8; ++i) out[i] = static_cast<std::uint8_t>(value >> (8 * i));
  return out;
}

std::uint64_t name_from_bytes(const std::uint8_t* bytes) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | bytes[i];
  return v;
}

std::optional<std::uint64_t> parse_name_hex(const std::string& text) {
  std::string_view s(text);
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) s.remove_prefix(2);
  if (s.empty() || s.size() > 16) return std::nullopt;
  std::uint64_t value = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), value, 16);
  if (r.ec != std::errc{} || r.ptr != s.data() + s.size()) return std::nullopt;
  return value;
}

std::string describe_name(std::uint64_t value) {
  const IsoName n = decode_name(value);
  char text[320];
  std::snprintf(text, sizeof(text),
                "NAME 0x%016llX (self-configurable %d, industry group %u, device class %u instance %u, function %u "
                "instance %u, ECU instance %u, manufacturer %u, identity %u)",
                static_cast<unsigned long long>(value), n.self_configurable ? 1 : 0, unsigned{n.industry_group},
                unsigned{n.device_class}, unsigned{n.device_class_instance}, unsigned{n.function},
                unsigned{n.function_instance}, unsigned{n.ecu_instance}, unsigned{n.manufacturer_code},
                unsigned{n.identity_number});
  return text;
}

}  // namespace spread::isobus
