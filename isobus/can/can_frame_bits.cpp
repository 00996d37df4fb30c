#include "isobus/can/can_frame_bits.hpp"

#include <vector>

namespace spread::isobus::can {
namespace {

bool is_extended(const can_frame& f) { return (f.can_id & CAN_EFF_FLAG) != 0; }
bool is_remote(const can_frame& f) { return (f.can_id & CAN_RTR_FLAG) != 0; }
// A classical frame carries at most 8 bytes; a DLC above 8 still means 8 (CAN 2.0 Part B §3.2.1).
int data_bytes(const can_frame& f) { return is_remote(f) ? 0 : (f.len > 8 ? 8 : f.len); }

// CRC delimiter 1, ACK slot 1, ACK delimiter 1, EOF 7, intermission 3: fixed form, never stuffed.
constexpr int kUnstuffedTail = 13;

void push_bits(std::vector<bool>& bits, std::uint32_t value, int count) {
  for (int i = count - 1; i >= 0; --i) bits.push_back(((value >> i) & 1U) != 0);
}

// SOF through the data field, as transmitted (most significant bit first), before stuffing.
std::vector<bool> header_and_data(const can_frame& f) {
  std::vector<bool> bits;
  bits.reserve(19 + 8 * 8 + 20);
  bits.push_back(false);  // SOF, dominant
  const bool remote = is_remote(f);
  if (is_extended(f)) {
    const std::uint32_t id = f.can_id & CAN_EFF_MASK;
    push_bits(bits, id >> 18, 11);
    bits.push_back(true);  // SRR, recessive
    bits.push_back(true);  // IDE, recessive: extended format
    push_bits(bits, id & 0x3FFFFU, 18);
    bits.push_back(remote);
    bits.push_back(false);  // r1
    bits.push_back(false);  // r0
  } else {
    push_bits(bits, f.can_id & CAN_SFF_MASK, 11);
    bits.push_back(remote);
    bits.push_back(false);  // IDE, dominant: standard format
    bits.push_back(false);  // r0
  }
  push_bits(bits, f.len > 15 ? 15U : f.len, 4);  // the DLC as sent
  for (int i = 0; i < data_bytes(f); ++i) push_bits(bits, f.data[i], 8);
  return bits;
}

// CRC-15 of CAN (generator x^15 + x^14 + x^10 + x^8 + x^7 + x^4 + x^3 + 1 = 0x4599) over the unstuffed
// bits from SOF to the end of the data field.
std::uint32_t crc15(const std::vector<bool>& bits) {
  std::uint32_t crc = 0;
  for (const bool bit : bits) {
    const bool next = bit != (((crc >> 14) & 1U) != 0);
    crc = (crc << 1) & 0x7FFFU;
    if (next) crc ^= 0x4599U;
  }
  return crc;
}

}  // namespace

int can_frame_bit_count(const can_frame& frame) {
  std::vector<bool> bits = header_and_data(frame);
  push_bits(bits, crc15(bits), 15);
  // After five equal bits the transmitter inserts a complementary one, which starts the next run.
  int stuffed = 0;
  int run = 0;
  bool last = true;
  for (const bool bit : bits) {
    run = (run > 0 && bit == last) ? run + 1 : 1;
    last = bit;
    if (run == 5) {
      ++stuffed;
      last = !bit;
      run = 1;
    }
  }
  return static_cast<int>(bits.size()) + stuffed + kUnstuffedTail;
}

int can_frame_bit_count_unstuffed(const can_frame& frame) {
  const int header = is_extended(frame) ? 39 : 19;  // SOF + arbitration + control fields
  return header + 8 * data_bytes(frame) + 15 + kUnstuffedTail;
}

int can_frame_bit_count_worst_case(const can_frame& frame) {
  // The stuffed span (SOF to CRC) of g bits holds at most floor((g - 1) / 4) stuff bits: the first run
  // needs 5 bits, every later one 4 more (the stuff bit itself opens the next run).
  const int stuffed_span = can_frame_bit_count_unstuffed(frame) - kUnstuffedTail;
  return can_frame_bit_count_unstuffed(frame) + (stuffed_span - 1) / 4;
}

std::uint32_t can_arbitration_key(const can_frame& frame) {
  const std::uint32_t rtr = is_remote(frame) ? 1U : 0U;
  if (is_extended(frame)) {
    const std::uint32_t id = frame.can_id & CAN_EFF_MASK;
    return ((id >> 18) << 21) | (1U << 20) | (1U << 19) | ((id & 0x3FFFFU) << 1) | rtr;
  }
  // Decided by bit 19 (IDE) at the latest against an extended frame of the same base identifier.
  return ((frame.can_id & CAN_SFF_MASK) << 21) | (rtr << 20);
}

}  // namespace spread::isobus::can
