#include "isobus/frame_description.hpp"

#include <cstdio>

#include "isobus/ddi.hpp"
#include "isobus/isobus_id.hpp"
#include "isobus/process_data.hpp"
#include "isobus/speed_messages.hpp"

namespace spread::isobus {
namespace {

std::string printf_string(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

std::string command_name(std::uint8_t command) {
  switch (static_cast<ProcessDataCommand>(command)) {
    case ProcessDataCommand::kTechnicalCapabilities: return "technical capabilities";
    case ProcessDataCommand::kDeviceDescriptor: return "device descriptor";
    case ProcessDataCommand::kRequestValue: return "request value";
    case ProcessDataCommand::kValue: return "value";
    case ProcessDataCommand::kMeasurementTimeInterval: return "measurement time interval";
    case ProcessDataCommand::kMeasurementDistanceInterval: return "measurement distance interval";
    case ProcessDataCommand::kMeasurementMinimumThreshold: return "measurement minimum threshold";
    case ProcessDataCommand::kMeasurementMaximumThreshold: return "measurement maximum threshold";
    case ProcessDataCommand::kMeasurementChangeThreshold: return "measurement change threshold";
    case ProcessDataCommand::kPeerControlAssignment: return "peer control assignment";
    case ProcessDataCommand::kSetValueAndAcknowledge: return "set value and acknowledge";
    case ProcessDataCommand::kAcknowledge: return "acknowledge";
    case ProcessDataCommand::kTaskControllerStatus: return "task controller status";
    case ProcessDataCommand::kClientTask: return "client task";
  }
  return "reserved command " + std::to_string(command);
}

std::string pdack_errors(std::uint8_t bits) {
  if (bits == 0) return "ok";
  static const char* const names[8] = {"command not supported", "invalid element", "DDI not supported",
                                       "trigger not supported", "not settable", "invalid interval",
                                       "value not conform", "value out of range"};
  std::string out;
  for (int i = 0; i < 8; ++i) {
    if ((bits >> i) & 1u) {
      if (!out.empty()) out += ", ";
      out += names[i];
    }
  }
  return out;
}

}  // namespace

std::string ddi_name(std::uint16_t ddi) {
  switch (static_cast<Ddi>(ddi)) {
    case Ddi::kSetpointMassPerArea: return "set-point mass per area";
    case Ddi::kActualMassPerArea: return "actual mass per area";
    case Ddi::kSetpointWorkingWidth: return "set-point working width";
    case Ddi::kActualWorkingWidth: return "actual working width";
    case Ddi::kMaximumWorkingWidth: return "maximum working width";
    case Ddi::kActualWorkState: return "actual work state";
    case Ddi::kSetpointWorkState: return "set-point work state";
    case Ddi::kActualCondensedWorkState1_16: return "actual condensed work state 1-16";
    case Ddi::kSetpointCondensedWorkState1_16: return "set-point condensed work state 1-16";
    case Ddi::kSetpointRevolutions: return "set-point revolutions";
    case Ddi::kActualRevolutions: return "actual revolutions";
    case Ddi::kActualSpeed: return "actual speed";
    case Ddi::kSectionControlState: return "section control state";
    case Ddi::kSetpointBorderMode: return "set-point border spreading (proprietary)";
    case Ddi::kSetpointBorderGap: return "set-point border gap (proprietary)";
    case Ddi::kSetpointWindCompensation: return "set-point wind compensation (proprietary)";
    case Ddi::kSetpointWindAcross: return "measured wind across (proprietary)";
    case Ddi::kSetpointWindAlong: return "measured wind along (proprietary)";
    case Ddi::kSetpointProduct: return "set-point product (proprietary)";
    case Ddi::kProductNumber: return "product number (proprietary)";
  }
  return "unknown DDI";
}

std::string format_ddi_value(std::uint16_t ddi, std::int32_t raw) {
  switch (static_cast<Ddi>(ddi)) {
    case Ddi::kSetpointMassPerArea:
    case Ddi::kActualMassPerArea:
      return std::to_string(raw) + " mg/m2 (" + printf_string("%.2f", raw / 100.0) + " kg/ha)";
    case Ddi::kSetpointWorkingWidth:
    case Ddi::kActualWorkingWidth:
    case Ddi::kMaximumWorkingWidth: return std::to_string(raw) + " mm";
    case Ddi::kActualWorkState:
    case Ddi::kSetpointWorkState: return raw == 1 ? "on" : raw == 0 ? "off" : std::to_string(raw);
    case Ddi::kActualCondensedWorkState1_16:
    case Ddi::kSetpointCondensedWorkState1_16: {
      // One character per section: 1 on, 0 off, E error, - not installed (section 1 first).
      std::string out = "sections ";
      const auto v = static_cast<std::uint32_t>(raw);
      for (int i = 0; i < 16; ++i) out += "01E-"[(v >> (2 * i)) & 3u];
      return out;
    }
    case Ddi::kSetpointRevolutions:
    case Ddi::kActualRevolutions: return printf_string("%.4f r/min", raw / kRevolutionsScale);
    case Ddi::kActualSpeed: return std::to_string(raw) + " mm/s";
    case Ddi::kSectionControlState: return raw == 1 ? "automatic" : raw == 0 ? "manual" : std::to_string(raw);
    case Ddi::kSetpointBorderMode: {
      static constexpr const char* kModes[] = {"off", "left border", "right border", "left field edge",
                                               "right field edge"};
      return raw >= 0 && raw <= 4 ? kModes[raw] : std::to_string(raw);
    }
    case Ddi::kSetpointBorderGap: return std::to_string(raw) + " mm";
    case Ddi::kSetpointWindCompensation: return raw == 1 ? "on" : raw == 0 ? "off" : std::to_string(raw);
    case Ddi::kSetpointWindAcross:
    case Ddi::kSetpointWindAlong: return std::to_string(raw) + " mm/s";
    case Ddi::kSetpointProduct:
    case Ddi::kProductNumber: return raw == 0 ? "none" : "product " + std::to_string(raw);
  }
  return std::to_string(raw);
}

std::string describe_frame(const can_frame& frame) {
  char head[48];
  if ((frame.can_id & CAN_ERR_FLAG) != 0) return "error frame";
  if ((frame.can_id & CAN_EFF_FLAG) == 0) {
    std::snprintf(head, sizeof(head), "standard frame 0x%03X (not ISOBUS)", frame.can_id & CAN_SFF_MASK);
    return head;
  }
  const IsobusId id = decode_id(frame.can_id & CAN_EFF_MASK);
  std::snprintf(head, sizeof(head), "0x%02X->0x%02X ", id.source, id.destination);
  std::string out(head);
  std::array<std::uint8_t, 8> bytes{};
  for (std::size_t i = 0; i < 8 && i < frame.len; ++i) bytes[i] = frame.data[i];
  if (id.pgn == kProcessDataPgn && frame.len == 8) {
    const ProcessData m = decode_process_data(bytes);
    if (auto ack = decode_pdack(bytes)) {
      return out + "PD acknowledge of " + command_name(ack->acknowledged_command) + " element " +
             std::to_string(ack->element) + " DDI " + std::to_string(ack->ddi) + " (" + ddi_name(ack->ddi) +
             "): " + pdack_errors(ack->error_bits);
    }
    out += "PD " + command_name(m.command) + " element " + std::to_string(m.element) + " DDI " +
           std::to_string(m.ddi) + " " + ddi_name(m.ddi);
    if (m.command != static_cast<std::uint8_t>(ProcessDataCommand::kRequestValue)) {
      out += " = " + format_ddi_value(m.ddi, m.value);
    }
    return out;
  }
  if ((id.pgn == kWheelBasedSpeedPgn || id.pgn == kGroundBasedSpeedPgn) && frame.len == 8) {
    out += id.pgn == kWheelBasedSpeedPgn ? "wheel-based speed " : "ground-based speed ";
    const auto speed = decode_speed(bytes);
    return out + (speed ? printf_string("%.3f m/s", speed->speed_m_s) : std::string("not available"));
  }
  if (id.pgn == 0xEE00) return out + "address claimed";
  if (id.pgn == 0xEA00) return out + "request";
  std::snprintf(head, sizeof(head), "PGN 0x%05X, %u bytes", id.pgn, static_cast<unsigned>(frame.len));
  return out + head;
}

}  // namespace spread::isobus
