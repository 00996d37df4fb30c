#pragma once
// A two-node virtual CAN bus: socketpair(AF_UNIX, SOCK_SEQPACKET) carrying struct can_frame records,
// for machines without AF_CAN/vcan (docs/design.md §6). What one end sends, the other end reads.
#include <utility>

#include "isobus/can/can_frame_port.hpp"

namespace spread::isobus::can {

// Throws std::runtime_error when the socket pair cannot be created.
std::pair<CanFramePort, CanFramePort> make_virtual_can_pair();

}  // namespace spread::isobus::can
