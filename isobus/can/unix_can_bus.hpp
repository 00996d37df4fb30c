#pragma once
// Joining a spread-canbus virtual bus: a Unix SOCK_SEQPACKET socket whose every datagram is one 16-byte
// `struct can_frame` (docs/can-integration.md). The returned port is used exactly like a CAN_RAW socket.
#include <string>

#include "isobus/can/can_frame_port.hpp"

namespace spread::isobus::can {

// The prefix that selects a spread-canbus socket where a CAN interface name is expected ("unix:PATH").
inline constexpr std::string_view kUnixBusPrefix = "unix:";

// Connects to the bus served at `path`. Throws std::runtime_error naming the path and the cause
// (no such socket, nobody serving it, path too long for sockaddr_un).
CanFramePort connect_unix_can_bus(const std::string& path);

// Opens what a command line names as a bus: "unix:PATH" joins a spread-canbus, anything else is a
// SocketCAN interface name (can0). Throws like the two functions it dispatches to.
CanFramePort open_can_bus(const std::string& spec);

// A short name for candump logs: the interface name, or "can0" for a virtual bus (candump readers
// expect an interface-like token, not a path).
std::string can_bus_log_name(const std::string& spec);

}  // namespace spread::isobus::can
