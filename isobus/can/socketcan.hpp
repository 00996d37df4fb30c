#pragma once
// The one place that touches AF_CAN: open a CAN_RAW socket bound to a network interface (can0).
// Everything else works on the returned CanFramePort and is tested over the virtual bus.
#include <string>

#include "isobus/can/can_frame_port.hpp"

namespace spread::isobus::can {

// Throws std::runtime_error naming the interface and the cause (no AF_CAN in the kernel, no such
// interface, permission).
CanFramePort open_socketcan(const std::string& interface_name);
// True when this kernel can create an AF_CAN socket at all (tests skip on false).
bool socketcan_available();

}  // namespace spread::isobus::can
