#pragma once
// ISO 11783 / SAE J1939 29-bit identifier:
//   bits 28-26 priority | 25 EDP | 24 DP | 23-16 PF | 15-8 PS | 7-0 source address
// PF < 240 (PDU1): PS is the destination address and not part of the PGN.
// PF >= 240 (PDU2): PS is the group extension, part of the PGN; the message is broadcast.
#include <cstdint>

namespace spread::isobus {

inline constexpr std::uint8_t kGlobalAddress = 0xFF;
inline constexpr std::uint8_t kNullAddress = 0xFE;

struct IsobusId {
  std::uint8_t priority = 6;        // 0 (highest) .. 7
  std::uint32_t pgn = 0;            // parameter group number, 18 bits
  std::uint8_t destination = kGlobalAddress;  // PDU1 only; kGlobalAddress for PDU2
  std::uint8_t source = kNullAddress;
};

bool is_pdu1(std::uint32_t pgn);
// 29-bit identifier without the CAN_EFF_FLAG.
std::uint32_t encode_id(const IsobusId& id);
IsobusId decode_id(std::uint32_t id29);

}  // namespace spread::isobus
