#pragma once
// ISO 11783-10 process data message, PGN 0xCB00, always 8 bytes:
//   byte 0: command (bits 0-3) | element number bits 0-3 (bits 4-7)
//   byte 1: element number bits 4-11
//   bytes 2-3: DDI, little endian
//   bytes 4-7: value, int32 little endian
// The process data acknowledge (command 0xD) reuses bytes 0-3 and carries the error bits in byte 4
// and the acknowledged command in the low nibble of byte 5 (bytes 6-7 = 0xFF).
#include <array>
#include <cstdint>
#include <optional>

namespace spread::isobus {

inline constexpr std::uint32_t kProcessDataPgn = 0xCB00;
inline constexpr std::uint8_t kProcessDataPriority = 3;

enum class ProcessDataCommand : std::uint8_t {
  kTechnicalCapabilities = 0x0,
  kDeviceDescriptor = 0x1,
  kRequestValue = 0x2,
  kValue = 0x3,  // set-value from the task controller, value answer from the client
  kMeasurementTimeInterval = 0x4,
  kMeasurementDistanceInterval = 0x5,
  kMeasurementMinimumThreshold = 0x6,
  kMeasurementMaximumThreshold = 0x7,
  kMeasurementChangeThreshold = 0x8,
  kPeerControlAssignment = 0x9,
  kSetValueAndAcknowledge = 0xA,
  kAcknowledge = 0xD,  // PDACK
  kTaskControllerStatus = 0xE,
  kClientTask = 0xF,
};

// PDACK error bits (byte 4).
enum PdackError : std::uint8_t {
  kPdackNoError = 0x00,
  kPdackCommandNotSupported = 0x01,
  kPdackInvalidElement = 0x02,
  kPdackDdiNotSupported = 0x04,
  kPdackTriggerNotSupported = 0x08,
  kPdackNotSettable = 0x10,
  kPdackInvalidInterval = 0x20,
  kPdackValueNotConform = 0x40,
  kPdackValueOutOfRange = 0x80,
};

struct ProcessData {
  std::uint8_t command = 0;      // 0..15 (a ProcessDataCommand value)
  std::uint16_t element = 0;     // 0..4095
  std::uint16_t ddi = 0;
  std::int32_t value = 0;
};

using ProcessDataBytes = std::array<std::uint8_t, 8>;

ProcessDataBytes encode_process_data(const ProcessData& message);
ProcessData decode_process_data(const ProcessDataBytes& bytes);
// PDACK answering `request`: same element and DDI, error bits, acknowledged command.
ProcessDataBytes encode_pdack(const ProcessData& request, std::uint8_t error_bits);

struct Pdack {
  std::uint16_t element = 0;
  std::uint16_t ddi = 0;
  std::uint8_t error_bits = 0;
  std::uint8_t acknowledged_command = 0;
};
std::optional<Pdack> decode_pdack(const ProcessDataBytes& bytes);  // nullopt when not command 0xD

}  // namespace spread::isobus
