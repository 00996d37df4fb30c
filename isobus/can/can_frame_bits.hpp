#pragma once
// A classical CAN frame as the bus carries it (CAN 2.0 Part B §3.2.1 data frame, §3.2.2 remote frame,
// §6 bit-stream coding; ISO 11898-1 frame format and coding): how many bit times it holds the bus, and
// where it stands in arbitration. spread-canbus paces and orders frames with these.
#include <linux/can.h>

#include <cstdint>

namespace spread::isobus::can {

// Bit times of a data or remote frame on the bus, from its start-of-frame to the end of the 3-bit
// intermission that must follow it before the next frame may start: SOF, arbitration field, control
// field, data field and CRC sequence with their stuff bits (a complementary bit after every 5 equal bits,
// counted on this frame's actual bits: identifier, DLC, data and its CRC-15), then the fixed-form CRC
// delimiter, ACK slot and delimiter, 7-bit EOF and the intermission, which are not stuffed.
// An extended data frame of n bytes is 67 + 8n bits unstuffed (131 for 8 bytes) and at most
// 67 + 8n + floor((54 + 8n - 1) / 4) with the worst stuffing (160 for 8 bytes).
int can_frame_bit_count(const can_frame& frame);

// The same count without stuff bits, and with the worst-case number of them, for the frame's format and
// length (the bounds can_frame_bit_count lies between).
int can_frame_bit_count_unstuffed(const can_frame& frame);
int can_frame_bit_count_worst_case(const can_frame& frame);

// Bitwise arbitration (CAN 2.0 Part B §3.2.1 arbitration field; ISO 11898-1 bus arbitration): nodes
// send the arbitration field together and a dominant 0 overwrites a recessive 1, so the frame whose
// field has the first 0 where the others have 1 wins. The key orders frames as the bus does: a lower
// key wins. Extended field: 11-bit base identifier, SRR (1), IDE (1), 18-bit extension, RTR; standard
// field: 11-bit identifier, RTR, IDE (0). Between two extended frames the lower 29-bit identifier wins;
// a standard frame beats an extended one with the same base identifier; a data frame beats a remote frame
// with the same identifier.
std::uint32_t can_arbitration_key(const can_frame& frame);

}  // namespace spread::isobus::can
