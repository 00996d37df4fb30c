#pragma once
// Device descriptor object pool (DDOP), ISO 11783-10 Annex B: how an implement describes itself to a task
// controller. A pool is a list of objects, each a 3-letter type tag, a 16-bit object ID and its fields,
// all little endian:
//   DVC device                  designator, software version, working-set master NAME (8 bytes), serial
//                               number, structure label (7 bytes), localisation label (7 bytes) and, from
//                               version 4 on, the extended structure label: a length byte (0-32) and
//                               that many bytes (Annex B, device object)
//   DET device element          type, designator, element number, parent object ID, the IDs of its DPD
//                               and DPT objects (Annex B, device element object)
//   DPD device process data     DDI, properties, available trigger methods, designator, presentation ID
//   DPT device property         DDI, value (int32), designator, presentation ID
//   DVP device value presentation  offset (int32), scale (float32), decimals, unit designator
// Strings are a length byte and that many bytes (no terminator). The element tree is built through each
// DET's parent object ID (the device element's parent is the DVC); a DET's object list names only its DPD
// and DPT objects, never another element, and task controllers refuse a pool that does otherwise. The
// writer and the reader here are each other's inverse for one version, and the reader checks every
// reference a task controller would rely on.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace spread::isobus {

inline constexpr std::uint16_t kNullObjectId = 0xFFFF;  // "no presentation object"
// The TC version the pool is written for (ISO 11783-10 technical capabilities): version 4 adds the DVC's
// extended structure label; a client connecting to a version-3 TC writes its pool without it.
inline constexpr std::uint8_t kDdopVersion = 4;
inline constexpr std::size_t kMaxExtendedStructureLabel = 32;  // bytes (Annex B, device object)

enum class ElementType : std::uint8_t {
  kDevice = 1,
  kFunction = 2,
  kBin = 3,
  kSection = 4,
  kUnit = 5,
  kConnector = 6,
  kNavigationReference = 7,
};

// DPD properties (ISO 11783-10 B.4): bit 0 member of the default set, bit 1 settable, bit 2 control source.
inline constexpr std::uint8_t kPropertyDefaultSet = 0x01;
inline constexpr std::uint8_t kPropertySettable = 0x02;
inline constexpr std::uint8_t kPropertyControlSource = 0x04;

// DPD available trigger methods (ISO 11783-10 B.4): the measurement commands the TC may use.
inline constexpr std::uint8_t kTriggerTimeInterval = 0x01;
inline constexpr std::uint8_t kTriggerDistanceInterval = 0x02;
inline constexpr std::uint8_t kTriggerThresholdLimits = 0x04;
inline constexpr std::uint8_t kTriggerOnChange = 0x08;
inline constexpr std::uint8_t kTriggerTotal = 0x10;

struct DeviceObject {
  std::uint16_t id = 0;
  std::string designator;
  std::string software_version;
  std::uint64_t working_set_master_name = 0;  // ISO 11783-5 NAME of the implement
  std::string serial_number;
  std::array<std::uint8_t, 7> structure_label{};     // changes whenever the pool's structure changes
  std::array<std::uint8_t, 7> localization_label{};  // ISO 11783-6 language command bytes 1-7
  std::vector<std::uint8_t> extended_structure_label;  // version 4 only; 0-32 bytes
};

struct DeviceElement {
  std::uint16_t id = 0;
  ElementType type = ElementType::kDevice;
  std::string designator;
  std::uint16_t element_number = 0;  // the element number process data messages address (12 bits)
  std::uint16_t parent_id = 0;       // the DVC for the device element, another DET otherwise
  std::vector<std::uint16_t> children;  // its DPD and DPT objects (child elements name it as parent)
};

struct DeviceProcessData {
  std::uint16_t id = 0;
  std::uint16_t ddi = 0;
  std::uint8_t properties = 0;
  std::uint8_t triggers = 0;
  std::string designator;
  std::uint16_t presentation_id = kNullObjectId;
};

struct DeviceProperty {
  std::uint16_t id = 0;
  std::uint16_t ddi = 0;
  std::int32_t value = 0;
  std::string designator;
  std::uint16_t presentation_id = kNullObjectId;
};

struct DeviceValuePresentation {
  std::uint16_t id = 0;
  std::int32_t offset = 0;
  float scale = 1.0f;  // shown value = (raw + offset) * scale
  std::uint8_t decimals = 0;
  std::string unit;
};

using DdopObject = std::variant<DeviceObject, DeviceElement, DeviceProcessData, DeviceProperty, DeviceValuePresentation>;

struct Ddop {
  std::vector<DdopObject> objects;
};

std::uint16_t object_id(const DdopObject& object);

// A structure or localisation label as 14 hex digits, for logs and the pool tree.
std::string label_hex(const std::array<std::uint8_t, 7>& label);

// Bytes of the pool as transferred with the "object pool transfer" message (ISO 11783-10 B.1), without
// the leading command byte, for a TC of `version` (3 or 4; below 4 the extended structure label is left
// out). Throws std::invalid_argument for a string longer than 255 bytes, more than 65535 children or an
// extended structure label longer than 32 bytes.
std::vector<std::uint8_t> write_ddop(const Ddop& pool, std::uint8_t version = kDdopVersion);

struct DdopParseResult {
  std::optional<Ddop> pool;  // set when the bytes are a valid pool
  std::string error;         // otherwise what is wrong, with the byte offset
};

// Parses and validates a pool written for a TC of `version`: known type tags, complete fields, unique
// object IDs below 0xFFFF, exactly one DVC and one device-type DET whose parent is the DVC, every DET's
// objects resolving to DPD or DPT objects, presentation references resolving to DVPs, DET parents
// resolving to the DVC or a DET, no element number twice, an extended structure label of at most 32 bytes.
DdopParseResult parse_ddop(std::span<const std::uint8_t> bytes, std::uint8_t version = kDdopVersion);

}  // namespace spread::isobus
